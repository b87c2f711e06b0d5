"""The orientation joint primitive with marker J on ground (ADAMS JPRIM/id, ORIENTATION).

Geometry and PAR layout: ucon/specs/_joint.py. A JOINT or JPRIM statement of a dataset whose
J marker is on the ground part is served by this routine and its kin (docs/datasets.md).
"""

from ucon.specs._joint import primitive

SPEC = primitive("orientation", ground=True)
