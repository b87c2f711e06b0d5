"""Constraint specs: what a file in ``ucon/specs/`` declares, and the checks it must pass.

A spec names its variables by ADAMS code, its parameters by PAR index (with meaning and
units), and one or more constraint expressions F(q, t). The PAR layout is the paper's for
every spec of one part (docs/design.md §5)::

    PAR(1)                  part id of every variable
    PAR(2 .. m+1)           the m variable codes, in declaration order
    PAR(m+2 .. m+p+1)       the p physical parameters, in declaration order
    PAR(m+p+2)              which constraint component (only when there are several)

A spec of two parts (a joint between two parts: some variables declared with ``part=2``,
after those of the first part) has the second part's id and codes after the first's::

    PAR(1)                  part id of the first part's m1 variables
    PAR(2 .. m1+1)          their codes
    PAR(m1+2)               part id of the second part's m2 variables (not PAR(1))
    PAR(m1+3 .. m1+m2+2)    their codes
    PAR(m+3 ..)             the parameters, then the component (m = m1 + m2)

:func:`validate` rejects anything ADAMS would not accept, or the generator could not print,
with a :class:`ValueError` whose message names the spec and the offending item.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy

from .rules import (CODE_NAMES, MAX_PAR, MAX_SPEC_NAME, MAX_VARIABLES, PARAMETER_CHECKS,
                    RESERVED_NAMES, RESERVED_SPEC_NAMES, SUPPORTED_FUNCTIONS)

__all__ = [
    "TIME",
    "CODE_NAMES",
    "MAX_VARIABLES",
    "MAX_PAR",
    "Variable",
    "Parameter",
    "Constraint",
    "ConstraintSpec",
    "validate",
]

#: The simulation time, the only symbol besides variables and parameters a spec may use.
TIME = sympy.Symbol("time", real=True)

_NAME = re.compile(r"[a-z][a-z0-9_]*\Z")
_CSE_NAME = re.compile(r"cse[0-9]+\Z")
_SPEC_NAME = re.compile(r"[a-z][a-z0-9_]*\Z")


@dataclass(frozen=True)
class Variable:
    """One variable the routine declares with UCOVAR.

    Attributes:
        symbol: the SymPy symbol standing for it in the constraints; its name becomes the
            Fortran local that holds ``Q(i)``.
        code: its ADAMS code (11-16 displacements, 21-26 velocities).
        part: 1 for a variable of the part in PAR(1), 2 for one of the second part (a spec
            of two parts; its variables come after the first part's).
    """

    symbol: sympy.Symbol
    code: int
    part: int = 1

    @property
    def is_velocity(self) -> bool:
        """True for a velocity code (21-26)."""
        return 21 <= self.code <= 26

    @property
    def description(self) -> str:
        """Readable name with units, e.g. ``"Xdot [m/s]"``."""
        name, units = CODE_NAMES.get(self.code, (f"code {self.code}", "?"))
        return f"{name} [{units}]"


@dataclass(frozen=True)
class Parameter:
    """One physical constant of the UCON statement, read from ``PAR(index)``.

    Attributes:
        symbol: the SymPy symbol standing for it; its name becomes the Fortran local.
        index: its PAR index (the layout of the module docstring fixes which one it must be).
        meaning: what it is, e.g. ``"disk radius R"``.
        units: its units, e.g. ``"m"``.
        check: ``"positive"`` (positive and finite) or ``"finite"``.
    """

    symbol: sympy.Symbol
    index: int
    meaning: str
    units: str
    check: str = "finite"

    @property
    def description(self) -> str:
        """Meaning with units, e.g. ``"disk radius R [m]"``."""
        return f"{self.meaning} [{self.units}]"


@dataclass(frozen=True)
class Constraint:
    """One constraint component F(q, t) = 0.

    Attributes:
        expression: F, in terms of the spec's variables, parameters and :data:`TIME`.
        meaning: what F measures, e.g. ``"X velocity of the disk's material contact point"``.
    """

    expression: sympy.Expr
    meaning: str


@dataclass(frozen=True)
class ConstraintSpec:
    """A constraint ADAMS accepts as a UCON, stated symbolically.

    Attributes:
        name: file stem of the spec and stem of every generated name (``rolling_disk``).
        title: short noun phrase for messages (``"rolling disk"``).
        summary: one sentence on what the constraint enforces.
        variables: the declared variables, in UCOVAR order.
        parameters: the physical constants, in PAR order.
        constraints: one or more components; several share one UCOSUB and PAR picks one.
        component_meaning: what the component number selects (``"no-slip component"``).
        simplify: run SymPy's simplify on every derived entry (the default). False keeps the
            entries as differentiated: for specs whose components are sums of products of
            sines, cosines and parameters already (the joint primitives), where simplify
            costs minutes per spec and shortens little; the one cse still shares their terms.
        origin: the spec file as the user named it, for a spec outside ``ucon/specs/``
            (``python -m ucon write PATH/spec.py``); "" for the catalog's.
        command: the command that regenerates the spec's files, for their header.
    """

    name: str
    title: str
    summary: str
    variables: tuple[Variable, ...]
    parameters: tuple[Parameter, ...]
    constraints: tuple[Constraint, ...]
    component_meaning: str = "constraint component"
    simplify: bool = True
    origin: str = ""
    command: str = "python -m ucon write"

    @property
    def source(self) -> str:
        """Path of the spec file: relative to the project root for the catalog's, as the user
        named it for one outside."""
        return self.origin or f"ucon/specs/{self.name}.py"

    @property
    def nvars(self) -> int:
        """Number of variables."""
        return len(self.variables)

    @property
    def ncomponents(self) -> int:
        """Number of constraint components."""
        return len(self.constraints)

    @property
    def two_parts(self) -> bool:
        """True when some variable belongs to the second part."""
        return any(v.part == 2 for v in self.variables)

    @property
    def first_part_nvars(self) -> int:
        """Number of variables of the part in PAR(1)."""
        return sum(1 for v in self.variables if v.part == 1)

    @property
    def second_part_index(self) -> int:
        """PAR index of the second part's id, 0 for a spec of one part."""
        return 2 + self.first_part_nvars if self.two_parts else 0

    def code_index(self, position: int) -> int:
        """PAR index of the code of variable ``position`` (0-based, declaration order)."""
        if position < self.first_part_nvars:
            return 2 + position
        return self.second_part_index + 1 + position - self.first_part_nvars

    @property
    def first_parameter_index(self) -> int:
        """PAR index of the first physical parameter."""
        return 2 + self.nvars + (1 if self.two_parts else 0)

    @property
    def component_index(self) -> int:
        """PAR index of the component number, 0 when there is a single component."""
        if self.ncomponents == 1:
            return 0
        return self.first_parameter_index + len(self.parameters)

    @property
    def npar(self) -> int:
        """Number of PAR entries the routine needs."""
        return (1 + self.nvars + len(self.parameters) + (1 if self.ncomponents > 1 else 0)
                + (1 if self.two_parts else 0))

    @property
    def symbols(self) -> tuple[sympy.Symbol, ...]:
        """Variables, then parameters: the declared symbols in a fixed order."""
        return tuple(v.symbol for v in self.variables) + tuple(
            p.symbol for p in self.parameters
        )

    def par_layout(self) -> list[tuple[str, str]]:
        """Rows ``(PAR index or range, what it holds)`` describing the PAR layout."""
        codes = " ".join(str(v.code) for v in self.variables)
        rows = [("1", "part id"), (f"2:{1 + self.nvars}", f"codes {codes}")]
        if self.nvars == 1:
            rows[1] = ("2", f"code {codes}")
        if self.two_parts:
            n1 = self.first_part_nvars
            first = " ".join(str(v.code) for v in self.variables[:n1])
            second = " ".join(str(v.code) for v in self.variables[n1:])
            j = self.second_part_index
            rows = [("1", "part id of the first part"), (f"2:{1 + n1}", f"codes {first}"),
                    (str(j), "part id of the second part (not PAR(1))"),
                    (f"{j + 1}:{j + self.nvars - n1}", f"codes {second}")]
        for parameter in self.parameters:
            rule = "> 0" if parameter.check == "positive" else "finite"
            rows.append((str(parameter.index), f"{parameter.description}, {rule}"))
        if self.component_index:
            rows.append((str(self.component_index),
                         f"{self.component_meaning}: {component_choices(self.ncomponents)}"))
        return rows


def component_choices(count: int) -> str:
    """``"1, 2 or 3"`` for three components, ``"1 or 2"`` for two."""
    numbers = [str(k) for k in range(1, count + 1)]
    if count == 1:
        return "1"
    return ", ".join(numbers[:-1]) + " or " + numbers[-1]


def validate(spec: ConstraintSpec) -> None:
    """Check that ``spec`` states a constraint ADAMS accepts and the generator can print.

    Raises:
        ValueError: naming the spec and the offending item, for: a malformed or taken name,
            no or more than 30 variables, an unknown or repeated code, a parameter at the wrong
            PAR index, more than 30 PAR entries, a symbol that is not a declared variable,
            parameter or the time, a function the printers do not support, a constraint that is
            not linear in the velocities (ADAMS's rule), or a declared symbol no constraint uses.
    """
    where = f"spec '{spec.name}'"
    if not isinstance(spec.name, str) or not _SPEC_NAME.match(spec.name):
        raise ValueError(f"{where}: name must be lowercase letters, digits and underscores, "
                         "starting with a letter")
    if len(spec.name) > MAX_SPEC_NAME:
        raise ValueError(f"{where}: name has {len(spec.name)} characters; at most "
                         f"{MAX_SPEC_NAME} keep the header of ucosub.f within column 72")
    if spec.name in RESERVED_SPEC_NAMES:
        raise ValueError(f"{where}: the name is taken ({RESERVED_SPEC_NAMES[spec.name]}); "
                         "choose another")
    _validate_text(spec, where)
    _validate_variables(spec, where)
    _validate_parameters(spec, where)
    _validate_names(spec, where)
    if spec.npar > MAX_PAR:
        raise ValueError(
            f"{where}: needs NPAR = {spec.npar} (part id, {spec.nvars} codes, "
            f"{len(spec.parameters)} parameters"
            + (", component" if spec.ncomponents > 1 else "")
            + f"); FUNCTION=USER takes at most {MAX_PAR} constants")
    if not spec.constraints:
        raise ValueError(f"{where}: declares no constraint")
    for number, constraint in enumerate(spec.constraints, start=1):
        _validate_constraint(spec, f"{where}, constraint {number}", constraint.expression)
    _validate_all_used(spec, where)


def _validate_text(spec: ConstraintSpec, where: str) -> None:
    """Descriptions are printed into Fortran comments and messages: one line of ASCII each."""
    texts = [("title", spec.title), ("summary", spec.summary),
             ("component_meaning", spec.component_meaning)]
    texts += [(f"meaning of parameter {i}", p.meaning) for i, p in enumerate(spec.parameters, 1)]
    texts += [(f"units of parameter {i}", p.units) for i, p in enumerate(spec.parameters, 1)]
    texts += [(f"meaning of constraint {i}", c.meaning)
              for i, c in enumerate(spec.constraints, 1)]
    for label, text in texts:
        if not isinstance(text, str) or not text.strip() or not text.isascii() \
                or not text.isprintable():
            raise ValueError(f"{where}: {label} must be one non-empty line of printable ASCII, "
                             f"got {text!r}")


def _validate_variables(spec: ConstraintSpec, where: str) -> None:
    """Count, codes and symbols of the variables."""
    if not spec.variables:
        raise ValueError(f"{where}: declares no variable")
    if len(spec.variables) > MAX_VARIABLES:
        raise ValueError(f"{where}: declares {len(spec.variables)} variables; UCOVAR accepts "
                         f"at most {MAX_VARIABLES}")
    seen: dict[tuple[int, int], str] = {}
    parts = [v.part for v in spec.variables]
    if any(part not in (1, 2) for part in parts) or parts != sorted(parts) or parts[0] != 1:
        raise ValueError(f"{where}: variables must be of part 1, then (a spec of two parts) "
                         "of part 2, each part's in a block; got parts "
                         + " ".join(str(p) for p in parts))
    for variable in spec.variables:
        if not isinstance(variable.symbol, sympy.Symbol):
            raise ValueError(f"{where}: variable {variable.symbol!r} is not a SymPy Symbol")
        name = variable.symbol.name
        if not isinstance(variable.code, int) or variable.code not in CODE_NAMES:
            valid = " ".join(str(code) for code in CODE_NAMES)
            raise ValueError(f"{where}: variable '{name}' has unknown code {variable.code!r}; "
                             f"expected one of {valid}")
        key = (variable.part, variable.code)
        if key in seen:
            raise ValueError(f"{where}: code {variable.code} is declared twice "
                             f"('{seen[key]}' and '{name}')")
        seen[key] = name


def _validate_parameters(spec: ConstraintSpec, where: str) -> None:
    """Symbols, PAR indices and checks of the parameters."""
    for position, parameter in enumerate(spec.parameters):
        if not isinstance(parameter.symbol, sympy.Symbol):
            raise ValueError(f"{where}: parameter {parameter.symbol!r} is not a SymPy Symbol")
        name = parameter.symbol.name
        expected = spec.first_parameter_index + position
        if parameter.index != expected:
            raise ValueError(
                f"{where}: parameter '{name}' is at PAR({parameter.index}); expected "
                f"PAR({expected}) (part id in PAR(1), the {spec.nvars} codes in "
                f"PAR(2:{1 + spec.nvars}), then the parameters in order)"
                if not spec.two_parts else
                f"{where}: parameter '{name}' is at PAR({parameter.index}); expected "
                f"PAR({expected}) (the two parts' ids and codes, then the parameters in "
                "order)")
        if parameter.check not in PARAMETER_CHECKS:
            raise ValueError(f"{where}: parameter '{name}' has check {parameter.check!r}; "
                             f"expected one of {', '.join(PARAMETER_CHECKS)}")
        if not parameter.meaning or not parameter.units:
            raise ValueError(f"{where}: parameter '{name}' needs a meaning and units")


def _validate_names(spec: ConstraintSpec, where: str) -> None:
    """Every declared symbol name must be a distinct, free Fortran name."""
    seen: set[str] = set()
    for symbol in spec.symbols:
        name = symbol.name
        if not _NAME.match(name) or len(name) > 31:
            raise ValueError(f"{where}: symbol name '{name}' is not a lowercase Fortran name "
                             "(letters, digits, underscores, at most 31, starting with a letter)")
        if name in RESERVED_NAMES or _CSE_NAME.match(name) or name.startswith(
                (f"{spec.name}_", "rollcon_")):
            raise ValueError(f"{where}: symbol name '{name}' is reserved for the generated code")
        if name in seen:
            raise ValueError(f"{where}: symbol name '{name}' is declared twice")
        seen.add(name)


def _validate_constraint(spec: ConstraintSpec, where: str, expression: object) -> None:
    """One component: a supported, declared, non-trivial expression linear in the velocities."""
    if not isinstance(expression, sympy.Expr):
        raise ValueError(f"{where}: expression {expression!r} is not a SymPy expression")
    for node in sympy.preorder_traversal(expression):
        if isinstance(node, (sympy.Symbol, sympy.Add, sympy.Mul, sympy.Pow)):
            continue
        if isinstance(node, sympy.Number) and node.is_finite and node.is_real:
            continue
        if isinstance(node, sympy.NumberSymbol):
            continue
        if isinstance(node, SUPPORTED_FUNCTIONS):
            continue
        supported = ", ".join(f.__name__ for f in SUPPORTED_FUNCTIONS)
        raise ValueError(f"{where}: '{node}' ({type(node).__name__}) is not supported; use "
                         f"numbers, + - * / **, and the functions {supported}")
    declared = set(spec.symbols) | {TIME}
    by_name = {symbol.name: symbol for symbol in declared}
    for symbol in sorted(expression.free_symbols, key=lambda s: s.name):
        if symbol in declared:
            continue
        message = (f"{where}: symbol '{symbol.name}' is not a declared variable, parameter "
                   "or the time (ucon.spec.TIME)")
        if symbol.name in by_name:
            message += (f"; a symbol named '{symbol.name}' is declared, but with other "
                        "assumptions: create each symbol once and reuse it")
        raise ValueError(message)
    variables = {v.symbol for v in spec.variables}
    if not expression.free_symbols & variables:
        raise ValueError(f"{where} depends on no declared variable")
    velocities = [v.symbol for v in spec.variables if v.is_velocity]
    offending = _nonlinear_velocity_term(expression, velocities)
    if offending is not None:
        raise ValueError(
            f"{where} is not linear in the velocities: term {sympy.sstr(offending)}; ADAMS "
            "accepts F(q, t) or F = sum a_i(q, t)*qdot_i + a_0(q, t), no product or function "
            "of velocities")


def _nonlinear_velocity_term(expression: sympy.Expr,
                             velocities: list[sympy.Symbol]) -> sympy.Expr | None:
    """The first additive term of the expanded expression that is not linear in the
    velocities, the whole expression if none can be singled out, None if it is linear."""
    velocity_set = set(velocities)

    def nonlinear(term: sympy.Expr) -> bool:
        return any(sympy.diff(term, v).free_symbols & velocity_set
                   for v in velocities if term.has(v))

    if not nonlinear(expression):
        return None
    for term in sympy.Add.make_args(sympy.expand(expression)):
        if nonlinear(term):
            return term
    return expression


def _validate_all_used(spec: ConstraintSpec, where: str) -> None:
    """A declared variable or parameter that no constraint uses is a mistake."""
    used: set[sympy.Symbol] = set()
    for constraint in spec.constraints:
        used |= constraint.expression.free_symbols
    for variable in spec.variables:
        if variable.symbol not in used:
            raise ValueError(f"{where}: variable '{variable.symbol.name}' (code "
                             f"{variable.code}) appears in no constraint; do not declare it")
    for parameter in spec.parameters:
        if parameter.symbol not in used:
            raise ValueError(f"{where}: parameter '{parameter.symbol.name}' (PAR("
                             f"{parameter.index})) appears in no constraint")
