"""Printers and templates: the free-form module and the fixed-form ADAMS ``ucosub.f``.

Both files are printed from one common-subexpression elimination over every non-zero output
of every component at once, so they evaluate the same expressions in the same order. The
printers subclass SymPy's ``FCodePrinter`` only to print numbers the project's way (``_wp``
kind suffixes in the module, ``D0`` exponents in ``ucosub.f``) and to leave line wrapping to
this module, which never breaks inside a name, a number or a string.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy
from sympy.printing.fortran import FCodePrinter
from sympy.printing.precedence import precedence

from .derive import ARRAY_SELECTORS, SCALAR_SELECTORS, Derivatives, Entry
from .spec import TIME, ConstraintSpec, component_choices

__all__ = [
    "ModulePrinter",
    "LegacyPrinter",
    "Program",
    "lower",
    "render_module",
    "render_legacy",
    "module_path",
    "legacy_path",
    "wrap_free",
    "wrap_fixed",
]

#: Preferred and hard line lengths of the free-form module (shared/STYLE.md).
FREE_WIDTH = 100
#: Last column of a fixed-form statement.
FIXED_WIDTH = 72
#: Prefix of the common-subexpression temporaries.
CSE_PREFIX = "cse"
#: Largest finite double, for the finiteness checks of ``ucosub.f`` (no IEEE module in F77).
LEGACY_HUGE = "1.7976931348623157D308"


def module_path(spec: ConstraintSpec) -> str:
    """Path of the generated module, relative to the project root."""
    return f"src/rollcon_gen_{spec.name}.f90"


def legacy_path(spec: ConstraintSpec) -> str:
    """Path of the generated ``ucosub.f``, relative to the project root."""
    return f"ucon/adams/{spec.name}/ucosub.f"


class ModulePrinter(FCodePrinter):
    """Free-form Fortran 2008 expressions whose real literals carry the kind ``wp``.

    Integers print as real literals (``2.0_wp*x``) except integer exponents, which stay
    integers so ``x**2`` is a multiplication; rationals print as a quotient of real literals;
    pi and other number symbols as a literal with every digit a double holds.
    """

    def __init__(self) -> None:
        super().__init__({"source_format": "free", "standard": 2008, "name_mangling": False,
                          "precision": 17, "strict": True})

    def real_literal(self, value: float) -> str:
        """Shortest text that reads back as ``value``, with the kind suffix."""
        mantissa, exponent = self._split_float(value)
        return f"{mantissa}e{exponent}_wp" if exponent else f"{mantissa}_wp"

    @staticmethod
    def _split_float(value: float) -> tuple[str, int]:
        """Mantissa with a decimal point and the decimal exponent of Python's repr."""
        text = repr(float(value))
        if text in ("inf", "-inf", "nan"):
            raise ValueError(f"cannot print the non-finite number {text}")
        mantissa, _, exponent = text.partition("e")
        if "." not in mantissa:
            mantissa += ".0"
        return mantissa, int(exponent or 0)

    def expression(self, expr: sympy.Expr) -> str:
        """The Fortran text of one expression, unwrapped."""
        self._not_supported: set[sympy.Basic] = set()
        self._number_symbols: set[tuple[sympy.Basic, sympy.Float]] = set()
        return str(self._print(expr))

    def _print_Float(self, expr: sympy.Float) -> str:
        return self.real_literal(float(expr))

    def _print_Integer(self, expr: sympy.Integer) -> str:
        return self.real_literal(float(int(expr)))

    def _print_Rational(self, expr: sympy.Rational) -> str:
        return (f"{self.real_literal(float(int(expr.p)))}/"
                f"{self.real_literal(float(int(expr.q)))}")

    def _print_NumberSymbol(self, expr: sympy.NumberSymbol) -> str:
        return self.real_literal(float(expr.evalf(20)))

    def _print_Pow(self, expr: sympy.Pow) -> str:
        prec = precedence(expr)
        base, exponent = expr.base, expr.exp
        if exponent == -1:
            return f"{self.real_literal(1.0)}/{self.parenthesize(base, prec)}"
        if exponent == sympy.S.Half:
            return f"sqrt({self._print(base)})"
        if exponent == -sympy.S.Half:
            return f"{self.real_literal(1.0)}/sqrt({self._print(base)})"
        if exponent.is_Integer:
            power = int(exponent)
            text = str(power) if power >= 0 else f"({power})"
            return f"{self.parenthesize(base, prec, strict=True)}**{text}"
        return (f"{self.parenthesize(base, prec, strict=True)}"
                f"**{self.parenthesize(exponent, prec, strict=True)}")


class LegacyPrinter(ModulePrinter):
    """Fixed-form FORTRAN 77 expressions: DOUBLE PRECISION literals with a ``D`` exponent."""

    def __init__(self) -> None:
        FCodePrinter.__init__(self, {"source_format": "fixed", "standard": 77,
                                     "name_mangling": False, "precision": 17, "strict": True})

    def real_literal(self, value: float) -> str:
        """Shortest text that reads back as ``value``, as a DOUBLE PRECISION constant."""
        mantissa, exponent = self._split_float(value)
        return f"{mantissa}D{exponent}"

    def expression(self, expr: sympy.Expr) -> str:
        """The FORTRAN 77 text of one expression, in upper case, unwrapped."""
        return super().expression(expr).upper()


@dataclass(frozen=True)
class Program:
    """What both files evaluate: the temporaries and the entries rewritten in terms of them.

    Attributes:
        derivatives: the entries before elimination.
        temporaries: ``(name, expression)`` in evaluation order.
        entries: the entries of ``derivatives`` with their expressions rewritten.
    """

    derivatives: Derivatives
    temporaries: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    entries: tuple[Entry, ...]

    @property
    def spec(self) -> ConstraintSpec:
        """The spec the program evaluates."""
        return self.derivatives.spec

    @property
    def uses_time(self) -> bool:
        """True when any output depends on the time explicitly."""
        return any(e.expression.has(TIME) for e in self.derivatives.entries)

    def of(self, component: int, output: str) -> tuple[Entry, ...]:
        """Rewritten entries of one output of one component."""
        return tuple(e for e in self.entries if e.component == component and e.output == output)


def lower(derivatives: Derivatives) -> Program:
    """One ``sympy.cse`` over every non-zero output of every component at once."""
    expressions = [entry.expression for entry in derivatives.entries]
    replacements, reduced = sympy.cse(expressions, symbols=sympy.numbered_symbols(CSE_PREFIX),
                                      order="canonical")
    entries = tuple(Entry(e.component, e.output, e.row, e.column, r)
                    for e, r in zip(derivatives.entries, reduced))
    return Program(derivatives, tuple(replacements), entries)


# --- line wrapping --------------------------------------------------------------------------


_OPERATORS = ("// ", "+ ", "- ", ".and. ", ".or. ", ".AND. ", ".OR. ")


def _break_points(text: str) -> list[tuple[int, int]]:
    """Positions where a statement may be split, with a priority (lower is better): a blank
    before a binary operator (0), any other blank (1), after ``(``, a single ``*`` or a single
    ``/`` (2). Never inside a string literal."""
    points = []
    quote = ""
    for i, char in enumerate(text):
        if quote:
            if char == quote:
                quote = ""
            continue
        if char in "'\"":
            quote = char
        elif char == " ":
            points.append((i, 0 if text.startswith(_OPERATORS, i + 1) else 1))
        elif char == "(" or (char in "*/" and text[i - 1:i] != char
                             and text[i + 1:i + 2] != char):
            points.append((i + 1, 2))
    return points


def _split(text: str, first: int, rest: int) -> list[str]:
    """Split ``text`` into pieces of at most ``first`` then ``rest`` characters, each cut at
    the best break point in the last 40 % of the room, or at the last one that fits."""
    pieces = []
    width = first
    while len(text) > width:
        points = [(p, priority) for p, priority in _break_points(text) if 0 < p <= width]
        if not points:
            raise ValueError(f"cannot wrap: {text[:60]}...")
        window = [(priority, -p) for p, priority in points if p > 0.6 * width]
        cut = -min(window)[1] if window else points[-1][0]
        pieces.append(text[:cut].rstrip())
        text = text[cut:].lstrip()
        width = rest
    pieces.append(text)
    return pieces


def wrap_free(statement: str, indent: int, width: int = FREE_WIDTH) -> list[str]:
    """A free-form statement as lines of at most ``width``: ``&`` ends a continued line and
    starts the next, four columns deeper."""
    lead = " " * indent
    pieces = _split(statement, width - indent - 2, width - indent - 8)
    lines = [lead + pieces[0]]
    for piece in pieces[1:]:
        lines[-1] += " &"
        lines.append(f"{lead}    & {piece}")
    return lines


def wrap_fixed(statement: str, indent: int) -> list[str]:
    """A fixed-form statement in columns 7-72, continued with ``&`` in column 6."""
    lead = " " * (6 + indent)
    pieces = _split(statement, FIXED_WIDTH - 6 - indent, FIXED_WIDTH - 6 - indent - 6)
    lines = [lead + pieces[0]]
    for piece in pieces[1:]:
        lines.append(f"     &{' ' * (indent + 6)}{piece}")
    return lines


def wrap_comment(text: str, lead: str, width: int) -> list[str]:
    """A comment paragraph as lines of at most ``width`` starting with ``lead``."""
    words = text.split()
    lines: list[str] = []
    line = lead.rstrip()
    for word in words:
        candidate = f"{line} {word}" if line != lead.rstrip() else f"{lead}{word}"
        if len(candidate) > width and line != lead.rstrip():
            lines.append(line)
            line = f"{lead}{word}"
        else:
            line = candidate
    lines.append(line)
    return lines


def _chunks(text: str, size: int) -> list[str]:
    """Split message text after blanks into chunks of at most about ``size`` characters;
    joined again they give ``text`` exactly."""
    chunks: list[str] = []
    for word in re.findall(r"\S+\s*|\s+", text):
        if chunks and len(chunks[-1]) + len(word) <= size:
            chunks[-1] += word
        else:
            chunks.append(word)
    return chunks


def free_string(text: str) -> str:
    """A free-form character expression: double-quoted chunks joined by ``//``."""
    return " // ".join('"' + c.replace('"', '""') + '"' for c in _chunks(text, 70))


def fixed_string(text: str) -> str:
    """A FORTRAN 77 character expression: apostrophe-quoted chunks joined by ``//``."""
    return " // ".join("'" + c.replace("'", "''") + "'" for c in _chunks(text, 48))


# --- what both files say ---------------------------------------------------------------------


def header_lines(spec: ConstraintSpec) -> list[str]:
    """The two lines every generated file starts with, without comment markers."""
    return [f"Generated by ucon from {spec.source} -- do not edit.",
            "Regenerate with: python -m ucon write"]


def npar_message(spec: ConstraintSpec) -> str:
    """Start of the message for a short PAR; the caller appends NPAR."""
    def counted(number: int, noun: str) -> str:
        return f"{number} {noun}" + ("s" if number != 1 else "")

    parts = ["part id", counted(spec.nvars, "code")]
    if len(spec.parameters) == 1:
        parts.append(spec.parameters[0].meaning)
    elif spec.parameters:
        parts.append(counted(len(spec.parameters), "parameter"))
    if spec.component_index:
        parts.append(spec.component_meaning)
    return f"{spec.title} needs NPAR >= {spec.npar} ({', '.join(parts)}), got NPAR ="


def codes_range(spec: ConstraintSpec) -> str:
    """``"PAR(2:9)"``, or ``"PAR(2)"`` for a single variable."""
    return "PAR(2)" if spec.nvars == 1 else f"PAR(2:{1 + spec.nvars})"


def code_message(spec: ConstraintSpec, index: int, code: int) -> str:
    """Message for a wrong code at PAR(index); the caller appends the value found."""
    codes = " ".join(str(v.code) for v in spec.variables)
    return f"PAR({index}) must be code {code} (codes {codes} in {codes_range(spec)}), got"


def parameter_message(index: int, description: str, check: str) -> str:
    """Message for a parameter that fails its check; the caller appends the value found."""
    rule = "positive and finite" if check == "positive" else "finite"
    return f"PAR({index}) ({description}) must be {rule}, got"


def component_message(spec: ConstraintSpec) -> str:
    """Message for a bad component number; the caller appends the value found."""
    return (f"PAR({spec.component_index}) ({spec.component_meaning}) must be "
            f"{component_choices(spec.ncomponents)}, got")


PART_MESSAGE = "PAR(1) (part id) must be a positive whole number, got"
IFLAG_MESSAGE = "IFLAG must be 3 (initialise) or 0 (evaluate)"
IDRSEL_MESSAGE = "IDRSEL must be (0..4, 0..2, 0..1)"


# --- the free-form module -------------------------------------------------------------------


class _Lines:
    """Accumulates wrapped free-form lines."""

    def __init__(self) -> None:
        self.lines: list[str] = []

    def add(self, statement: str = "", indent: int = 0) -> None:
        """One statement (wrapped) or an empty line."""
        if statement:
            self.lines.extend(wrap_free(statement, indent))
        else:
            self.lines.append("")

    def doc(self, text: str, indent: int) -> None:
        """A ``!>`` documentation paragraph."""
        self.lines.extend(wrap_comment(text, " " * indent + "!> ", FREE_WIDTH))

    def text(self) -> str:
        """The file's text, with a final newline."""
        return "\n".join(self.lines) + "\n"


def _module_names(spec: ConstraintSpec) -> dict[str, str]:
    """Public names of the module."""
    stem = spec.name
    return {"module": f"rollcon_gen_{stem}", "ucosub": f"{stem}_ucosub", "par": f"{stem}_par",
            "nvars": f"{stem}_nvars", "npar": f"{stem}_npar",
            "ncomponents": f"{stem}_ncomponents", "codes": f"{stem}_codes"}


def render_module(program: Program) -> str:
    """The free-form module ``rollcon_gen_<name>``, compiled into the library."""
    spec = program.spec
    names = _module_names(spec)
    printer = ModulePrinter()
    out = _Lines()
    for line in header_lines(spec):
        out.add(f"! {line}")
    out.doc(f"{spec.title[0].upper()}{spec.title[1:]} as an ADAMS UCOSUB. {spec.summary}", 0)
    out.doc("", 0)
    for index, meaning in spec.par_layout():
        out.doc(f"PAR({index}): {meaning}", 0)
    for k, constraint in enumerate(spec.constraints, start=1):
        out.doc(f"F{k}: {constraint.meaning}", 0)
    out.add(f"module {names['module']}")
    out.add("use rollcon_kinds, only : wp", 4)
    out.add("use rollcon_text, only : to_text", 4)
    out.add("use rollcon_ucon, only : ucovar, errmes, iflag_init, iflag_eval, scalar_none, "
            "scalar_value, scalar_time_part, scalar_dt, scalar_dtt, array_none, array_dq, "
            "array_dtdq, xmatrx_none, xmatrx_dqdq", 4)
    out.add("use, intrinsic :: ieee_arithmetic, only : ieee_is_finite", 4)
    out.add("implicit none", 4)
    out.add("private", 4)
    out.add()
    out.add(f"public :: {names['ucosub']}, {names['par']}", 4)
    out.add(f"public :: {names['nvars']}, {names['npar']}, {names['ncomponents']}, "
            f"{names['codes']}", 4)
    out.add()
    out.doc("Number of variables declared with UCOVAR", 4)
    out.add(f"integer, parameter :: {names['nvars']} = {spec.nvars}", 4)
    out.doc("Number of constants in FUNCTION=USER(...) (layout in the module header)", 4)
    out.add(f"integer, parameter :: {names['npar']} = {spec.npar}", 4)
    out.doc("Number of constraint components (UCON statements sharing this routine)", 4)
    out.add(f"integer, parameter :: {names['ncomponents']} = {spec.ncomponents}", 4)
    out.doc("Codes of " + ", ".join(v.symbol.name for v in spec.variables) + ", in UCOVAR order",
            4)
    out.add(f"integer, parameter :: {names['codes']}({names['nvars']}) = ["
            + ", ".join(str(v.code) for v in spec.variables) + "]", 4)
    out.add()
    out.add("contains")
    out.add()
    _module_ucosub(out, program, names)
    out.add()
    _module_par_function(out, spec, names)
    out.add()
    _module_read_par(out, spec, names)
    out.add()
    _module_selectors(out)
    out.add()
    _module_is_whole(out)
    out.add()
    _module_evaluate(out, program, printer)
    out.add()
    out.add(f"end module {names['module']}")
    return out.text()


def _module_ucosub(out: _Lines, program: Program, names: dict[str, str]) -> None:
    """The public UCOSUB: check PAR, declare or evaluate."""
    spec = program.spec
    out.doc(f"The {spec.title} UCOSUB, with ADAMS's calling sequence (see ucosub_interface "
            "in rollcon_ucon). Bad PAR, IFLAG or IDRSEL are reported through ERRMES and leave "
            "the outputs untouched.", 4)
    out.add(f"subroutine {names['ucosub']}(id, time, q, par, npar, idrsel, iflag, scalar, "
            "array, xmatrx)", 4)
    time_doc = "Simulation time [s]" if program.uses_time else \
        "Simulation time [s] (the constraint does not depend on it)"
    arguments = [
        ("UCON statement id", "integer, intent(in) :: id"),
        (time_doc, "real(wp), intent(in) :: time"),
        ("Variables in UCOVAR order: " + ", ".join(
            f"{v.symbol.name} {v.description.split()[-1]}" for v in spec.variables),
         "real(wp), intent(in) :: q(30)"),
        ("Constants of the UCON statement (layout in the module header)",
         "real(wp), intent(in) :: par(*)"),
        ("Number of constants", "integer, intent(in) :: npar"),
        ("Output selectors", "integer, intent(in) :: idrsel(3)"),
        ("3: declare the variables with UCOVAR; 0: evaluate", "integer, intent(in) :: iflag"),
        ("F, f(t), dF/dt or d2F/dt2, as idrsel(1) asks", "real(wp), intent(inout) :: scalar"),
        ("dF/dq_j or d2F/dt dq_j, as idrsel(2) asks", "real(wp), intent(inout) :: array(30)"),
        ("d2F/dq_i dq_j (both triangles), as idrsel(3) asks",
         "real(wp), intent(inout) :: xmatrx(30, 30)"),
    ]
    for doc, declaration in arguments:
        out.doc(doc, 8)
        out.add(declaration, 8)
    out.add("character(len=:), allocatable :: message", 8)
    several = spec.ncomponents > 1
    out.add("integer :: part, component" if several else "integer :: part", 8)
    out.add()
    out.add("call read_par(par, npar, part, component, message)" if several
            else "call read_par(par, npar, part, message)", 8)
    out.add("if (allocated(message)) then", 8)
    out.add('call errmes(.true., message, id, "STOP")', 12)
    out.add("return", 12)
    out.add("end if", 8)
    out.add("select case (iflag)", 8)
    out.add("case (iflag_init)", 8)
    out.add(f"call ucovar(id, {names['nvars']}, spread(part, 1, {names['nvars']}), "
            f"{names['nvars']}, {names['codes']})", 12)
    out.add("case (iflag_eval)", 8)
    out.add("if (.not. selectors_valid(idrsel)) then", 12)
    out.add(f'call errmes(.true., "{IDRSEL_MESSAGE}", id, "STOP")', 16)
    out.add("return", 16)
    out.add("end if", 12)
    out.add(f"call evaluate({_evaluate_actuals(program)})", 12)
    out.add("case default", 8)
    out.add(f'call errmes(.true., "{IFLAG_MESSAGE}", id, "STOP")', 12)
    out.add("end select", 8)
    out.add(f"end subroutine {names['ucosub']}", 4)


def _evaluate_actuals(program: Program) -> str:
    """Argument list of the call to ``evaluate``."""
    names = (["time"] if program.uses_time else []) + ["q"]
    if program.spec.parameters:
        names.append("par")
    if program.spec.ncomponents > 1:
        names.append("component")
    return ", ".join(names + ["idrsel", "scalar", "array", "xmatrx"])


def _module_par_function(out: _Lines, spec: ConstraintSpec, names: dict[str, str]) -> None:
    """``<name>_par``: the PAR list of one UCON statement."""
    dummies = ["part"] + [p.symbol.name for p in spec.parameters]
    if spec.component_index:
        dummies.append("component")
    out.doc("PAR of one UCON statement: part id, the codes, the parameters"
            + (", the component." if spec.component_index else "."), 4)
    out.add(f"pure function {names['par']}({', '.join(dummies)}) result(par)", 4)
    out.doc("Part id of every variable", 8)
    out.add("integer, intent(in) :: part", 8)
    for parameter in spec.parameters:
        out.doc(parameter.description[0].upper() + parameter.description[1:], 8)
        out.add(f"real(wp), intent(in) :: {parameter.symbol.name}", 8)
    if spec.component_index:
        out.doc(f"{spec.component_meaning[0].upper()}{spec.component_meaning[1:]}: "
                f"{component_choices(spec.ncomponents)}", 8)
        out.add("integer, intent(in) :: component", 8)
    out.add(f"real(wp) :: par({names['npar']})", 8)
    out.add()
    values = ["real(part, wp)", f"real({names['codes']}, wp)"]
    values += [p.symbol.name for p in spec.parameters]
    if spec.component_index:
        values.append("real(component, wp)")
    out.add(f"par = [{', '.join(values)}]", 8)
    out.add(f"end function {names['par']}", 4)


def _module_read_par(out: _Lines, spec: ConstraintSpec, names: dict[str, str]) -> None:
    """``read_par``: every PAR check, in PAR order, with the message that names the entry."""
    several = spec.ncomponents > 1
    out.doc("Check PAR; message is allocated, and says what was expected, when PAR is wrong.", 4)
    out.add("pure subroutine read_par(par, npar, part, component, message)" if several
            else "pure subroutine read_par(par, npar, part, message)", 4)
    out.doc("Constants of the UCON statement", 8)
    out.add("real(wp), intent(in) :: par(*)", 8)
    out.doc("Number of constants", 8)
    out.add("integer, intent(in) :: npar", 8)
    out.doc("Part id of every variable", 8)
    out.add("integer, intent(out) :: part", 8)
    if several:
        out.doc(f"Which component: {component_choices(spec.ncomponents)}", 8)
        out.add("integer, intent(out) :: component", 8)
    out.doc("Allocated when PAR is wrong", 8)
    out.add("character(len=:), allocatable, intent(out) :: message", 8)
    out.add("integer :: i", 8)
    out.add()
    out.add("part = 0", 8)
    if several:
        out.add("component = 0", 8)
    out.add(f"if (npar < {names['npar']}) then", 8)
    out.add(f"message = {free_string(npar_message(spec) + ' ')} // to_text(npar)", 12)
    out.add("return", 12)
    out.add("end if", 8)
    out.add("if (.not. is_whole(par(1)) .or. par(1) < 1.0_wp) then", 8)
    out.add(f"message = {free_string(PART_MESSAGE + ' ')} // to_text(par(1))", 12)
    out.add("return", 12)
    out.add("end if", 8)
    out.add("part = nint(par(1))", 8)
    out.add(f"do i = 1, {names['nvars']}", 8)
    out.add(f"if (par(1 + i) /= real({names['codes']}(i), wp)) then", 12)
    codes = " ".join(str(v.code) for v in spec.variables)
    out.add(f'message = "PAR(" // to_text(1 + i) // ") must be code " // '
            f'to_text({names["codes"]}(i)) // '
            f'{free_string(f" (codes {codes} in {codes_range(spec)}), got ")}'
            " // to_text(par(1 + i))", 16)
    out.add("return", 16)
    out.add("end if", 12)
    out.add("end do", 8)
    for parameter in spec.parameters:
        value = f"par({parameter.index})"
        if parameter.check == "positive":
            condition = f".not. ieee_is_finite({value}) .or. {value} <= 0.0_wp"
        else:
            condition = f".not. ieee_is_finite({value})"
        text = parameter_message(parameter.index, parameter.description, parameter.check)
        out.add(f"if ({condition}) then", 8)
        out.add(f"message = {free_string(text + ' ')} // to_text({value})", 12)
        out.add("return", 12)
        out.add("end if", 8)
    if several:
        value = f"par({spec.component_index})"
        choices = ", ".join(f"{k}.0_wp" for k in range(1, spec.ncomponents + 1))
        out.add(f"if (.not. any({value} == [{choices}])) then", 8)
        out.add(f"message = {free_string(component_message(spec) + ' ')} // to_text({value})",
                12)
        out.add("return", 12)
        out.add("end if", 8)
        out.add(f"component = nint({value})", 8)
    out.add("end subroutine read_par", 4)


def _module_selectors(out: _Lines) -> None:
    """``selectors_valid``: IDRSEL within the table of DESIGN section 2."""
    out.doc("True when every selector is one the contract defines.", 4)
    out.add("pure function selectors_valid(idrsel) result(valid)", 4)
    out.doc("Output selectors", 8)
    out.add("integer, intent(in) :: idrsel(3)", 8)
    out.add("logical :: valid", 8)
    out.add()
    out.add("valid = idrsel(1) >= scalar_none .and. idrsel(1) <= scalar_dtt "
            ".and. idrsel(2) >= array_none .and. idrsel(2) <= array_dtdq "
            ".and. idrsel(3) >= xmatrx_none .and. idrsel(3) <= xmatrx_dqdq", 8)
    out.add("end function selectors_valid", 4)


def _module_is_whole(out: _Lines) -> None:
    """``is_whole``: the part id check."""
    out.doc("True for a finite real with no fractional part, small enough for a default "
            "integer.", 4)
    out.add("elemental function is_whole(value) result(whole)", 4)
    out.doc("Value to test", 8)
    out.add("real(wp), intent(in) :: value", 8)
    out.add("logical :: whole", 8)
    out.add()
    out.add("whole = ieee_is_finite(value)", 8)
    out.add("if (whole) whole = abs(value) < real(huge(1), wp) .and. value == aint(value)", 8)
    out.add("end function is_whole", 4)


def _module_evaluate(out: _Lines, program: Program, printer: ModulePrinter) -> None:
    """``evaluate``: the temporaries, then the selected outputs of the selected component."""
    spec = program.spec
    several = spec.ncomponents > 1
    out.doc("Evaluate what idrsel asks for; entries that are symbolically zero are left "
            "untouched.", 4)
    out.add(f"pure subroutine evaluate({_evaluate_actuals(program)})", 4)
    if program.uses_time:
        out.doc("Simulation time [s]", 8)
        out.add("real(wp), intent(in) :: time", 8)
    out.doc("Variables in UCOVAR order", 8)
    out.add("real(wp), intent(in) :: q(:)", 8)
    if spec.parameters:
        out.doc("Constants of the UCON statement, already checked", 8)
        out.add("real(wp), intent(in) :: par(*)", 8)
    if several:
        out.doc("Which component", 8)
        out.add("integer, intent(in) :: component", 8)
    out.doc("Output selectors", 8)
    out.add("integer, intent(in) :: idrsel(3)", 8)
    out.doc("Selected scalar", 8)
    out.add("real(wp), intent(inout) :: scalar", 8)
    out.doc("Selected first partials", 8)
    out.add("real(wp), intent(inout) :: array(:)", 8)
    out.doc("Selected second partials", 8)
    out.add("real(wp), intent(inout) :: xmatrx(:, :)", 8)
    out.add("real(wp) :: " + ", ".join(s.name for s in spec.symbols), 8)
    if program.temporaries:
        out.add("real(wp) :: " + ", ".join(t.name for t, _ in program.temporaries), 8)
    out.add()
    for i, variable in enumerate(spec.variables, start=1):
        out.add(f"{variable.symbol.name} = q({i})", 8)
    for parameter in spec.parameters:
        out.add(f"{parameter.symbol.name} = par({parameter.index})", 8)
    for name, expression in program.temporaries:
        out.add(f"{name.name} = {printer.expression(expression)}", 8)
    indent = 8
    if several:
        out.add("select case (component)", 8)
    for k in range(1, spec.ncomponents + 1):
        if several:
            out.add(f"case ({k})" if k < spec.ncomponents else "case default", 8)
            indent = 12
        _module_component(out, program, printer, k, indent)
    if several:
        out.add("end select", 8)
    out.add("end subroutine evaluate", 4)


def _module_component(out: _Lines, program: Program, printer: ModulePrinter, k: int,
                      indent: int) -> None:
    """The outputs of component k."""
    selector_names = {"value": "scalar_value", "time_part": "scalar_time_part",
                      "dt": "scalar_dt", "dtt": "scalar_dtt"}
    out.add("select case (idrsel(1))", indent)
    zero_kinds = []
    for kind in SCALAR_SELECTORS:
        entries = program.of(k, kind)
        if entries:
            out.add(f"case ({selector_names[kind]})", indent)
            out.add(f"scalar = {printer.expression(entries[0].expression)}", indent + 4)
        else:
            zero_kinds.append(selector_names[kind])
    if zero_kinds:
        out.add(f"case ({', '.join(zero_kinds)})", indent)
        out.add("scalar = 0.0_wp", indent + 4)
    out.add("end select", indent)
    first = [(kind, program.of(k, kind)) for kind in ARRAY_SELECTORS]
    first = [(kind, entries) for kind, entries in first if entries]
    for position, (kind, entries) in enumerate(first):
        keyword = "if" if position == 0 else "else if"
        out.add(f"{keyword} (idrsel(2) == {'array_dq' if kind == 'dq' else 'array_dtdq'}) then",
                indent)
        for entry in entries:
            out.add(f"array({entry.row}) = {printer.expression(entry.expression)}", indent + 4)
    if first:
        out.add("end if", indent)
    second = program.of(k, "dqdq")
    if second:
        out.add("if (idrsel(3) == xmatrx_dqdq) then", indent)
        for entry in second:
            out.add(f"xmatrx({entry.row}, {entry.column}) = "
                    f"{printer.expression(entry.expression)}", indent + 4)
            if entry.row != entry.column:
                out.add(f"xmatrx({entry.column}, {entry.row}) = "
                        f"xmatrx({entry.row}, {entry.column})", indent + 4)
        out.add("end if", indent)


# --- the fixed-form ucosub.f ------------------------------------------------------------------


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
    out.add("INTEGER LPARTS(NVARS), LVARS(NVARS), IPART, I" + (", ICOMP" if several else ""))
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
    texts += [code_message(spec, i, v.code) for i, v in enumerate(spec.variables, start=2)]
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
    for i, variable in enumerate(spec.variables, start=2):
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

