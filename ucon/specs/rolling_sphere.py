"""Rolling sphere: no slip and no penetration of a sphere of radius R on the ground plane.

The contact point is C = G - R e_Z. The sphere's material point at C has zero velocity::

    v_G + omega x (-R e_Z) = 0

with omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md §3), in ground components
(thetadot cos(psi) + phidot sin(theta) sin(psi), thetadot sin(psi) - phidot sin(theta) cos(psi),
psidot + phidot cos(theta)). Expanded::

    F1 = Xdot + R (phidot sin(theta) cos(psi) - thetadot sin(psi))
    F2 = Ydot + R (phidot sin(theta) sin(psi) + thetadot cos(psi))
    F3 = Zdot

The spin about the vertical (the Z component of omega) does not move the contact point, so
psidot does not appear and is not declared. F3 is the velocity form of Z = R; three UCON
statements share the routine and PAR(10) picks the component.
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

xdot, ydot, zdot = sympy.symbols("xdot ydot zdot", real=True)
psi, theta = sympy.symbols("psi theta", real=True)
psidot, thetadot, phidot = sympy.symbols("psidot thetadot phidot", real=True)
radius = sympy.Symbol("radius", positive=True)

e_Z = sympy.Matrix([0, 0, 1])
e_x1 = sympy.Matrix([cos(psi), sin(psi), 0])
e_z2 = sympy.Matrix([sin(theta) * sin(psi), -sin(theta) * cos(psi), cos(theta)])

omega = psidot * e_Z + thetadot * e_x1 + phidot * e_z2
velocity_of_contact = sympy.Matrix([xdot, ydot, zdot]) + omega.cross(-radius * e_Z)

SPEC = ConstraintSpec(
    name="rolling_sphere",
    title="rolling sphere",
    summary="No slip, no penetration: the sphere's material point at the contact has zero "
    "velocity.",
    variables=(
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(zdot, 23),
        Variable(psi, 14),
        Variable(theta, 15),
        Variable(thetadot, 25),
        Variable(phidot, 26),
    ),
    parameters=(Parameter(radius, 9, "sphere radius R", "m", check="positive"),),
    constraints=tuple(
        Constraint(sympy.expand(velocity_of_contact[i]),
                   f"{axis} velocity of the sphere's material point at the contact [m/s]")
        for i, axis in enumerate("XYZ")
    ),
    component_meaning="no-slip component",
)
