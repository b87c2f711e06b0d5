"""From derivatives to the generated Fortran: paths, the shared lowering, the entry points.

Both files are printed from one common-subexpression elimination over every non-zero output
of every component at once, so they evaluate the same expressions in the same order. The
printers live in ``printers.py``, the shared texts in ``messages.py``, the two templates in
``module_writer.py`` and ``legacy_writer.py``; this module re-exports their public names.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy

from .derive import Derivatives, Entry
from .legacy_writer import render_legacy
from .module_writer import render_module
from .printers import LegacyPrinter, ModulePrinter, wrap_fixed, wrap_free
from .spec import TIME, ConstraintSpec

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

#: Prefix of the common-subexpression temporaries.
CSE_PREFIX = "cse"


def module_path(spec: ConstraintSpec) -> str:
    """Path of the generated module, relative to the project root."""
    return f"src/ucosubs/generated/rollcon_gen_{spec.name}.f90"


def legacy_path(spec: ConstraintSpec) -> str:
    """Path of the generated ``ucosub.f``, relative to the project root."""
    return f"ucon/adams/{spec.name}/ucosub.f"


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
