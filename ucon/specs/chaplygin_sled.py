"""Chaplygin sled: a body sliding flat on the ground on a blade behind its centre of mass.

The sled's principal axes at its centre of mass G: body x along the blade, body y vertical,
body z horizontal across the blade. That is theta = pi/2 (body z horizontal) and phi = 0 (body
y vertical, e_y2 = e_Z); the blade's direction is then the line of nodes e_x1 = (cos(psi),
sin(psi), 0) and psi is the heading (docs/design.md section 3). The blade touches the ground at
P = G - a e_x1, a distance a behind G along the blade. P has no velocity across the blade,
n = e_Z x e_x1 = (-sin(psi), cos(psi), 0); with the sled flat, omega = psidot e_Z and
v_P = v_G - a psidot n::

    F1 = -Xdot sin(psi) + Ydot cos(psi) - a psidot     (nonholonomic: no sideways skid)

and three position components keep the body flat on the ground at its height h::

    F2 = Z - h            F3 = cos(theta)            F4 = phi

(F3 and F4 vanish at theta = pi/2, phi = 0, with gradients -1 and 1 there.) With a = 0, F1 is
the knife edge's constraint (knife_edge.py). Four UCON statements share the routine and PAR(11)
picks the component.

Textbook result (a test's target): the energy E is conserved; the speed u of G along the blade
obeys du/dt = a psidot^2, so u = U tanh(k U t + atanh(u0/U)) with U = sqrt(2E/m) and
k = m a / (J + m a^2) (J the moment about the vertical at G): the turning rate decays to zero
and the sled settles on a straight line at the speed sqrt(2E/m) (docs/models.md).
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

z, psi, theta, phi = sympy.symbols("z psi theta phi", real=True)
xdot, ydot, psidot = sympy.symbols("xdot ydot psidot", real=True)
blade_offset = sympy.Symbol("blade_offset", real=True)
height = sympy.Symbol("height", real=True)

across = sympy.Matrix([-sin(psi), cos(psi), 0])
velocity_of_contact = sympy.Matrix([xdot, ydot, 0]) - blade_offset * psidot * across

SPEC = ConstraintSpec(
    name="chaplygin_sled",
    title="Chaplygin sled",
    summary="No velocity across the blade at its contact point, a distance a behind the centre "
    "of mass; the body kept flat at its height.",
    variables=(
        Variable(z, 13),
        Variable(psi, 14),
        Variable(theta, 15),
        Variable(phi, 16),
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(psidot, 24),
    ),
    parameters=(
        Parameter(blade_offset, 9, "distance a from the blade's contact to the centre of mass",
                  "m"),
        Parameter(height, 10, "height h of the centre of mass", "m"),
    ),
    constraints=(
        Constraint(sympy.expand(across.dot(velocity_of_contact)),
                   "velocity of the blade's contact point across the blade [m/s]"),
        Constraint(z - height, "height of the centre of mass above h [m]"),
        Constraint(cos(theta), "cosine of the tilt theta (zero: body z horizontal) [1]"),
        Constraint(phi, "roll angle phi (zero: body y vertical) [rad]"),
    ),
    component_meaning="sled component",
)
