"""ucon: generate ADAMS UCOSUBs from symbolic constraints, with no manual editing.

A constraint is stated once, symbolically, in ``ucon/specs/<name>.py``. The generator
validates it, derives every quantity ADAMS asks a UCOSUB for, runs one common-subexpression
elimination over all of them, and prints two files: a free-form module compiled into the
rollcon library, and an ADAMS-ready fixed-form ``ucosub.f``. Nothing here writes to disk;
``python -m ucon`` does (see ``ucon/__main__.py``).
"""

from __future__ import annotations

import dataclasses
import importlib
import importlib.util
import pkgutil
import sys
from pathlib import Path

from . import specs as _specs_package
from .derive import SimplifyBound
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
    "load_spec_file",
    "is_spec_file",
    "SimplifyBound",
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


def is_spec_file(name: str) -> bool:
    """True when ``name`` names a spec file (``PATH/spec.py``) rather than a catalog spec."""
    return name.endswith(".py") or "/" in name


def load_spec_file(path: str) -> ConstraintSpec:
    """Import the spec file at ``path`` (anywhere: a user's spec outside ``ucon/specs/``) and
    return its ``SPEC``, its ``origin`` the path as given. The file imports ``ucon.spec`` as
    the catalog's do; its spec's name need not be the file's name.

    Raises:
        ValueError: when the file is missing, fails to import, or defines no ``SPEC``.
    """
    file = Path(path)
    if not file.is_file():
        raise ValueError(f"{path}: no such spec file")
    module_name = f"_ucon_spec_file_{abs(hash(str(file.resolve())))}"
    loader = importlib.util.spec_from_file_location(module_name, file)
    if loader is None or loader.loader is None:
        raise ValueError(f"{path}: not a Python file")
    module = importlib.util.module_from_spec(loader)
    sys.modules[module_name] = module
    try:
        loader.loader.exec_module(module)
    except Exception as error:  # a user's file: any failure is reported, not raised on
        del sys.modules[module_name]
        raise ValueError(f"{path}: the spec file does not import: {type(error).__name__}: "
                         f"{error}") from error
    spec = getattr(module, "SPEC", None)
    if not isinstance(spec, ConstraintSpec):
        raise ValueError(f"{path} defines no SPEC of type ConstraintSpec (from ucon.spec "
                         "import ConstraintSpec)")
    return dataclasses.replace(spec, origin=path)


def load_specs() -> list[ConstraintSpec]:
    """Every spec, in name order."""
    return [load_spec(name) for name in spec_names()]


def generate(spec: ConstraintSpec, bound: SimplifyBound | None = None) -> dict[str, str]:
    """The generated files of one spec: path relative to the project root -> text.
    ``bound``: the time bound on its simplification (ucon.derive.derive)."""
    program = lower(_derive(spec, bound))
    return {module_path(spec): render_module(program), legacy_path(spec): render_legacy(program)}


def generate_all(specs: list[ConstraintSpec] | None = None,
                 bound: SimplifyBound | None = None) -> dict[str, str]:
    """The generated files of every spec (or of ``specs``), in path order."""
    files: dict[str, str] = {}
    for spec in specs if specs is not None else load_specs():
        files.update(generate(spec, bound))
    return dict(sorted(files.items()))

