"""Ball on a turntable: a sphere rolling without slip on a horizontal table turning at a rate.

The table is the plane Z = 0 turning at the constant rate Omega about the vertical axis through
c = (a, b, 0). The sphere (radius r, centre G) touches it at C = G - r e_Z. The table's
material point at C moves with velocity Omega e_Z x (r_C - c); no slip: the sphere's material
point at C moves with it::

    v_G + omega x (-r e_Z) - Omega e_Z x (r_C - c) = 0

with omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md section 3). Only the
horizontal part of r_C - c enters, and it is that of G: (X - a, Y - b). Expanded::

    F1 = Xdot + r (phidot sin(theta) cos(psi) - thetadot sin(psi)) + Omega (Y - b)
    F2 = Ydot + r (phidot sin(theta) sin(psi) + thetadot cos(psi)) - Omega (X - a)
    F3 = Zdot

The axis is fixed and the rate constant, so time does not appear: every component is
time-free (a moving axis or a varying rate would bring TIME in, as in turntable_disk.py). As
for the rolling sphere, the spin about the vertical does not move the contact point, so psidot
is not declared. F3 is the velocity form of Z = r. Three UCON statements share the routine and
PAR(15) picks the component.

Textbook result (a test's target): the centre of a uniform sphere (I = 2 m r^2 / 5) circles at
the rate Omega I / (I + m r^2) = (2/7) Omega, whatever the start (docs/models.md).
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

x, y = sympy.symbols("x y", real=True)
xdot, ydot, zdot = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psidot, thetadot, phidot = sympy.symbols("psidot thetadot phidot", real=True)
radius = sympy.Symbol("radius", positive=True)
table_rate = sympy.Symbol("table_rate", real=True)
centre_x, centre_y = sympy.symbols("centre_x centre_y", real=True)

e_Z = sympy.Matrix([0, 0, 1])
e_x1 = sympy.Matrix([cos(psi), sin(psi), 0])
e_z2 = sympy.Matrix([sin(theta) * sin(psi), -sin(theta) * cos(psi), cos(theta)])

omega = psidot * e_Z + thetadot * e_x1 + phidot * e_z2
contact_from_axis = sympy.Matrix([x - centre_x, y - centre_y, 0])
slip = (sympy.Matrix([xdot, ydot, zdot]) + omega.cross(-radius * e_Z)
        - table_rate * e_Z.cross(contact_from_axis))

SPEC = ConstraintSpec(
    name="turntable_ball",
    title="ball on a turntable",
    summary="No slip on a table turning at a constant rate Omega about a fixed vertical axis: "
    "the sphere's material point at the contact moves with the table's.",
    variables=(
        Variable(x, 11),
        Variable(y, 12),
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(zdot, 23),
        Variable(psi, 14),
        Variable(theta, 15),
        Variable(thetadot, 25),
        Variable(phidot, 26),
    ),
    parameters=(
        Parameter(radius, 11, "sphere radius r", "m", check="positive"),
        Parameter(table_rate, 12, "table rate Omega", "rad/s"),
        Parameter(centre_x, 13, "X of the table's axis a", "m"),
        Parameter(centre_y, 14, "Y of the table's axis b", "m"),
    ),
    constraints=tuple(
        Constraint(sympy.expand(slip[i]),
                   f"{axis} slip velocity of the sphere on the table at the contact [m/s]")
        for i, axis in enumerate("XYZ")
    ),
    component_meaning="no-slip component",
)
