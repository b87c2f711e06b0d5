"""The orientation joint primitive between two parts (ADAMS JPRIM/id, ORIENTATION).

Geometry and PAR layout: ucon/specs/_joint.py. A JOINT or JPRIM statement of a dataset whose
markers are on two moving parts is served by this routine and its kin (docs/datasets.md).
"""

from ucon.specs._joint import primitive

SPEC = primitive("orientation", ground=False)
