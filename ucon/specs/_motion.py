"""Shared geometry of the angles a MOTION drives (ADAMS's MOTION statement).

Not a spec (the underscore): ``jp_motion_angle.py`` (marker I on part i, marker J on part j)
and ``gnd_motion_angle.py`` (the markers' second side on the ground) build their ``SPEC``
from :func:`motion_angle`. Five unit vectors are parameters: a and c fixed in part i, b, d
and e fixed in part j (in ground for ``gnd_``), each in its part's principal axes, in ground
components once turned with the part (R = Rz(psi) Rx(theta) Rz(phi), docs/design.md §3)::

    component 1   atan2(a.b, c.d)                           an angle of rotation [rad]
    component 2   atan2(a.e, sqrt((a.b)^2 + (c.d)^2))       an angle of tilt [rad]

The driver (rollcon_motion_geometry) picks the vectors so that these are the angles ADAMS
measures (docs/datasets.md, "MOTION"). With A = R_J^T R_I the turn of I's axes from J's
(A_kl = e_k(J).e_l(I)) and I's axes turned from J's by the body 1-2-3 sequence
Rx(b1) Ry(b2) Rz(b3): A13 = sin b2, A23 = -sin b1 cos b2, A33 = cos b1 cos b2,
A12 = -cos b2 sin b3, A11 = cos b2 cos b3, so

    b1 = atan2(z_i.(-y_j), z_i.z_j)                 component 1: a = c = z_i, b = -y_j, d = z_j
    b2 = atan2(z_i.x_j, sqrt(A23^2 + A33^2))        component 2: the same, e = x_j
    b3 = atan2(y_i.(-x_j), x_i.x_j)                 component 1: a = y_i, b = -x_j, c = x_i, d = x_j

and a joint's rotation, that of x_i about the common z axis from x_j (ADAMS's measure on a
REVOLUTE or CYLINDRICAL joint), is atan2(x_i.y_j, x_i.x_j): component 1 with a = c = x_i,
b = y_j, d = x_j. The value is the angle in (-pi, pi]; the driver subtracts the MOTION's
function and brings the difference into (-pi, pi], so that a motion of many turns is served
by the same routine (the partials of the angle are those of the difference).

Only the three angles of each part are declared (the angles do not depend on the origins).
"""

import sympy
from sympy import atan2, sqrt

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable
from ucon.specs._joint import _rotation, _vector, phi, phij, psi, psij, theta, thetaj

#: The vectors, in PAR order: name -> (symbol stem, meaning); a and c in part i, b, d, e in
#: part j (or in ground)
VECTORS = (
    ("va", "vector a in part i"),
    ("vc", "vector c in part i"),
    ("vb", "vector b in {frame}"),
    ("vd", "vector d in {frame}"),
    ("ve", "vector e in {frame}"),
)


def motion_angle(ground: bool) -> ConstraintSpec:
    """The spec ``gnd_motion_angle`` (b, d, e in ground) or ``jp_motion_angle``."""
    rotation = _rotation(psi, theta, phi)
    vec = {stem: _vector(stem) for stem, _ in VECTORS}
    a = rotation * vec["va"]
    c = rotation * vec["vc"]
    b, d, e = vec["vb"], vec["vd"], vec["ve"]
    if not ground:
        rotation_j = _rotation(psij, thetaj, phij)
        b, d, e = rotation_j * b, rotation_j * d, rotation_j * e

    def dot(u: sympy.Matrix, v: sympy.Matrix) -> sympy.Expr:
        return sympy.expand((u.T * v)[0, 0])

    ab, cd, ae = dot(a, b), dot(c, d), dot(a, e)
    components = [
        Constraint(atan2(ab, cd), "atan2(a.b, c.d): an angle of rotation [rad]"),
        Constraint(atan2(ae, sqrt(ab**2 + cd**2)),
                   "atan2(a.e, sqrt((a.b)^2 + (c.d)^2)): an angle of tilt [rad]"),
    ]
    variables = [Variable(psi, 14), Variable(theta, 15), Variable(phi, 16)]
    if not ground:
        variables += [Variable(psij, 14, part=2), Variable(thetaj, 15, part=2),
                      Variable(phij, 16, part=2)]
    parameters = []
    index = 2 + len(variables) + (0 if ground else 1)
    frame = "ground" if ground else "part j"
    for stem, what in VECTORS:
        symbols = _vector(stem)
        for k, axis in enumerate("xyz"):
            parameters.append(Parameter(symbols[k], index,
                                        f"{axis} of {what.format(frame=frame)}", "1"))
            index += 1
    where = "the second side on ground" if ground else "between two parts"
    return ConstraintSpec(
        name="gnd_motion_angle" if ground else "jp_motion_angle",
        title="motion angle to ground" if ground else "motion angle",
        summary=f"An angle of one part's axes from another's, {where}, that a MOTION drives "
        "(ADAMS MOTION, ROTATION or B1, B2, B3).",
        variables=tuple(variables),
        parameters=tuple(parameters),
        constraints=tuple(components),
        component_meaning="angle",
        simplify=False,
    )
