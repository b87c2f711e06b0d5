"""Disk on a turntable: the rolling disk on a horizontal table turning at a rippling rate.

The table is the plane Z = 0 turning about the vertical axis through (a, b, 0) at the rate

    Omega(t) = Omega0 + Omega1 sin(nu t)

(a drive of mean rate Omega0 with a rate ripple of amplitude Omega1 and angular frequency nu,
the "wow" of a record player). The table's material point at r moves with velocity
Omega(t) e_Z x (r - c), c = (a, b, 0). No slip at the contact point C: the disk's material
point at C moves with the table's::

    v_G + omega x r_GC - Omega(t) e_Z x (r_C - c) = 0,   r_GC = -R e_y2,   r_C = r_G + r_GC

with omega and e_y2 as for the rolling disk (docs/design.md §3 and §5). The table's velocity
at C needs the centre's X and Y, so they are declared too (codes 11 12). Expanded::

    F1 = F1(rolling disk) + Omega(t) (Y - R cos(theta) cos(psi) - b)
    F2 = F2(rolling disk) - Omega(t) (X + R cos(theta) sin(psi) - a)
    F3 = Zdot - R thetadot cos(theta)

Time appears explicitly through Omega(t), multiplied by the variables: dF/dt,
d2F/dt dq (for X, Y, psi, theta) and d2F/dt2 are non-zero for F1 and F2 when Omega1 nu is,
and so is f(t), the part free of the variables: -b Omega(t) in F1, a Omega(t) in F2.
"""

import sympy
from sympy import cos, sin

from ucon.spec import TIME, Constraint, ConstraintSpec, Parameter, Variable

x, y = sympy.symbols("x y", real=True)
xdot, ydot, zdot = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psidot, thetadot, phidot = sympy.symbols("psidot thetadot phidot", real=True)
radius = sympy.Symbol("radius", positive=True)
centre_x, centre_y = sympy.symbols("centre_x centre_y", real=True)
rate_mean, rate_ripple, ripple_frequency = sympy.symbols(
    "rate_mean rate_ripple ripple_frequency", real=True)

e_Z = sympy.Matrix([0, 0, 1])
e_x1 = sympy.Matrix([cos(psi), sin(psi), 0])
e_z2 = sympy.Matrix([sin(theta) * sin(psi), -sin(theta) * cos(psi), cos(theta)])
e_y2 = sympy.Matrix([-cos(theta) * sin(psi), cos(theta) * cos(psi), sin(theta)])

omega = psidot * e_Z + thetadot * e_x1 + phidot * e_z2
r_gc = -radius * e_y2
# Only the horizontal part of r_C - c matters in e_Z x (r_C - c); Z is not needed.
r_c_from_centre = sympy.Matrix([x - centre_x, y - centre_y, 0]) + r_gc
table_rate = rate_mean + rate_ripple * sin(ripple_frequency * TIME)
slip = (sympy.Matrix([xdot, ydot, zdot]) + omega.cross(r_gc)
        - table_rate * e_Z.cross(r_c_from_centre))

SPEC = ConstraintSpec(
    name="turntable_disk",
    title="disk on a turntable",
    summary="No slip on a table turning about a vertical axis at the rate Omega0 + Omega1 "
    "sin(nu t): the disk's material point at the contact moves with the table's.",
    variables=(
        Variable(x, 11),
        Variable(y, 12),
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(zdot, 23),
        Variable(psi, 14),
        Variable(theta, 15),
        Variable(psidot, 24),
        Variable(thetadot, 25),
        Variable(phidot, 26),
    ),
    parameters=(
        Parameter(radius, 12, "disk radius R", "m", check="positive"),
        Parameter(centre_x, 13, "X of the table's axis a", "m"),
        Parameter(centre_y, 14, "Y of the table's axis b", "m"),
        Parameter(rate_mean, 15, "mean table rate Omega0", "rad/s"),
        Parameter(rate_ripple, 16, "table rate ripple amplitude Omega1", "rad/s"),
        Parameter(ripple_frequency, 17, "ripple angular frequency nu", "rad/s"),
    ),
    constraints=tuple(
        Constraint(sympy.expand(slip[i]),
                   f"{axis} slip velocity of the disk on the table at the contact [m/s]")
        for i, axis in enumerate("XYZ")
    ),
    component_meaning="no-slip component",
)
