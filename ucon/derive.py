"""Every quantity ADAMS asks a UCOSUB for (docs/design.md §2), derived symbolically.

For each component F(q, t): the value F; f(t), the part of F free of the variables (the
additive terms of the expanded F in which no variable appears); dF/dt; d2F/dt2; dF/dq_j;
d2F/dt dq_j; and d2F/dq_i dq_j (one expression per unordered pair, written to both
triangles). Each is simplified (never into a longer expression); zeros are dropped, so the
routine leaves those entries untouched and the caller's zeroing stands.

SymPy's simplify may take minutes on one entry (a spec whose components hold square roots of
trigonometric sums). A time bound on a spec's simplification (:class:`SimplifyBound`) keeps
every entry it did not reach, and the one it interrupted, as differentiated: exact, only
longer, and the one cse still shares their terms.
"""

from __future__ import annotations

import signal
import threading
import time
from dataclasses import dataclass, field
from typing import Callable

import sympy

from .spec import TIME, ConstraintSpec, validate

__all__ = ["OUTPUTS", "TIME_OUTPUTS", "Entry", "Derivatives", "SimplifyBound", "derive",
           "table", "DEFAULT_SIMPLIFY_SECONDS"]

#: The command line's bound on the simplification of a spec file [s] (``python -m ucon write
#: PATH/spec.py``): the catalog's slowest spec, turntable_disk, takes 6 s of CPU; a spec
#: that would take many minutes is written after it, its remaining entries as differentiated.
DEFAULT_SIMPLIFY_SECONDS = 120.0
#: Least wall time between two progress lines [s].
PROGRESS_SECONDS = 5.0

#: Output kinds in the order the generated code and the table list them, with their labels.
OUTPUTS: dict[str, str] = {
    "value": "F",
    "time_part": "f(t)",
    "dt": "dF/dt",
    "dtt": "d2F/dt2",
    "dq": "dF/dq",
    "dtdq": "d2F/dt dq",
    "dqdq": "d2F/dq dq",
}

#: Outputs returned through SCALAR, with their IDRSEL(1) value.
SCALAR_SELECTORS: dict[str, int] = {"value": 1, "time_part": 2, "dt": 3, "dtt": 4}
#: Outputs returned through ARRAY, with their IDRSEL(2) value.
ARRAY_SELECTORS: dict[str, int] = {"dq": 1, "dtdq": 2}
#: Outputs that are identically zero when F has no explicit time.
TIME_OUTPUTS = ("dt", "dtt", "dtdq")


@dataclass(frozen=True)
class Entry:
    """One non-zero output entry.

    Attributes:
        component: 1-based constraint component.
        output: one of :data:`OUTPUTS`.
        row: 1-based variable index for ARRAY and XMATRX entries, 0 for SCALAR ones.
        column: 1-based second variable index for XMATRX entries (``row <= column``), else 0.
        expression: the simplified expression.
    """

    component: int
    output: str
    row: int
    column: int
    expression: sympy.Expr

    @property
    def multiplicity(self) -> int:
        """How many output numbers the entry fills: 2 for an off-diagonal XMATRX pair."""
        return 2 if self.output == "dqdq" and self.row != self.column else 1


@dataclass(frozen=True)
class Derivatives:
    """The non-zero entries of every output of a spec, in a fixed order.

    Attributes:
        spec: the validated spec they were derived from.
        entries: component by component, output kind by :data:`OUTPUTS` order, then by
            variable index.
    """

    spec: ConstraintSpec
    entries: tuple[Entry, ...]

    def of(self, component: int, output: str) -> tuple[Entry, ...]:
        """The non-zero entries of one output of one component."""
        return tuple(e for e in self.entries if e.component == component and e.output == output)

    def count(self, output: str | None = None) -> int:
        """Number of non-zero output numbers (XMATRX pairs count twice), of one kind or all."""
        return sum(e.multiplicity for e in self.entries if output in (None, e.output))

    def time_free(self, component: int) -> bool:
        """True when F of the component has no explicit time: its dF/dt, d2F/dt2 and
        d2F/dt dq_j are identically zero (its f(t) is then a constant, often zero)."""
        return not any(self.of(component, kind) for kind in TIME_OUTPUTS)

    def holonomic(self, component: int) -> bool:
        """True when F of the component depends on no velocity: dF/dq_j is identically zero
        for every velocity variable q_j, and the UCON is a position constraint."""
        velocity = [v.is_velocity for v in self.spec.variables]
        return not any(velocity[e.row - 1] for e in self.of(component, "dq"))


def simplified(expression: sympy.Expr) -> sympy.Expr:
    """SymPy's simplify, kept only when it does not lengthen the expression."""
    if expression.is_Number or expression.is_Symbol:
        return expression
    return sympy.simplify(expression, ratio=1)


class _OutOfTime(Exception):
    """Raised by the alarm inside SymPy's simplify when the bound runs out."""


@dataclass
class SimplifyBound:
    """A wall-clock bound on the simplification of one spec, and its progress.

    Attributes:
        seconds: the bound [s]; None (the default) for none.
        progress: called with a line of progress (every :data:`PROGRESS_SECONDS`, also in the
            middle of one long simplification, and when the bound runs out); None for silence.
        simplified: expressions simplified so far; ``kept``: expressions kept as
            differentiated because the bound ran out (the one interrupted among them).
        ran_out: the bound ran out.
    """

    seconds: float | None = None
    progress: Callable[[str], None] | None = None
    simplified: int = 0
    kept: int = 0
    ran_out: bool = False
    _start: float = field(default=0.0, repr=False)
    _last: float = field(default=0.0, repr=False)
    _total: int = field(default=0, repr=False)
    _name: str = field(default="", repr=False)

    def start(self, name: str, total: int) -> None:
        """Begin a spec of at most ``total`` expressions to simplify."""
        self._name, self._total = name, total
        self._start = self._last = time.monotonic()
        self.simplified = self.kept = 0
        self.ran_out = False

    def _say(self, text: str) -> None:
        if self.progress is not None:
            self.progress(f"ucon: {self._name}: {text}")

    def _tick(self, now: float) -> None:
        """A progress line when the last is PROGRESS_SECONDS old."""
        if now - self._last >= PROGRESS_SECONDS:
            self._last = now
            self._say(f"simplified {self.simplified} of at most {self._total} expressions "
                      f"({now - self._start:.0f} s)")

    def simplify(self, expression: sympy.Expr) -> sympy.Expr:
        """``simplified(expression)`` within the bound; the expression itself once it ran out."""
        if self.ran_out:
            self.kept += 1
            return expression
        deadline = None if self.seconds is None else self._start + self.seconds
        try:
            result = self._bounded(expression, deadline)
        except _OutOfTime:
            self.ran_out = True
            self.kept += 1
            self._say(f"the time bound on simplification ({self.seconds:g} s, "
                      "--simplify-seconds) ran out after "
                      f"{self.simplified} of at most {self._total} expressions; the rest are "
                      "kept as differentiated (exact, longer)")
            return expression
        self.simplified += 1
        self._tick(time.monotonic())
        return result

    def _bounded(self, expression: sympy.Expr, deadline: float | None) -> sympy.Expr:
        """simplified(expression), with a progress line every PROGRESS_SECONDS while it runs
        and interrupted (_OutOfTime) at the deadline, both by SIGALRM. Off the main thread no
        alarm can be set: the deadline is then checked between expressions only."""
        now = time.monotonic()
        if deadline is not None and now >= deadline:
            raise _OutOfTime()
        if threading.current_thread() is not threading.main_thread():
            return simplified(expression)

        def arm(now: float) -> None:
            wait = PROGRESS_SECONDS - (now - self._last)
            if deadline is not None:
                wait = min(wait, deadline - now)
            signal.setitimer(signal.ITIMER_REAL, max(wait, 1e-3))

        def alarm(signum, frame) -> None:  # noqa: ARG001 - a signal handler's signature
            now = time.monotonic()
            if deadline is not None and now >= deadline:
                raise _OutOfTime()
            self._tick(now)
            arm(now)

        previous = signal.signal(signal.SIGALRM, alarm)
        try:
            arm(now)
            return simplified(expression)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)

    def finish(self) -> None:
        """The closing progress line, when the work took long enough to report or ran out."""
        spent = time.monotonic() - self._start
        if self.ran_out or spent >= PROGRESS_SECONDS:
            distinct = self.simplified + self.kept
            self._say(f"{distinct} distinct expressions (a repeated one is simplified once): "
                      f"{self.simplified} simplified, {self.kept} kept as differentiated; "
                      f"{spent:.0f} s for the whole derivation (the bound is on simplification)")


def time_part(expression: sympy.Expr, variables: set[sympy.Symbol]) -> sympy.Expr:
    """f(t): the sum of the additive terms of the expanded F in which no variable appears."""
    terms = sympy.Add.make_args(sympy.expand(expression))
    return sympy.Add(*[term for term in terms if not term.free_symbols & variables])


def derive(spec: ConstraintSpec, bound: SimplifyBound | None = None) -> Derivatives:
    """Validate ``spec`` and derive the non-zero entries of every output of every component.

    ``bound``: the time bound on simplification and its progress (default: none, silent); an
    entry the bound leaves is kept as differentiated.

    Raises:
        ValueError: when the spec is invalid (see :func:`ucon.spec.validate`).
    """
    validate(spec)
    q = [v.symbol for v in spec.variables]
    variables = set(q)
    entries: list[Entry] = []
    cache: dict[sympy.Expr, sympy.Expr] = {}

    bound = bound if bound is not None else SimplifyBound()
    # F, then its value, f(t), dF/dt, d2F/dt2, n dF/dq, n d2F/dt dq and n(n+1)/2 d2F/dq dq
    n = len(q)
    bound.start(spec.name, spec.ncomponents * (5 + 2 * n + n * (n + 1) // 2))
    simplify = bound.simplify if spec.simplify else (lambda expression: expression)

    def add(component: int, output: str, row: int, column: int, raw: sympy.Expr) -> None:
        if raw not in cache:
            cache[raw] = simplify(raw)
        expression = cache[raw]
        if expression != 0:
            entries.append(Entry(component, output, row, column, expression))

    for k, constraint in enumerate(spec.constraints, start=1):
        # Simplifying F first keeps its derivatives short (a spec stated with vectors carries
        # sin**2 + cos**2 and the like).
        f = simplify(constraint.expression)
        add(k, "value", 0, 0, f)
        add(k, "time_part", 0, 0, time_part(f, variables))
        add(k, "dt", 0, 0, sympy.diff(f, TIME))
        add(k, "dtt", 0, 0, sympy.diff(f, TIME, 2))
        first = [sympy.diff(f, qj) for qj in q]
        for j, dq in enumerate(first, start=1):
            add(k, "dq", j, 0, dq)
        for j, dq in enumerate(first, start=1):
            add(k, "dtdq", j, 0, sympy.diff(dq, TIME))
        for i, dq in enumerate(first, start=1):
            for j in range(i, len(q) + 1):
                add(k, "dqdq", i, j, sympy.diff(dq, q[j - 1]))
    if spec.simplify:
        bound.finish()
    return Derivatives(spec, tuple(entries))


def table(derivatives: Derivatives) -> str:
    """The table of non-zero entries, one per line, and the count by output kind."""
    spec = derivatives.spec
    names = [v.symbol.name for v in spec.variables]
    lines = [
        f"{spec.name}: {spec.ncomponents} constraint(s) over {spec.nvars} variables "
        f"({' '.join(names)})",
        f"{'F':<4}{'output':<11}{'entry':<22}expression",
    ]
    for entry in derivatives.entries:
        if entry.output == "dqdq":
            a, b = names[entry.row - 1], names[entry.column - 1]
            where = f"({a}, {a})" if a == b else f"({a}, {b}) x2"
        elif entry.row:
            where = names[entry.row - 1]
        else:
            where = "-"
        lines.append(f"F{entry.component:<3}{OUTPUTS[entry.output]:<11}{where:<22}"
                     f"{sympy.sstr(entry.expression)}")
    counts = " + ".join(f"{derivatives.count(kind)} {label}" for kind, label in OUTPUTS.items())
    lines.append(f"non-zero entries: {counts} = {derivatives.count()}")
    components = range(1, spec.ncomponents + 1)
    for label, test in (("time-free (no dF/dt, d2F/dt2, d2F/dt dq)", derivatives.time_free),
                        ("holonomic (no velocity)", derivatives.holonomic)):
        which = " ".join(f"F{k}" for k in components if test(k)) or "none"
        lines.append(f"{label}: {which}")
    return "\n".join(lines) + "\n"
