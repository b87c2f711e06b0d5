"""Reference partials of ADAMS function expressions, derived by SymPy, for rollcon's tests.

rollcon computes an expression's partials at run time by forward-mode automatic
differentiation (src/mechanics/rollcon_jet.f90, rollcon_expression_jet.f90,
rollcon_measures.f90). This module states the same definitions a second time, in SymPy
(docs/datasets.md, "Function expressions" and "Measures of markers"), and derives each
expression's value, gradient and Hessian symbolically over two parts' coordinates q, rates u and
the time t, at fixed states. It writes them as a Fortran module the suite ``expression-functions``
compares rollcon's jets with::

    python3 -m ucon.expression_partials [test/unit/mechanics/expression_reference.f90]

Independent of rollcon's code: a marker's velocity is dr/dt by the chain rule over q, and its
angular velocity comes from the skew matrix dR/dt R^T, not from rollcon's formulas. A function
with branches (STEP, IMPACT, MIN, IF, ...) is differentiated on the branch its arguments'
values select at the state. The Hessian is stored as its products with two fixed vectors (H v1,
H v2): a wrong entry changes them for any such vector.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import mpmath
import sympy
from sympy import Matrix, cos, sin

#: The file written, relative to the project root
OUTPUT = "test/unit/mechanics/expression_reference.f90"

Q = sympy.symbols("q1:13", real=True)
U = sympy.symbols("u1:13", real=True)
T = sympy.Symbol("t", real=True)
VARIABLES = (*Q, *U, T)

#: The markers: id -> (part: 0 ground, 1, 2; origin in the part's principal axes; 3-1-3 angles
#: of its axes there; principal: the part's principal axes themselves, as a CM marker)
MARKERS = {
    1: (0, (0.5, 0.2, -0.1), (0.2, 0.3, 0.1)),
    11: (1, (0.1, -0.2, 0.3), (0.3, 0.5, -0.2)),
    12: (1, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
    21: (2, (-0.2, 0.1, 0.05), (1.1, 0.7, 0.4)),
    22: (2, (0.3, 0.0, -0.1), (0.0, 1.2, 2.0)),
}
#: The markers whose angles are their part's own coordinates (a CM marker)
PRINCIPAL = (12,)

#: The states: q of parts 1 and 2, u of parts 1 and 2, t
STATES = (
    ((0.3, -0.4, 1.2, 0.7, 1.1, -0.5, -0.6, 0.9, 0.4, 2.3, 0.6, 1.4),
     (0.5, -0.3, 0.8, 1.2, -0.7, 2.1, -0.9, 0.4, -0.2, 0.6, 1.5, -1.1), 0.8),
    ((-1.1, 0.2, 0.5, -2.6, 2.2, 0.9, 0.8, -0.3, -0.7, 0.4, 1.3, -2.8),
     (-0.2, 0.6, 0.1, -0.8, 0.3, -1.7, 0.7, -1.2, 0.9, 2.2, -0.4, 0.5), 1.7),
)

#: The expressions, each read at every state
EXPRESSIONS = (
    "DX(11, 21, 1)", "DY(21, 11)", "DZ(11, 0, 21)", "DM(11, 21)", "DM(21)",
    "VX(11, 21, 1, 21)", "VY(21, 11, 11, 1)", "VZ(11)", "VM(11, 21, 21)", "VR(11, 21)",
    "VR(22, 1, 11)", "WX(11, 21, 1)", "WY(21)", "WZ(11, 21, 11)", "WM(11, 21)",
    "AX(11, 21)", "AY(21, 1)", "AZ(11)", "PSI(11, 21)", "THETA(21, 11)", "PHI(11)",
    "PSI(12)", "THETA(12) * PHI(12)", "YAW(11, 21)", "PITCH(21)", "ROLL(11, 1)",
    "STEP5(DX(11), -2, 2, 2, 3)", "STEP(TIME, 0, 1, 2, 5) * DY(21)",
    "HAVSIN(DZ(11, 21), -3, 0, 3, 1)", "SHF(TIME, 0.1, 2, 3, 0.4, 0.5) + DM(11, 21)",
    "POLY(DX(11, 21), 0.2, 1, -2, 3, 0.5)", "CHEBY(DY(11), 0.1, 1, 2, 3, 4)",
    "FORCOS(TIME*DX(21), 0, 2, 1, 0.5, -0.25)", "FORSIN(DZ(22), 0.3, 1.5, 0.2, -1, 0.7)",
    "IMPACT(DM(11, 21), VR(11, 21), 5, 100, 1.5, 2, 3)",
    "BISTOP(DX(11, 21), VX(11, 21), -5, -3, 80, 2.5, 4, 3)",
    "DIM(DX(11), DY(21)) + DIM(DY(21), DX(11))", "MOD(3*DZ(11), 0.7)",
    "SIGN(DX(11), DY(21))", "ATAN2(DY(11, 21), DX(11, 21))",
    "EXP(0.3*DX(11)) * LOG(DM(21)) / SQRT(DM(11, 21))", "DX(11, 21)**3 * VX(21)",
    "TAN(0.2*AX(11)) + ASIN(0.1*DX(11)) - ACOS(0.2*DY(21)) + ATAN(DZ(22))",
    "SINH(0.5*DX(21)) + COSH(0.3*DY(11)) * TANH(DZ(21)) + LOG10(DM(22))",
    "MIN(DX(11), DY(21)) - MAX(DZ(11), DZ(21)) + ABS(DX(22))",
    "IF(DX(11) - DY(21): DM(11), 2, WX(21)) * SIN(TIME) + COS(WZ(11))",
    "AINT(2*DX(11)) * DY(21) + ANINT(3*DZ(21)) + RTOD*AZ(22, 11)",
    "DM(11, 21)**2.5 - 2**DX(22)",
)


def rotation(a, b, c) -> Matrix:
    """R = Rz(a) Rx(b) Rz(c)."""
    rz1 = Matrix([[cos(a), -sin(a), 0], [sin(a), cos(a), 0], [0, 0, 1]])
    rx = Matrix([[1, 0, 0], [0, cos(b), -sin(b)], [0, sin(b), cos(b)]])
    rz3 = Matrix([[cos(c), -sin(c), 0], [sin(c), cos(c), 0], [0, 0, 1]])
    return rz1 * rx * rz3


def time_derivative(expression):
    """d/dt of an expression of q (and t): the chain rule over q with rates u."""
    return sum(sympy.diff(expression, Q[i]) * U[i] for i in range(12)) + sympy.diff(expression, T)


@functools.lru_cache(maxsize=None)
def angular_velocity(part: int) -> Matrix:
    """A part's angular velocity in ground: the axial vector of dR/dt R^T, simplified."""
    q = Q[6 * (part - 1):6 * part]
    body = rotation(q[3], q[4], q[5])
    spin = body.applyfunc(time_derivative) * body.T
    return Matrix([sympy.trigsimp(sympy.expand(spin[2, 1])),
                   sympy.trigsimp(sympy.expand(spin[0, 2])),
                   sympy.trigsimp(sympy.expand(spin[1, 0]))])


class Kinematics:
    """A marker's position, axes, velocity and angular velocity in ground, symbolically."""

    def __init__(self, marker: int):
        self.r, self.axes, self.v, self.w = kinematics(marker)


@functools.lru_cache(maxsize=None)
def kinematics(marker: int):
    """Position, axes, velocity (dr/dt by the chain rule over q) and angular velocity."""
    part, point, angles = MARKERS[marker] if marker else (0, (0, 0, 0), (0, 0, 0))
    local = rotation(*[sympy.Float(a) for a in angles])
    point = Matrix([sympy.Float(p) for p in point])
    if part == 0:
        return point, local, Matrix([0, 0, 0]), Matrix([0, 0, 0])
    q = Q[6 * (part - 1):6 * part]
    body = rotation(q[3], q[4], q[5])
    r = Matrix(q[0:3]) + body * point
    return r, body * local, r.applyfunc(time_derivative), angular_velocity(part)


def numeric(expression, point) -> float:
    """The value at a state, computed with 30 digits (mpmath) through one common-subexpression
    pass: evalf on the whole tree would expand every shared subexpression."""
    expression = sympy.sympify(expression)
    if expression.is_number:
        return float(expression.evalf(30))
    used = sorted(expression.free_symbols, key=lambda v: v.name)
    function = sympy.lambdify(used, expression, modules="mpmath", cse=True)
    with mpmath.workdps(30):
        return float(function(*[mpmath.mpf(float(point[v])) for v in used]))


class Language:
    """The functions of an expression, for Python's eval of its text at one state."""

    def __init__(self, point):
        self.point = point

    def value(self, e) -> float:
        return numeric(sympy.sympify(e), self.point)

    def names(self) -> dict:
        def step(x, x0, h0, x1, h1, shape):
            if self.value(x) <= self.value(x0):
                return sympy.sympify(h0)
            if self.value(x) >= self.value(x1):
                return sympy.sympify(h1)
            s = (x - x0) / (x1 - x0)
            return shape(s, h0, h1)

        def impact_side(x, xdot, x1, k, e, cmax, d):
            f = k * (x1 - x)**e - step(x, x1 - d, cmax, x1, 0, cubic) * xdot
            return f if self.value(f) > 0 else sympy.Integer(0)

        def cubic(s, h0, h1):
            return h0 + (h1 - h0) * s**2 * (3 - 2 * s)

        def quintic(s, h0, h1):
            return h0 + (h1 - h0) * s**3 * (10 - 15 * s + 6 * s**2)

        def haversine(s, h0, h1):
            return (h0 + h1) / 2 + (h1 - h0) / 2 * sin(sympy.pi * s - sympy.pi / 2)

        def bistop(x, xdot, x1, x2, k, e, cmax, d):
            if self.value(x) < x1:
                return impact_side(x, xdot, x1, k, e, cmax, d)
            if self.value(x) > x2:
                f = -k * (x - x2)**e - step(x, x2, 0, x2 + d, cmax, cubic) * xdot
                return f if self.value(f) < 0 else sympy.Integer(0)
            return sympy.Integer(0)

        def impact(x, xdot, x1, k, e, cmax, d):
            return impact_side(x, xdot, x1, k, e, cmax, d) if self.value(x) < x1 \
                else sympy.Integer(0)

        def choose(condition, a, b):
            return a if condition else b

        names = {
            "TIME": T, "PI": sympy.pi, "DTOR": sympy.pi / 180, "RTOD": 180 / sympy.pi,
            "SIN": sin, "COS": cos, "TAN": sympy.tan, "ASIN": sympy.asin, "ACOS": sympy.acos,
            "ATAN": sympy.atan, "ATAN2": sympy.atan2, "EXP": sympy.exp, "LOG": sympy.log,
            "LOG10": lambda x: sympy.log(x) / sympy.log(10), "SQRT": sympy.sqrt,
            "SINH": sympy.sinh, "COSH": sympy.cosh, "TANH": sympy.tanh,
            "ABS": lambda x: choose(self.value(x) >= 0, x, -x),
            "MIN": lambda a, b: choose(self.value(b) < self.value(a), b, a),
            "MAX": lambda a, b: choose(self.value(b) > self.value(a), b, a),
            "DIM": lambda a, b: choose(self.value(a) > self.value(b), a - b, sympy.Integer(0)),
            "MOD": lambda a, b: a - sympy.Integer(int(self.value(a) / self.value(b))) * b,
            "AINT": lambda x: sympy.Integer(int(self.value(x))),
            "ANINT": lambda x: sympy.Integer(int(sympy.sign(self.value(x)) *
                                                 sympy.floor(abs(self.value(x)) + 0.5))),
            "SIGN": lambda a, b: choose(self.value(b) >= 0, 1, -1) *
            choose(self.value(a) >= 0, a, -a),
            "STEP": lambda x, x0, h0, x1, h1: step(x, x0, h0, x1, h1, cubic),
            "STEP5": lambda x, x0, h0, x1, h1: step(x, x0, h0, x1, h1, quintic),
            "HAVSIN": lambda x, x0, h0, x1, h1: step(x, x0, h0, x1, h1, haversine),
            "SHF": lambda x, x0, a, w, phi, b: a * sin(w * (x - x0) - phi) + b,
            "POLY": lambda x, x0, *a: sum(c * (x - x0)**j for j, c in enumerate(a)),
            "CHEBY": lambda x, x0, *a: sum(c * sympy.chebyshevt(j, x - x0)
                                           for j, c in enumerate(a)),
            "FORCOS": lambda x, x0, w, a0, *a: a0 + sum(c * cos((j + 1) * w * (x - x0))
                                                        for j, c in enumerate(a)),
            "FORSIN": lambda x, x0, w, a0, *a: a0 + sum(c * sin((j + 1) * w * (x - x0))
                                                        for j, c in enumerate(a)),
            "IMPACT": impact, "BISTOP": bistop,
            "IF": lambda e, negative, zero, positive: choose(
                self.value(e) < 0, negative, choose(self.value(e) > 0, positive, zero)),
        }
        names.update(measures())
        return names


def relative(i: Kinematics, j: Kinematics) -> Matrix:
    """The rotation of i's axes in j's: A_j^T A_i."""
    return j.axes.T * i.axes


def measures() -> dict:
    """The measures of markers, as docs/datasets.md defines them."""
    def frame_rate(i, j, l):
        d = i.r - j.r
        return i.v - j.v - l.w.cross(d)

    def dx(c):
        return lambda i, j=0, k=0: (Kinematics(i).r - Kinematics(j).r).dot(
            Kinematics(k).axes[:, c])

    def vx(c):
        return lambda i, j=0, k=0, l=0: frame_rate(Kinematics(i), Kinematics(j),
                                                   Kinematics(l)).dot(Kinematics(k).axes[:, c])

    def wx(c):
        return lambda i, j=0, k=0: (Kinematics(i).w - Kinematics(j).w).dot(
            Kinematics(k).axes[:, c])

    def euler(c):
        def angle(i, j=0):
            if j == 0 and i in PRINCIPAL:
                part = MARKERS[i][0]
                return Q[6 * (part - 1) + 3 + c]
            m = relative(Kinematics(i), Kinematics(j))
            return (sympy.atan2(m[0, 2], -m[1, 2]),
                    sympy.atan2(sympy.sqrt(m[0, 2]**2 + m[1, 2]**2), m[2, 2]),
                    sympy.atan2(m[2, 0], m[2, 1]))[c]
        return angle

    def axis_angle(c):
        def angle(i, j=0):
            a, b = Kinematics(i).axes, Kinematics(j).axes
            return (sympy.atan2(-a[:, 2].dot(b[:, 1]), a[:, 2].dot(b[:, 2])),
                    sympy.atan2(a[:, 2].dot(b[:, 0]), a[:, 2].dot(b[:, 2])),
                    sympy.atan2(a[:, 0].dot(b[:, 1]), a[:, 0].dot(b[:, 0])))[c]
        return angle

    def ypr(c):
        def angle(i, j=0):
            m = relative(Kinematics(i), Kinematics(j))
            return (sympy.atan2(m[1, 0], m[0, 0]),
                    sympy.atan2(m[2, 0], sympy.sqrt(m[2, 1]**2 + m[2, 2]**2)),
                    sympy.atan2(m[2, 1], m[2, 2]))[c]
        return angle

    def norm(vector):
        return sympy.sqrt(vector.dot(vector))

    names = {}
    for c, axis in enumerate("XYZ"):
        names["D" + axis] = dx(c)
        names["V" + axis] = vx(c)
        names["W" + axis] = wx(c)
        names["A" + axis] = axis_angle(c)
    for c, name in enumerate(("PSI", "THETA", "PHI")):
        names[name] = euler(c)
    for c, name in enumerate(("YAW", "PITCH", "ROLL")):
        names[name] = ypr(c)
    names["DM"] = lambda i, j=0: norm(Kinematics(i).r - Kinematics(j).r)
    names["VM"] = lambda i, j=0, l=0: norm(frame_rate(Kinematics(i), Kinematics(j),
                                                      Kinematics(l)))
    names["VR"] = lambda i, j=0, l=0: (Kinematics(i).v - Kinematics(j).v).dot(
        Kinematics(i).r - Kinematics(j).r) / norm(Kinematics(i).r - Kinematics(j).r)
    names["WM"] = lambda i, j=0: norm(Kinematics(i).w - Kinematics(j).w)
    return names


def point_of(state) -> dict:
    q, u, t = state
    point = {Q[i]: sympy.Float(q[i]) for i in range(12)}
    point.update({U[i]: sympy.Float(u[i]) for i in range(12)})
    point[T] = sympy.Float(t)
    return point


#: The two vectors the Hessian is multiplied by (fixed, no structure)
PROBES = (
    tuple(((7 * k) % 11 - 5) / 4.0 for k in range(25)),
    tuple(((5 * k + 3) % 13 - 6) / 5.0 for k in range(25)),
)


def reference(text: str, state) -> tuple[float, list[float], list[list[float]]]:
    """Value, gradient and H v1, H v2 of an expression at a state: the value and gradient
    exactly (SymPy's derivatives evaluated with 60 digits), each H v as the central difference
    of that exact gradient along v with a step of 1e-25 in 60-digit arithmetic (truncation
    h^2 times the third derivative, ~1e-50; rounding 1e-60/h = 1e-35: exact to every digit a
    double holds)."""
    point = point_of(state)
    language = Language(point)
    written = text.replace(":", ",")
    expression = sympy.sympify(eval(written, {"__builtins__": {}}, language.names()))
    gradient = [sympy.diff(expression, v) if expression.has(v) else sympy.Integer(0)
                for v in VARIABLES]
    function = sympy.lambdify(VARIABLES, [expression, *gradient], modules="mpmath", cse=True)
    step = mpmath.mpf("1e-25")
    with mpmath.workdps(60):
        x = [mpmath.mpf(float(point[v])) for v in VARIABLES]
        values = [mpmath.mpf(value) for value in function(*x)]
        products = []
        for probe in PROBES:
            ahead = function(*[x[k] + step * probe[k] for k in range(25)])
            behind = function(*[x[k] - step * probe[k] for k in range(25)])
            products.append([float((ahead[k + 1] - behind[k + 1]) / (2 * step))
                             for k in range(25)])
        return float(values[0]), [float(v) for v in values[1:]], products


def fortran_reals(values, indent: str = "        & ") -> str:
    items = [f"{v:.17e}".replace("e", "e") + "_wp" for v in values]
    lines, line = [], ""
    for item in items:
        piece = item + ", "
        if len(indent) + len(line) + len(piece) > 84:
            lines.append(indent + line.rstrip())
            line = ""
        line += piece
    lines.append(indent + line.rstrip().rstrip(","))
    return " &\n".join(lines)


def module_text() -> str:
    rows = []
    for state in STATES:
        for text in EXPRESSIONS:
            print(f"  {text}", file=sys.stderr)
            rows.append((text, state, *reference(text, state)))
    n = len(rows)
    header = [
        "! SPDX-License-Identifier: MIT",
        "! Generated by python3 -m ucon.expression_partials (ucon/expression_partials.py): do not",
        "! edit; run that command again to regenerate.",
        "!> Reference values, gradients and Hessian products of ADAMS function expressions,",
        "!> derived by SymPy from docs/datasets.md's definitions (ucon/expression_partials.py), for",
        "!> the suite expression-functions to compare rollcon's jets with.",
        "module expression_reference",
        "    use rollcon_kinds, only : wp",
        "    implicit none",
        "    private",
        "",
        "    public :: reference_count, reference_texts, reference_states, reference_values, &",
        "        & reference_gradients, reference_products, reference_probes, reference_markers, &",
        "        & reference_marker_parts, reference_marker_points, reference_marker_angles",
        "",
        f"    integer, parameter :: reference_count = {n}",
    ]
    texts = ", &\n".join(f'        & "{row[0]}"' for row in rows)
    header.append(f"    !> The expressions, the state each is read at (index of reference_states)")
    header.append(f"    character(len=*), parameter :: reference_texts({n}) = [character(len=80) :: &")
    header.append(texts.replace("        & ", "        & ", 1) + "]")
    states = []
    for state in STATES:
        q, u, t = state
        states.extend([*q, *u, t])
    header.append(f"    !> Each state: q (12: parts 1 and 2), u (12), t")
    header.append(f"    real(wp), parameter :: reference_states(25, {len(STATES)}) = reshape([ &")
    header.append(fortran_reals(states) + f"], [25, {len(STATES)}])")
    header.append("    !> The value of each expression at its state (expression k at state")
    header.append(f"    !> (k - 1)/{len(EXPRESSIONS)} + 1)")
    header.append(f"    real(wp), parameter :: reference_values({n}) = [ &")
    header.append(fortran_reals([row[2] for row in rows]) + "]")
    header.append("    !> Its gradient over q (1:12), u (13:24) and t (25)")
    header.append(f"    real(wp), parameter :: reference_gradients(25, {n}) = reshape([ &")
    header.append(fortran_reals([g for row in rows for g in row[3]]) + f"], [25, {n}])")
    header.append("    !> Its Hessian times each probe")
    header.append(f"    real(wp), parameter :: reference_products(25, 2, {n}) = reshape([ &")
    header.append(fortran_reals([h for row in rows for p in row[4] for h in p]) +
                  f"], [25, 2, {n}])")
    header.append("    !> The probes")
    header.append("    real(wp), parameter :: reference_probes(25, 2) = reshape([ &")
    header.append(fortran_reals([v for p in PROBES for v in p]) + "], [25, 2])")
    ids = sorted(MARKERS)
    header.append("    !> The markers: id, part (0 ground), origin, 3-1-3 angles of the axes; a marker")
    header.append("    !> whose angles are all 0 on a moving part is its principal axes themselves")
    header.append(f"    integer, parameter :: reference_markers({len(ids)}) = [" +
                  ", ".join(str(i) for i in ids) + "]")
    header.append(f"    integer, parameter :: reference_marker_parts({len(ids)}) = [" +
                  ", ".join(str(MARKERS[i][0]) for i in ids) + "]")
    header.append(f"    real(wp), parameter :: reference_marker_points(3, {len(ids)}) = reshape([ &")
    header.append(fortran_reals([p for i in ids for p in MARKERS[i][1]]) + f"], [3, {len(ids)}])")
    header.append(f"    real(wp), parameter :: reference_marker_angles(3, {len(ids)}) = reshape([ &")
    header.append(fortran_reals([a for i in ids for a in MARKERS[i][2]]) + f"], [3, {len(ids)}])")
    header += ["", "end module expression_reference", ""]
    return "\n".join(header)


def main(argv: list[str]) -> int:
    root = Path(__file__).resolve().parent.parent
    out = Path(argv[0]) if argv else root / OUTPUT
    out.write_text(module_text(), encoding="utf-8")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
