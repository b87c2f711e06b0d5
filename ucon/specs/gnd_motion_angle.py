"""The angle a MOTION drives with one side on the ground (ADAMS MOTION, ROTATION or B1, B2, B3).

Geometry and PAR layout: ucon/specs/_motion.py. A MOTION of a dataset with one marker on the
ground part is served by this routine (docs/datasets.md, "MOTION").
"""

from ucon.specs._motion import motion_angle

SPEC = motion_angle(ground=True)
