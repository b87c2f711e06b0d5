"""The homokinetic condition between two parts: a CONVEL joint's (ADAMS JOINT/id, CONVEL).

Geometry and PAR layout: ucon/specs/_joint.py. A dataset's CONVEL joint whose markers are on
two moving parts is served by this routine and jp_atpoint (docs/datasets.md).
"""

from ucon.specs._joint import primitive

SPEC = primitive("homokinetic", ground=False)
