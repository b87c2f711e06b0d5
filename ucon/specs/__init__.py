"""Constraint specs, one module per constraint; each defines ``SPEC``, a ConstraintSpec.

The generator finds them by file name: ``ucon/specs/<name>.py`` must define a spec called
``<name>``. Modules whose names start with an underscore are not specs.
"""
