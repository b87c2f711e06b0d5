"""Shared geometry of the joint primitives (ADAMS's JPRIM statements) and CONVEL's condition.

Not a spec (the underscore): ``jp_<primitive>.py`` (marker I on part i, marker J on part j:
a spec of two parts) and ``gnd_<primitive>.py`` (marker J on the ground, which has no
coordinates: a spec of one part) build their ``SPEC`` from :func:`primitive`. x_i, y_i, z_i
and x_j, y_j, z_j are the markers' axes in ground components, d = r_I - r_J the vector from
J's origin to I's (docs/datasets.md, "JOINT and JPRIM")::

    atpoint        d = 0                                   3 components
    inline         d.x_j = d.y_j = 0                       2
    inplane        d.z_j = 0                               1
    parallel_axes  z_i.x_j = z_i.y_j = 0                   2
    perpendicular  z_i.z_j = 0                             1
    orientation    z_i.x_j = z_i.y_j = x_i.y_j = 0         3
    homokinetic    x_i.y_j + y_i.x_j = 0                   1

The first six are ADAMS's joint primitives (JPRIM). The seventh is no JPRIM: it is the
constant-velocity condition of a CONVEL joint (with atpoint). With the z axes along the two
shafts, each pointing away from the joint's centre (ADAMS's rule for CONVEL), let J' be J's
axes turned a half turn about x_j (z_j' = z_i when the shafts are in line). The rotation that
carries I's axes onto J', by an angle a about an axis n, has 2 sin(a) n.z_i =
x_i.y_j + y_i.x_j: the equation holds exactly when n is perpendicular to z_i (and so to both
shafts), in the plane that bisects them; the two halves of the joint are then mirror images
in that plane, and the shafts turn at the same rate. The equation is symmetric in I and J; it
also holds a half turn of twist away, which the start excludes as it excludes reversed axes
for the others.

The geometry is held by PAR as vectors, never as angles, so that the driver can turn it when
a part is re-based (docs/rebasing.md) by one matrix product, with no Euler-angle singularity:
I's origin and axes in part i's principal axes, J's in part j's (in ground for ``gnd_``). Each
spec takes only the vectors its components use, in the order I origin, z_i, x_i, y_i,
J origin, x_j, y_j, z_j (the generator refuses a parameter no component uses), and declares only the
coordinates they depend on (X, Y, Z only with an origin). A part's rotation is
R = Rz(psi) Rx(theta) Rz(phi) (docs/design.md section 3). As vectors, a joint's geometry fits
PAR's 30 entries primitive by primitive (a two-part in-line primitive needs 27), not joint by
joint (a two-part FIXED joint would need 33): a JOINT is served by its primitives' routines.
"""

import sympy
from sympy import cos, sin

from ucon.spec import Constraint, ConstraintSpec, Parameter, Variable

x, y, z = sympy.symbols("x y z", real=True)
psi, theta, phi = sympy.symbols("psi theta phi", real=True)
xj, yj, zj = sympy.symbols("xj yj zj", real=True)
psij, thetaj, phij = sympy.symbols("psij thetaj phij", real=True)

#: The vectors a primitive may use: name -> (symbol stem, meaning, units); "in part i" means
#: in part i's principal axes
VECTORS = {
    "ip": ("ip", "I's origin in part i", "length"),
    "iz": ("iz", "I's z axis in part i", "1"),
    "ix": ("ix", "I's x axis in part i", "1"),
    "iy": ("iy", "I's y axis in part i", "1"),
    "jp": ("jp", "J's origin in {frame}", "length"),
    "jx": ("jx", "J's x axis in {frame}", "1"),
    "jy": ("jy", "J's y axis in {frame}", "1"),
    "jz": ("jz", "J's z axis in {frame}", "1"),
}
#: The order of the vectors in PAR
ORDER = ("ip", "iz", "ix", "iy", "jp", "jx", "jy", "jz")

#: Each primitive: the vectors it uses, its title, the meaning of its components and the
#: ADAMS statement it serves
PRIMITIVES = {
    "atpoint": (("ip", "jp"), "at-point joint primitive", "I's origin at J's", "JPRIM"),
    "inline": (("ip", "jp", "jx", "jy"), "in-line joint primitive", "I's origin on J's z axis",
               "JPRIM"),
    "inplane": (("ip", "jp", "jz"), "in-plane joint primitive", "I's origin in J's x-y plane",
                "JPRIM"),
    "parallel_axes": (("iz", "jx", "jy"), "parallel-axes joint primitive",
                      "I's z axis parallel to J's", "JPRIM"),
    "perpendicular": (("iz", "jz"), "perpendicular joint primitive",
                      "I's z axis perpendicular to J's", "JPRIM"),
    "orientation": (("iz", "ix", "jx", "jy"), "orientation joint primitive",
                    "I's axes parallel to J's", "JPRIM"),
    "homokinetic": (("ix", "iy", "jx", "jy"), "homokinetic condition",
                    "I's and J's shafts turn alike", "JOINT CONVEL"),
}


def _rotation(a: sympy.Symbol, b: sympy.Symbol, c: sympy.Symbol) -> sympy.Matrix:
    """R = Rz(a) Rx(b) Rz(c): principal axes to ground."""
    rz1 = sympy.Matrix([[cos(a), -sin(a), 0], [sin(a), cos(a), 0], [0, 0, 1]])
    rx = sympy.Matrix([[1, 0, 0], [0, cos(b), -sin(b)], [0, sin(b), cos(b)]])
    rz3 = sympy.Matrix([[cos(c), -sin(c), 0], [sin(c), cos(c), 0], [0, 0, 1]])
    return rz1 * rx * rz3


def _vector(stem: str) -> sympy.Matrix:
    return sympy.Matrix(sympy.symbols(f"{stem}x {stem}y {stem}z", real=True))


def primitive(name: str, ground: bool) -> ConstraintSpec:
    """The spec ``gnd_<name>`` (marker J on ground) or ``jp_<name>`` (J on a second part)."""
    used, title, meaning, statement = PRIMITIVES[name]
    rotation = _rotation(psi, theta, phi)
    vec = {key: _vector(VECTORS[key][0]) for key in used}
    if not ground:
        # J's vectors are fixed in part j: in ground they turn and move with it
        rotation_j = _rotation(psij, thetaj, phij)
        for key in ("jx", "jy", "jz"):
            if key in vec:
                vec[key] = rotation_j * vec[key]
        if "jp" in vec:
            vec["jp"] = sympy.Matrix([xj, yj, zj]) + rotation_j * vec["jp"]
    r_i = sympy.Matrix([x, y, z]) + rotation * vec["ip"] if "ip" in vec else None
    d = r_i - vec["jp"] if r_i is not None else None
    z_i = rotation * vec["iz"] if "iz" in vec else None
    x_i = rotation * vec["ix"] if "ix" in vec else None
    y_i = rotation * vec["iy"] if "iy" in vec else None

    def dot(a: sympy.Matrix, b: sympy.Matrix) -> sympy.Expr:
        return sympy.expand((a.T * b)[0, 0])

    length = "[length]"
    if name == "atpoint":
        components = [Constraint(sympy.expand(d[k]), f"{axis} of I's origin from J's, ground "
                                 f"axes {length}") for k, axis in enumerate("XYZ")]
    elif name == "inline":
        components = [Constraint(dot(d, vec["jx"]), f"I's origin from J's along x_j {length}"),
                      Constraint(dot(d, vec["jy"]), f"I's origin from J's along y_j {length}")]
    elif name == "inplane":
        components = [Constraint(dot(d, vec["jz"]), f"I's origin from J's along z_j {length}")]
    elif name == "parallel_axes":
        components = [Constraint(dot(z_i, vec["jx"]), "z_i.x_j [1]"),
                      Constraint(dot(z_i, vec["jy"]), "z_i.y_j [1]")]
    elif name == "perpendicular":
        components = [Constraint(dot(z_i, vec["jz"]), "z_i.z_j [1]")]
    elif name == "orientation":
        components = [Constraint(dot(z_i, vec["jx"]), "z_i.x_j [1]"),
                      Constraint(dot(z_i, vec["jy"]), "z_i.y_j [1]"),
                      Constraint(dot(x_i, vec["jy"]), "x_i.y_j [1]")]
    else:
        components = [Constraint(dot(x_i, vec["jy"]) + dot(y_i, vec["jx"]),
                                 "x_i.y_j + y_i.x_j [1]")]
    codes = [(x, 11), (y, 12), (z, 13), (psi, 14), (theta, 15), (phi, 16)]
    if "ip" not in vec:
        codes = codes[3:]
    variables = [Variable(symbol, code) for symbol, code in codes]
    if not ground:
        codes_j = [(xj, 11), (yj, 12), (zj, 13), (psij, 14), (thetaj, 15), (phij, 16)]
        if "jp" not in vec:
            codes_j = codes_j[3:]
        variables += [Variable(symbol, code, part=2) for symbol, code in codes_j]
    parameters = []
    index = 2 + len(variables) + (0 if ground else 1)
    frame = "ground" if ground else "part j"
    for key in ORDER:
        if key not in used:
            continue
        stem, what, units = VECTORS[key]
        unit = "length unit" if units == "length" else "1"
        symbols = _vector(stem)
        for k, axis in enumerate("xyz"):
            parameters.append(Parameter(symbols[k], index,
                                        f"{axis} of {what.format(frame=frame)}", unit))
            index += 1
    where = "marker J on ground" if ground else "marker J on a second part"
    return ConstraintSpec(
        name=f"gnd_{name}" if ground else f"jp_{name}",
        title=f"{title} to ground" if ground else title,
        summary=f"{meaning}: marker I on a part, {where} (ADAMS {statement}).",
        variables=tuple(variables),
        parameters=tuple(parameters),
        constraints=tuple(components),
        component_meaning="primitive component",
        # sums of products of sines, cosines and parameters already: simplify would cost
        # minutes per spec (ucon/spec.py)
        simplify=False,
    )
