"""The free-form module ``rollcon_gen_<name>``, compiled into the rollcon library."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .derive import ARRAY_SELECTORS, SCALAR_SELECTORS
from .messages import (IDRSEL_MESSAGE, IFLAG_MESSAGE, PART_MESSAGE, codes_range,
                       component_message, header_lines, npar_message, parameter_message)
from .printers import FREE_WIDTH, ModulePrinter, free_string, wrap_comment, wrap_free
from .spec import ConstraintSpec, component_choices

if TYPE_CHECKING:
    from .fortran import Program

__all__ = ["render_module"]


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
    out.add("use rollcon_ucosub_contract, only : ucovar, errmes, iflag_init, iflag_eval, scalar_none, "
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
            "in rollcon_ucosub_contract). Bad PAR, IFLAG or IDRSEL are reported through ERRMES and leave "
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
