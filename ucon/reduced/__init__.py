"""The benchmark's reduced (minimal-coordinate) ODEs: the rolling disk's and the Whipple
bicycle's, the independent references and limits of `rollcon bench`.

``derivation`` and ``bicycle`` derive them with Kane's method; ``writer`` and
``bicycle_writer`` print their Fortran modules. ``python -m ucon write`` and ``check`` cover them
together with the specs' files (when no spec is named).
"""

from __future__ import annotations

from .bicycle_writer import BICYCLE_MODULE_PATH, bicycle_files
from .writer import REDUCED_MODULE_PATH
from .writer import reduced_files as disk_files

__all__ = ["REDUCED_MODULE_PATH", "BICYCLE_MODULE_PATH", "reduced_files"]


def reduced_files() -> dict[str, str]:
    """Every generated file of the reduced ODEs: path relative to the project root -> text."""
    files = disk_files()
    files.update(bicycle_files())
    return files
