"""The free-form module ``rollcon_gen_<name>``, compiled into the rollcon library."""

from __future__ import annotations

from typing import TYPE_CHECKING

import re

from .derive import ARRAY_SELECTORS, SCALAR_SELECTORS
from .messages import header_lines, npar_message
from .printers import FREE_WIDTH, ModulePrinter, free_string, wrap_comment, wrap_free
from .spec import ConstraintSpec, component_choices

if TYPE_CHECKING:
    from .fortran import Program

__all__ = ["render_module", "HELPER_MODULE", "HELPER_NAMES"]

#: The hand-written module of the checks every generated module shares.
HELPER_MODULE = "rollcon_ucosub_helpers"
#: What a generated module may take from it (it imports those it uses).
HELPER_NAMES = ("read_par_head", "read_second_part", "check_parameter", "read_component",
                "selectors_valid", "idrsel_message", "iflag_message")
#: What a generated module may take from the contract (it imports those it uses).
CONTRACT_NAMES = ("ucovar", "errmes", "iflag_init", "iflag_eval", "scalar_value",
                  "scalar_time_part", "scalar_dt", "scalar_dtt", "array_dq", "array_dtdq",
                  "xmatrx_dqdq")


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
            "ncomponents": f"{stem}_ncomponents", "codes": f"{stem}_codes",
            "time_free": f"{stem}_time_free", "holonomic": f"{stem}_holonomic",
            "component_time_free": f"{stem}_component_time_free",
            "component_holonomic": f"{stem}_component_holonomic"}


def render_module(program: Program) -> str:
    """The free-form module ``rollcon_gen_<name>``, compiled into the library."""
    spec = program.spec
    names = _module_names(spec)
    body = _Lines()
    body.add("contains")
    body.add()
    _module_ucosub(body, program, names)
    body.add()
    _module_par_function(body, spec, names)
    body.add()
    _module_read_par(body, spec, names)
    body.add()
    _module_evaluate(body, program, ModulePrinter())
    body.add()
    body.add(f"end module {names['module']}")
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
    code = "\n".join(line for line in body.lines if not line.lstrip().startswith("!"))
    for module, candidates in (("rollcon_ucosub_contract", CONTRACT_NAMES),
                               (HELPER_MODULE, HELPER_NAMES)):
        used = [name for name in candidates if re.search(rf"\b{name}\b", code)]
        out.add(f"use {module}, only : {', '.join(used)}", 4)
    out.add("implicit none", 4)
    out.add("private", 4)
    out.add()
    out.add(f"public :: {names['ucosub']}, {names['par']}", 4)
    out.add(f"public :: {names['nvars']}, {names['npar']}, {names['ncomponents']}, "
            f"{names['codes']}", 4)
    out.add(f"public :: {names['time_free']}, {names['component_time_free']}, "
            f"{names['holonomic']}, {names['component_holonomic']}", 4)
    out.add()
    _module_constants(out, program, names)
    out.add()
    out.lines.extend(body.lines)
    return out.text()


def _fortran_logicals(values: list[bool]) -> str:
    """``[.true., .false.]``."""
    return "[" + ", ".join(".true." if v else ".false." for v in values) + "]"


def _module_constants(out: _Lines, program: Program, names: dict[str, str]) -> None:
    """The sizes and codes, and what outputs can be non-zero (so a driver may skip calls)."""
    spec = program.spec
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
    components = range(1, spec.ncomponents + 1)
    time_free = [program.derivatives.time_free(k) for k in components]
    holonomic = [program.derivatives.holonomic(k) for k in components]
    which = f" (PAR({spec.component_index}))" if spec.component_index else ""
    out.doc("True when no component has an explicit time: dF/dt, d2F/dt2 (IDRSEL(1) = 3, 4) "
            "and d2F/dt dq_j (IDRSEL(2) = 2) are then identically zero and need not be asked "
            "for, and f(t) (IDRSEL(1) = 2) is a constant", 4)
    out.add(f"logical, parameter :: {names['time_free']} = "
            f"{'.true.' if all(time_free) else '.false.'}", 4)
    out.doc(f"The same, for each component{which}", 4)
    out.add(f"logical, parameter :: {names['component_time_free']}({names['ncomponents']}) = "
            f"{_fortran_logicals(time_free)}", 4)
    out.doc("True when no component depends on a velocity (no velocity code is declared): "
            "every UCON of this routine is a position constraint F(q, t) = 0, and dF/dq_j is "
            "identically zero for every velocity q_j", 4)
    out.add(f"logical, parameter :: {names['holonomic']} = "
            f"{'.true.' if all(holonomic) else '.false.'}", 4)
    out.doc(f"The same, for each component{which}", 4)
    out.add(f"logical, parameter :: {names['component_holonomic']}({names['ncomponents']}) = "
            f"{_fortran_logicals(holonomic)}", 4)


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
    parts = "part, part_j" if spec.two_parts else "part"
    out.add(f"integer :: {parts}, component" if several else f"integer :: {parts}", 8)
    out.add()
    out.add(f"call read_par(par, npar, {parts}, component, message)" if several
            else f"call read_par(par, npar, {parts}, message)", 8)
    out.add("if (allocated(message)) then", 8)
    out.add('call errmes(.true., message, id, "STOP")', 12)
    out.add("return", 12)
    out.add("end if", 8)
    out.add("select case (iflag)", 8)
    out.add("case (iflag_init)", 8)
    if spec.two_parts:
        n1, n2 = spec.first_part_nvars, spec.nvars - spec.first_part_nvars
        out.add(f"call ucovar(id, {names['nvars']}, [spread(part, 1, {n1}), "
                f"spread(part_j, 1, {n2})], {names['nvars']}, {names['codes']})", 12)
    else:
        out.add(f"call ucovar(id, {names['nvars']}, spread(part, 1, {names['nvars']}), "
                f"{names['nvars']}, {names['codes']})", 12)
    out.add("case (iflag_eval)", 8)
    out.add("if (.not. selectors_valid(idrsel)) then", 12)
    out.add('call errmes(.true., idrsel_message, id, "STOP")', 16)
    out.add("return", 16)
    out.add("end if", 12)
    out.add(f"call evaluate({_evaluate_actuals(program)})", 12)
    out.add("case default", 8)
    out.add('call errmes(.true., iflag_message, id, "STOP")', 12)
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
    dummies = (["part", "part_j"] if spec.two_parts else ["part"]) + [
        p.symbol.name for p in spec.parameters]
    if spec.component_index:
        dummies.append("component")
    out.doc("PAR of one UCON statement: part id, the codes, the parameters"
            + (", the component." if spec.component_index else "."), 4)
    out.add(f"pure function {names['par']}({', '.join(dummies)}) result(par)", 4)
    if spec.two_parts:
        out.doc("Part id of the first part's variables, and of the second part's", 8)
        out.add("integer, intent(in) :: part, part_j", 8)
    else:
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
    if spec.two_parts:
        n1 = spec.first_part_nvars
        values = ["real(part, wp)", f"real({names['codes']}(:{n1}), wp)", "real(part_j, wp)",
                  f"real({names['codes']}({n1 + 1}:), wp)"]
    values += [p.symbol.name for p in spec.parameters]
    if spec.component_index:
        values.append("real(component, wp)")
    out.add(f"par = [{', '.join(values)}]", 8)
    out.add(f"end function {names['par']}", 4)


def _module_read_par(out: _Lines, spec: ConstraintSpec, names: dict[str, str]) -> None:
    """``read_par``: every PAR check, in PAR order, through the shared helpers; the words of
    the messages are the spec's."""
    several = spec.ncomponents > 1
    out.doc("Check PAR; message is allocated, and says what was expected, when PAR is wrong.", 4)
    parts = "part, part_j" if spec.two_parts else "part"
    out.add(f"pure subroutine read_par(par, npar, {parts}, component, message)" if several
            else f"pure subroutine read_par(par, npar, {parts}, message)", 4)
    out.doc("Constants of the UCON statement", 8)
    out.add("real(wp), intent(in) :: par(*)", 8)
    out.doc("Number of constants", 8)
    out.add("integer, intent(in) :: npar", 8)
    if spec.two_parts:
        out.doc("Part id of the first part's variables, and of the second part's", 8)
        out.add("integer, intent(out) :: part, part_j", 8)
    else:
        out.doc("Part id of every variable", 8)
        out.add("integer, intent(out) :: part", 8)
    if several:
        out.doc(f"Which component: {component_choices(spec.ncomponents)}", 8)
        out.add("integer, intent(out) :: component", 8)
    out.doc("Allocated when PAR is wrong", 8)
    out.add("character(len=:), allocatable, intent(out) :: message", 8)
    out.add()
    if several:
        out.add("component = 0", 8)
    calls = [f"call read_par_head(par, npar, {names['npar']}, {names['codes']}, "
             f"{free_string(npar_message(spec))}, part, message)"]
    if spec.two_parts:
        n1 = spec.first_part_nvars
        calls = [f"call read_par_head(par, npar, {names['npar']}, {names['codes']}(:{n1}), "
                 f"{free_string(npar_message(spec))}, part, message)",
                 f"call read_second_part(par, {spec.second_part_index}, "
                 f"{names['codes']}({n1 + 1}:), part, part_j, message)"]
    for parameter in spec.parameters:
        positive = ".true." if parameter.check == "positive" else ".false."
        calls.append(f"call check_parameter(par, {parameter.index}, "
                     f"{free_string(parameter.description)}, {positive}, message)")
    if several:
        calls.append(f"call read_component(par, {spec.component_index}, "
                     f"{names['ncomponents']}, {free_string(spec.component_meaning)}, "
                     "component, message)")
    for position, call in enumerate(calls):
        if position:
            out.add("if (allocated(message)) return", 8)
        out.add(call, 8)
    out.add("end subroutine read_par", 4)


def _module_evaluate(out: _Lines, program: Program, printer: ModulePrinter) -> None:
    """``evaluate``: the temporaries, then the selected outputs of the selected component."""
    spec = program.spec
    several = spec.ncomponents > 1
    out.doc("Evaluate what idrsel asks for; entries that are symbolically zero are left "
            "untouched. Its length is that of the derived expressions: straight-line generated "
            "code, one block per selected output.", 4)
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
