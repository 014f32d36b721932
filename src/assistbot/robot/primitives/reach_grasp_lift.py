"""ReachGraspLift: grasp an object standing in the RWS and lift it."""

from __future__ import annotations

from assistbot.robot.phases import Move
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import LIFT, side_grasp_pose
from assistbot.robot.primitives.reaching import reach_and_grasp_phases


class ReachGraspLift(Primitive):
    name = "reach_grasp_lift"

    def phases(self):
        return reach_and_grasp_phases(self) + [Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2)]
