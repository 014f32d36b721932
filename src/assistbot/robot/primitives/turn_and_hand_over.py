"""TurnAndHandOver: turn the inverted glass in the air and give it to the person upright."""

from __future__ import annotations

import math

from assistbot.robot.phases import Move
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.carry_over import CarryOver
from assistbot.robot.primitives.geometry import grasp_pose_at
from assistbot.robot.primitives.handing_over import give, hand_not_free
from assistbot.robot.primitives.places import offer_point
from assistbot.robot.primitives.reaching import reach_and_grasp_phases
from assistbot.robot.primitives.turn_glass import seen_upright, turn_phases


class TurnAndHandOver(Primitive):
    """Turn the inverted glass in the air (as `TurnGlass`), then hold it out upright and give it to the human."""

    name = "turn_and_hand_over"

    def __init__(self, robot, obj="glass", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout

    def interrupted(self, phase) -> str:
        return seen_upright(self, phase) or hand_not_free(self, phase)

    def phases(self):
        # after the roll the gripper is upside down: keep that roll while holding out
        def hold(p):
            return grasp_pose_at(p, offer_point(p), p.object, roll=math.pi)
        return reach_and_grasp_phases(self) + turn_phases() + [
            CarryOver(hold), Move("hold out", hold, duration=2.5, tolerance=0.03),
            *give(self.timeout),
        ]
