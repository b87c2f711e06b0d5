"""Planar hold: a body kept level at a height, its principal axes x and z horizontal.

Three position constraints on a part's centre of mass height Z and its 3-1-3 Euler angles
(docs/design.md section 3): body z horizontal (theta = pi/2), body y vertical (phi = 0, so that
e_y2 = e_Z) and the centre of mass at the height h::

    F1 = Z - h            F2 = cos(theta)            F3 = phi

F2 and F3 vanish at theta = pi/2, phi = 0 with gradients -1 and 1 there. What is left is
planar motion: X, Y and the heading psi (the direction of body x, the line of nodes). The
Chaplygin sled (chaplygin_sled.py) uses it to lie flat on the ground. Displacement codes only:
three position UCONs; PAR(7) picks the component.
"""

import sympy

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

z, theta, phi = sympy.symbols("z theta phi", real=True)
height = sympy.Symbol("height", real=True)

SPEC = ConstraintSpec(
    name="planar_hold",
    title="planar hold",
    summary="The body stays level: centre of mass at the height h, body y vertical.",
    variables=(Variable(z, 13), Variable(theta, 15), Variable(phi, 16)),
    parameters=(Parameter(height, 5, "height h of the centre of mass", "m"),),
    constraints=(
        Constraint(z - height, "height of the centre of mass above h [m]"),
        Constraint(sympy.cos(theta), "cosine of the tilt theta (zero: body z horizontal) [1]"),
        Constraint(phi, "roll angle phi (zero: body y vertical) [rad]"),
    ),
    component_meaning="hold component",
)
