"""The ADAMS-ready fixed-form ``ucosub.f``: SUBROUTINE UCOSUB in FORTRAN 77."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .derive import ARRAY_SELECTORS, SCALAR_SELECTORS
from .messages import (IDRSEL_MESSAGE, IFLAG_MESSAGE, PART_MESSAGE, code_message,
                       second_part_message,
                       component_message, header_lines, npar_message, parameter_message)
from .printers import FIXED_WIDTH, LegacyPrinter, fixed_string, wrap_comment, wrap_fixed
from .spec import ConstraintSpec

if TYPE_CHECKING:
    from .fortran import Program

__all__ = ["render_legacy"]

#: Largest finite double, for the finiteness checks of ``ucosub.f`` (no IEEE module in F77).
LEGACY_HUGE = "1.7976931348623157D308"


class _FixedLines:
    """Accumulates fixed-form lines."""

    def __init__(self) -> None:
        self.lines: list[str] = []

    def add(self, statement: str = "", indent: int = 0, label: str = "") -> None:
        """One statement (wrapped, with an optional label in columns 1-5) or a blank line."""
        if not statement:
            self.lines.append("C")
            return
        lines = wrap_fixed(statement, indent)
        if label:
            lines[0] = f"{label:>5} " + lines[0][6:]
        self.lines.extend(lines)

    def comment(self, text: str) -> None:
        """A comment paragraph."""
        if not text:
            self.lines.append("C")
            return
        self.lines.extend(wrap_comment(text, "C     ", FIXED_WIDTH))

    def text(self) -> str:
        """The file's text, with a final newline."""
        return "\n".join(self.lines) + "\n"


def _legacy_names(spec: ConstraintSpec) -> list[str]:
    """Local DOUBLE PRECISION names: variables, then parameters, upper case."""
    return [s.name.upper() for s in spec.symbols]


def render_legacy(program: Program) -> str:
    """The ADAMS-ready fixed-form ``ucosub.f``: SUBROUTINE UCOSUB and nothing else."""
    spec = program.spec
    printer = LegacyPrinter()
    out = _FixedLines()
    for line in header_lines(spec):
        out.lines.append(f"C {line}")
    out.comment("")
    out.comment(f"{spec.title[0].upper()}{spec.title[1:]} as an ADAMS UCOSUB. {spec.summary}")
    out.comment("")
    for index, meaning in spec.par_layout():
        out.lines.extend(wrap_comment(f"PAR({index}): {meaning}", "C     ", FIXED_WIDTH))
    for k, constraint in enumerate(spec.constraints, start=1):
        out.lines.extend(wrap_comment(f"F{k}: {constraint.meaning}", "C     ", FIXED_WIDTH))
    out.comment("")
    out.comment("IFLAG = 3: declare the variables with UCOVAR. IFLAG = 0: evaluate what IDRSEL "
                "selects. IDRSEL(1) = 0/1/2/3/4: nothing, F, f(t), dF/dt, d2F/dt2 in SCALAR. "
                "IDRSEL(2) = 0/1/2: nothing, dF/dq, d2F/dt dq in ARRAY. IDRSEL(3) = 0/1: "
                "nothing, d2F/dq dq (both triangles) in XMATRX. Entries that are zero are "
                "left untouched: the caller zeroes the outputs. Errors go to ERRMES.")
    out.comment("")
    out.add("SUBROUTINE UCOSUB(ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG, SCALAR, ARRAY, XMATRX)")
    out.add("IMPLICIT NONE")
    out.add("INTEGER ID, NPAR, IDRSEL(3), IFLAG")
    out.add("DOUBLE PRECISION TIME, Q(30), PAR(*), SCALAR, ARRAY(30), XMATRX(30, 30)")
    out.add("INTEGER NVARS, NPARS")
    out.add(f"PARAMETER (NVARS = {spec.nvars}, NPARS = {spec.npar})")
    if spec.parameters:
        out.add("DOUBLE PRECISION BIG")
        out.add(f"PARAMETER (BIG = {LEGACY_HUGE})")
    several = spec.ncomponents > 1
    out.add("INTEGER LPARTS(NVARS), LVARS(NVARS), IPART, I" + (", ICOMP" if several else "")
            + (", JPART" if spec.two_parts else ""))
    out.add("DOUBLE PRECISION " + ", ".join(_legacy_names(spec)))
    if program.temporaries:
        out.add("DOUBLE PRECISION "
                + ", ".join(t.name.upper() for t, _ in program.temporaries))
    out.add(f"CHARACTER*{_legacy_message_length(spec)} MESAGE")
    out.add("DATA LVARS /" + ", ".join(str(v.code) for v in spec.variables) + "/")
    out.comment("")
    out.comment("Check PAR: a bad entry is reported through ERRMES; outputs stay untouched.")
    _legacy_read_par(out, spec)
    out.comment("")
    out.add("IF (IFLAG .EQ. 3) THEN")
    out.add("DO 10 I = 1, NVARS", 3)
    out.add("LPARTS(I) = IPART", 6)
    if spec.two_parts:
        out.add(f"IF (I .GT. {spec.first_part_nvars}) LPARTS(I) = JPART", 6)
    out.add("CONTINUE", 3, label="10")
    out.add("CALL UCOVAR(ID, NVARS, LPARTS, NVARS, LVARS)", 3)
    out.add("RETURN", 3)
    out.add("END IF")
    out.add("IF (IFLAG .NE. 0) THEN")
    out.add(f"MESAGE = {fixed_string(IFLAG_MESSAGE)}", 3)
    out.add("GO TO 900", 3)
    out.add("END IF")
    out.add("IF (IDRSEL(1) .LT. 0 .OR. IDRSEL(1) .GT. 4 .OR. IDRSEL(2) .LT. 0 .OR. "
            "IDRSEL(2) .GT. 2 .OR. IDRSEL(3) .LT. 0 .OR. IDRSEL(3) .GT. 1) THEN")
    out.add(f"MESAGE = {fixed_string(IDRSEL_MESSAGE)}", 3)
    out.add("GO TO 900", 3)
    out.add("END IF")
    out.comment("")
    out.comment("Common subexpressions of every output of every component.")
    for i, variable in enumerate(spec.variables, start=1):
        out.add(f"{variable.symbol.name.upper()} = Q({i})")
    for parameter in spec.parameters:
        out.add(f"{parameter.symbol.name.upper()} = PAR({parameter.index})")
    for name, expression in program.temporaries:
        out.add(f"{name.name.upper()} = {printer.expression(expression)}")
    for k in range(1, spec.ncomponents + 1):
        indent = 0
        if several:
            out.comment("")
            keyword = "IF" if k == 1 else "ELSE IF"
            out.add(f"{keyword} (ICOMP .EQ. {k}) THEN")
            indent = 3
        _legacy_component(out, program, printer, k, indent)
    if several:
        out.add("END IF")
    out.add("RETURN")
    out.comment("")
    out.add("CALL ERRMES(.TRUE., MESAGE, ID, 'STOP')", label="900")
    out.add("RETURN")
    out.add("END")
    return out.text()


def _legacy_message_length(spec: ConstraintSpec) -> int:
    """Length of MESAGE: the longest message and its number, rounded up to a multiple of 40."""
    texts = [npar_message(spec), PART_MESSAGE, IFLAG_MESSAGE, IDRSEL_MESSAGE]
    texts += [code_message(spec, spec.code_index(i), v.code)
              for i, v in enumerate(spec.variables)]
    if spec.two_parts:
        texts.append(second_part_message(spec))
    texts += [parameter_message(p.index, p.description, p.check) for p in spec.parameters]
    if spec.component_index:
        texts.append(component_message(spec))
    longest = max(len(text) for text in texts) + 24
    return 40 * ((longest + 39) // 40)


def _legacy_read_par(out: _FixedLines, spec: ConstraintSpec) -> None:
    """The PAR checks of ``ucosub.f``, unrolled, each with its own message."""

    def fail(condition: str, text: str, value: str, integer: bool = False) -> None:
        form = "(A, I4)" if integer else "(A, 1PE24.16)"
        out.add(f"IF ({condition}) THEN")
        out.add(f"WRITE (MESAGE, '{form}') {fixed_string(text)}, {value}", 3)
        out.add("GO TO 900", 3)
        out.add("END IF")

    fail("NPAR .LT. NPARS", npar_message(spec), "NPAR", integer=True)
    fail("PAR(1) .LT. 1.0D0 .OR. PAR(1) .GE. 2147483647.0D0 .OR. PAR(1) .NE. AINT(PAR(1))",
         PART_MESSAGE, "PAR(1)")
    out.add("IPART = NINT(PAR(1))")
    for position, variable in enumerate(spec.variables):
        i = spec.code_index(position)
        if spec.two_parts and position == spec.first_part_nvars:
            j = f"PAR({spec.second_part_index})"
            fail(f"{j} .LT. 1.0D0 .OR. {j} .GE. 2147483647.0D0 .OR. {j} .NE. AINT({j}) .OR. "
                 f"{j} .EQ. PAR(1)", second_part_message(spec), j)
            out.add(f"JPART = NINT({j})")
        fail(f"PAR({i}) .NE. {variable.code}.0D0", code_message(spec, i, variable.code),
             f"PAR({i})")
    for parameter in spec.parameters:
        value = f"PAR({parameter.index})"
        if parameter.check == "positive":
            condition = f".NOT. ({value} .GT. 0.0D0 .AND. {value} .LE. BIG)"
        else:
            condition = f".NOT. (ABS({value}) .LE. BIG)"
        fail(condition, parameter_message(parameter.index, parameter.description,
                                          parameter.check), value)
    if spec.component_index:
        value = f"PAR({spec.component_index})"
        condition = " .AND. ".join(f"{value} .NE. {k}.0D0"
                                   for k in range(1, spec.ncomponents + 1))
        fail(condition, component_message(spec), value)
        out.add(f"ICOMP = NINT({value})")


def _legacy_component(out: _FixedLines, program: Program, printer: LegacyPrinter, k: int,
                      indent: int) -> None:
    """The outputs of component k in ``ucosub.f``."""
    branches = []
    zeros = []
    for kind, selector in SCALAR_SELECTORS.items():
        entries = program.of(k, kind)
        if entries:
            branches.append((f"IDRSEL(1) .EQ. {selector}",
                             f"SCALAR = {printer.expression(entries[0].expression)}"))
        else:
            zeros.append(f"IDRSEL(1) .EQ. {selector}")
    if zeros:
        branches.append((" .OR. ".join(zeros), "SCALAR = 0.0D0"))
    for position, (condition, statement) in enumerate(branches):
        out.add(f"{'IF' if position == 0 else 'ELSE IF'} ({condition}) THEN", indent)
        out.add(statement, indent + 3)
    out.add("END IF", indent)
    first = [(selector, program.of(k, kind)) for kind, selector in ARRAY_SELECTORS.items()]
    first = [(selector, entries) for selector, entries in first if entries]
    for position, (selector, entries) in enumerate(first):
        out.add(f"{'IF' if position == 0 else 'ELSE IF'} (IDRSEL(2) .EQ. {selector}) THEN",
                indent)
        for entry in entries:
            out.add(f"ARRAY({entry.row}) = {printer.expression(entry.expression)}", indent + 3)
    if first:
        out.add("END IF", indent)
    second = program.of(k, "dqdq")
    if second:
        out.add("IF (IDRSEL(3) .EQ. 1) THEN", indent)
        for entry in second:
            out.add(f"XMATRX({entry.row}, {entry.column}) = "
                    f"{printer.expression(entry.expression)}", indent + 3)
            if entry.row != entry.column:
                out.add(f"XMATRX({entry.column}, {entry.row}) = "
                        f"XMATRX({entry.row}, {entry.column})", indent + 3)
        out.add("END IF", indent)
