"""Gaze: pan and tilt angles that point the head's cameras at a world point.

The head is a pan joint about world z and a tilt joint about the pan
frame's -y (positive tilt looks down); in the zero pose the cameras look
along -x. Closed form: no IK needed for two joints.
"""

from __future__ import annotations

import math

import numpy as np

PAN_RANGE = (-1.6, 1.6)
TILT_RANGE = (-0.3, 1.3)


def gaze_angles(head_center: np.ndarray, point: np.ndarray) -> tuple[float, float]:
    """(pan, tilt) in rad so that the head at ``head_center`` looks at ``point`` (both world, m)."""
    d = np.asarray(point, float) - np.asarray(head_center, float)
    # looking along -x at pan 0: pan rotates -x toward -y for positive angles
    pan = math.atan2(-d[1], -d[0])
    horizontal = math.hypot(d[0], d[1])
    tilt = math.atan2(-d[2], horizontal)
    return (min(max(pan, PAN_RANGE[0]), PAN_RANGE[1]), min(max(tilt, TILT_RANGE[0]), TILT_RANGE[1]))
