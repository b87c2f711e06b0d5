"""Knife edge: a blade on the ground plane cannot move sideways.

The blade lies in the body x-y plane. Its horizontal direction is the line of nodes
e_x1 = (cos(psi), sin(psi), 0) (docs/design.md §3), the only horizontal direction in that
plane, whatever the tilt theta. As in the textbook knife edge (a skate or a sledge runner
touching the ground below the centre of mass), the contact point moves with the centre of
mass, and its velocity across the blade, along e_Z x e_x1 = (-sin(psi), cos(psi), 0), is zero::

    F = -Xdot sin(psi) + Ydot cos(psi)

One nonholonomic constraint, no physical parameter: PAR holds the part id and the codes.
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Variable

xdot, ydot = sympy.symbols("xdot ydot", real=True)
psi = sympy.Symbol("psi", real=True)

across = sympy.Matrix([-sin(psi), cos(psi), 0])
velocity = sympy.Matrix([xdot, ydot, 0])

SPEC = ConstraintSpec(
    name="knife_edge",
    title="knife edge",
    summary="The blade's contact point has no velocity across the blade.",
    variables=(Variable(xdot, 21), Variable(ydot, 22), Variable(psi, 14)),
    parameters=(),
    constraints=(Constraint(across.dot(velocity),
                            "velocity of the contact point across the blade [m/s]"),),
)
