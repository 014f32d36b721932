"""MJCF changes the robot needs, applied in memory until assets/mjcf/robot.xml has them.

Requested from the scene's owner (see the issue 6 report):
  1. robot_base pos x 0.80 -> 0.65: with the shoulder at x = 0.70 the 0.74 m arm
     reaches the RWS default places only with a straight (singular) arm and
     cannot reach the middle line at a hand-over height at all.
  2. robot_f3_prox / robot_f1_base / robot_f2_base pos y +-0.046 -> +-0.056: the
     open fingers leave 74 mm between them, less than the glass (80 mm); with
     the change the opening is 94 mm.
`apply(spec)` sets these absolute values on an `mujoco.MjSpec` (a no-op once
the MJCF has them); both the physics bench and the IK model use it, so they
always agree.
"""

from __future__ import annotations

import mujoco

BASE_X = 0.65
FINGER_Y = 0.056


def apply(spec: mujoco.MjSpec) -> mujoco.MjSpec:
    base = spec.body("robot_base")
    base.pos = [BASE_X, base.pos[1], base.pos[2]]
    for name, sign in (("robot_f3_prox", 1), ("robot_f1_base", -1), ("robot_f2_base", -1)):
        b = spec.body(name)
        b.pos = [b.pos[0], sign * FINGER_Y, b.pos[2]]
    return spec


def load_model(xml) -> mujoco.MjModel:
    return apply(mujoco.MjSpec.from_file(str(xml))).compile()
