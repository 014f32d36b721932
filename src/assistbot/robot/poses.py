"""TCP poses for approaches: side and top grasps, rolls, min-jerk interpolation between poses.

Gripper frame (see robot.xml): the palm faces the gripper's -x, the fingers
close about its z axis. Identity rotation = a side approach along world -x
(from the robot toward the human) with the fingers closing horizontally.
"""

from __future__ import annotations

import math

import mink
import numpy as np


def min_jerk(s: float) -> float:
    """Minimum-jerk position profile on [0, 1] (zero velocity and acceleration at both ends)."""
    s = min(max(s, 0.0), 1.0)
    return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)


def approach_yaw(point: np.ndarray, shoulder: np.ndarray) -> float:
    """Yaw (rad) of a horizontal approach from the shoulder's side toward a world point."""
    d = np.asarray(point, float)[:2] - np.asarray(shoulder, float)[:2]
    return math.atan2(-d[1], -d[0])


def side_rotation(point: np.ndarray, shoulder: np.ndarray, roll: float = 0.0) -> mink.SO3:
    """Side grasp at ``point``: palm toward it horizontally, rolled by ``roll`` about the approach axis."""
    return mink.SO3.from_z_radians(approach_yaw(point, shoulder)) @ mink.SO3.from_x_radians(roll)


def top_rotation(point: np.ndarray, shoulder: np.ndarray) -> mink.SO3:
    """Top grasp: palm facing down, fingers closing across the robot's line of approach."""
    return mink.SO3.from_z_radians(approach_yaw(point, shoulder)) @ mink.SO3.from_y_radians(-math.pi / 2)


def pose(rot: mink.SO3, pos) -> mink.SE3:
    return mink.SE3.from_rotation_and_translation(rot, np.asarray(pos, float))


def interpolate(a: mink.SE3, b: mink.SE3, s: float) -> mink.SE3:
    """Pose at fraction s from a to b (straight line, geodesic rotation)."""
    pa, pb = a.translation(), b.translation()
    ra, rb = a.rotation(), b.rotation()
    rot = ra @ mink.SO3.exp(s * (ra.inverse() @ rb).log())
    return mink.SE3.from_rotation_and_translation(rot, pa + s * (pb - pa))


def approach_axis(rot: mink.SO3) -> np.ndarray:
    """World direction from the palm toward the object (the gripper's -x)."""
    return -rot.as_matrix()[:, 0]


def upside_down(rot: mink.SO3) -> bool:
    """The hand rolled past a quarter turn about its approach axis (its z axis points down): it has turned
    the glass in it."""
    return bool(rot.as_matrix()[2, 2] < 0.0)
