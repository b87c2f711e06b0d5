"""The rolling disk's reduced (minimal-coordinate) ODE: the benchmark's independent reference.

``derivation`` derives it with Kane's method; ``writer`` prints its Fortran module. ``python -m
ucon write`` and ``check`` cover it together with the specs' files (when no spec is named).
"""

from __future__ import annotations

from .writer import REDUCED_MODULE_PATH, reduced_files

__all__ = ["REDUCED_MODULE_PATH", "reduced_files"]
