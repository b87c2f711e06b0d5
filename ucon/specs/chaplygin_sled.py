"""Chaplygin sled: a body sliding on the ground on a blade behind its centre of mass.

The sled's principal axes at its centre of mass G: body x along the blade, body y vertical,
body z horizontal across the blade. That is theta = pi/2 (body z horizontal) and phi = 0 (body
y vertical), which the holonomic spec planar_hold.py keeps; the blade's direction is then the
line of nodes e_x1 = (cos(psi), sin(psi), 0) and psi is the heading (docs/design.md section 3).
The blade touches the ground at P = G - a e_x1, a distance a behind G along the blade. P has no
velocity across the blade, n = e_Z x e_x1 = (-sin(psi), cos(psi), 0); with the sled flat,
omega = psidot e_Z and v_P = v_G - a psidot n::

    F = -Xdot sin(psi) + Ydot cos(psi) - a psidot

With a = 0 this is the knife edge (knife_edge.py). One nonholonomic constraint: PAR holds the
part id, the codes and a. (A velocity UCON and the position UCONs that keep the body flat need
two routines: the driver treats a UCON as a position constraint when its routine declares no
velocity code.)

Textbook result (a test's target): the energy E is conserved; the speed u of G along the blade
obeys du/dt = a psidot^2, so u = U tanh(k U t + atanh(u0/U)) with U = sqrt(2E/m) and
k = m a / (J + m a^2) (J the moment about the vertical at G): the turning rate decays to zero
and the sled settles on a straight line at the speed sqrt(2E/m) (docs/models.md).
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

psi = sympy.Symbol("psi", real=True)
xdot, ydot, psidot = sympy.symbols("xdot ydot psidot", real=True)
blade_offset = sympy.Symbol("blade_offset", real=True)

across = sympy.Matrix([-sin(psi), cos(psi), 0])
velocity_of_contact = sympy.Matrix([xdot, ydot, 0]) - blade_offset * psidot * across

SPEC = ConstraintSpec(
    name="chaplygin_sled",
    title="Chaplygin sled",
    summary="No velocity across the blade at its contact point, a distance a behind the centre "
    "of mass.",
    variables=(
        Variable(xdot, 21),
        Variable(ydot, 22),
        Variable(psi, 14),
        Variable(psidot, 24),
    ),
    parameters=(
        Parameter(blade_offset, 6, "distance a from the blade's contact to the centre of mass",
                  "m"),
    ),
    constraints=(
        Constraint(sympy.expand(across.dot(velocity_of_contact)),
                   "velocity of the blade's contact point across the blade [m/s]"),
    ),
)
