"""ucon: generate ADAMS UCOSUBs from symbolic constraints, with no manual editing.

A constraint is stated once, symbolically, in ``ucon/specs/<name>.py``. The generator
validates it, derives every quantity ADAMS asks a UCOSUB for, runs one common-subexpression
elimination over all of them, and prints two files: a free-form module compiled into the
rollcon library, and an ADAMS-ready fixed-form ``ucosub.f``. Nothing here writes to disk;
``python -m ucon`` does (see ``ucon/__main__.py``).
"""

from __future__ import annotations

import importlib
import pkgutil

from . import specs as _specs_package
from .derive import derive as _derive
from .fortran import legacy_path, lower, module_path, render_legacy, render_module
from .spec import TIME, Constraint, ConstraintSpec, Parameter, Variable, validate

__all__ = [
    "TIME",
    "Constraint",
    "ConstraintSpec",
    "Parameter",
    "Variable",
    "validate",
    "spec_names",
    "load_spec",
    "load_specs",
    "generate",
    "generate_all",
]


def spec_names() -> list[str]:
    """Names of the spec modules in ``ucon/specs/``, sorted."""
    return sorted(info.name for info in pkgutil.iter_modules(_specs_package.__path__)
                  if not info.name.startswith("_"))


def load_spec(name: str) -> ConstraintSpec:
    """Import ``ucon.specs.<name>`` and return its ``SPEC``.

    Raises:
        ValueError: when there is no such spec, it defines no ``SPEC``, or its name differs.
    """
    if name not in spec_names():
        raise ValueError(f"no spec '{name}' in ucon/specs/ (known: {', '.join(spec_names())})")
    module = importlib.import_module(f"{_specs_package.__name__}.{name}")
    spec = getattr(module, "SPEC", None)
    if not isinstance(spec, ConstraintSpec):
        raise ValueError(f"ucon/specs/{name}.py defines no SPEC of type ConstraintSpec")
    if spec.name != name:
        raise ValueError(f"ucon/specs/{name}.py defines a spec named '{spec.name}'; the name "
                         "must equal the file name")
    return spec


def load_specs() -> list[ConstraintSpec]:
    """Every spec, in name order."""
    return [load_spec(name) for name in spec_names()]


def generate(spec: ConstraintSpec) -> dict[str, str]:
    """The generated files of one spec: path relative to the project root -> text."""
    program = lower(_derive(spec))
    return {module_path(spec): render_module(program), legacy_path(spec): render_legacy(program)}


def generate_all(specs: list[ConstraintSpec] | None = None) -> dict[str, str]:
    """The generated files of every spec (or of ``specs``), in path order."""
    files: dict[str, str] = {}
    for spec in specs if specs is not None else load_specs():
        files.update(generate(spec))
    return dict(sorted(files.items()))

