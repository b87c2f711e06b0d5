"""Rolling disk: no slip and no penetration at the contact point (docs/design.md §5).

The disk's mid-plane circle of radius R touches the ground plane Z = 0 at C. The velocity of
the disk's material point at C is zero::

    v_G + omega x r_GC = 0,   r_GC = -R e_y2,   e_y2 = (-cos(theta) sin(psi),
                                                        cos(theta) cos(psi), sin(theta))

with omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md §3). Expanded::

    F1 = Xdot + R cos(psi) (phidot + psidot cos(theta)) - R thetadot sin(psi) sin(theta)
    F2 = Ydot + R sin(psi) (phidot + psidot cos(theta)) + R thetadot cos(psi) sin(theta)
    F3 = Zdot - R thetadot cos(theta)

Three UCON statements share the routine and PAR(11) picks the component, as in the paper.
Non-zero entries: 3 values + 15 first partials + 31 second partials = 49; no time derivative.
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

xdot, ydot, zdot = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psidot, thetadot, phidot = sympy.symbols("psidot thetadot phidot", real=True)
radius = sympy.Symbol("radius", positive=True)

# Unit vectors in ground components (docs/design.md §3): the line of nodes e_x1, the disk
# axis e_z2, and e_y2, pointing from the contact point towards the centre.
e_Z = sympy.Matrix([0, 0, 1])
e_x1 = sympy.Matrix([cos(psi), sin(psi), 0])
e_z2 = sympy.Matrix([sin(theta) * sin(psi), -sin(theta) * cos(psi), cos(theta)])
e_y2 = sympy.Matrix([-cos(theta) * sin(psi), cos(theta) * cos(psi), sin(theta)])

omega = psidot * e_Z + thetadot * e_x1 + phidot * e_z2
velocity_of_contact = sympy.Matrix([xdot, ydot, zdot]) + omega.cross(-radius * e_y2)

SPEC = ConstraintSpec(
    name="rolling_disk",
    title="rolling disk",
    summary="No slip, no penetration: the disk's material point at the contact has zero "
    "velocity.",
    variables=(
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(zdot, 23),
        Variable(psi, 14),
        Variable(theta, 15),
        Variable(psidot, 24),
        Variable(thetadot, 25),
        Variable(phidot, 26),
    ),
    parameters=(Parameter(radius, 10, "disk radius R", "m", check="positive"),),
    constraints=tuple(
        Constraint(sympy.expand(velocity_of_contact[i]),
                   f"{axis} velocity of the disk's material point at the contact [m/s]")
        for i, axis in enumerate("XYZ")
    ),
    component_meaning="no-slip component",
)
