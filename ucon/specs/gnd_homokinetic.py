"""The homokinetic condition with marker J on ground: a CONVEL joint's (ADAMS JOINT, CONVEL).

Geometry and PAR layout: ucon/specs/_joint.py. A dataset's CONVEL joint whose J marker is on
the ground part is served by this routine and gnd_atpoint (docs/datasets.md).
"""

from ucon.specs._joint import primitive

SPEC = primitive("homokinetic", ground=True)
