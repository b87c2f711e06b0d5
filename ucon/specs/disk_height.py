"""Disk height: the holonomic form of the rolling disk's third no-slip component.

The lowest point of the disk's mid-plane circle (radius R) stays on the ground plane Z = 0.
That point is G - R e_y2 with e_y2 = (-cos(theta) sin(psi), cos(theta) cos(psi), sin(theta))
(docs/design.md §5), so its height is Z - R sin(theta)::

    F = Z - R sin(theta)

Displacement codes only: a position constraint, whose time derivative is the rolling disk's
F3 = Zdot - R thetadot cos(theta). A scene may use it in place of F3 (docs/design.md §5).
"""

import sympy

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

z, theta = sympy.symbols("z theta", real=True)
radius = sympy.Symbol("radius", positive=True)

SPEC = ConstraintSpec(
    name="disk_height",
    title="disk height",
    summary="The lowest point of the disk's rim stays on the ground plane.",
    variables=(Variable(z, 13), Variable(theta, 15)),
    parameters=(Parameter(radius, 4, "disk radius R", "m", check="positive"),),
    constraints=(Constraint(z - radius * sympy.sin(theta),
                            "height of the rim's lowest point above the ground [m]"),),
)
