"""HandOver: carry an object to the hand-over zone and give it to the person."""

from __future__ import annotations

from assistbot.robot.phases import Move, Phase
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import LIFT, offer_grasp_height, side_grasp_pose
from assistbot.robot.primitives.handing_over import give, hand_not_free, hold_out
from assistbot.robot.primitives.reaching import reach_and_grasp_phases


def offer_phases(timeout: float) -> list[Phase]:
    """The object just grasped from the table: lift it, carry it upright (slowly: it may be a full glass) to
    the hand-over zone, hold it out and give it (`give`)."""
    return [
        Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.5),
        *hold_out(duration=3.0),
        *give(timeout),
    ]


class HandOver(Primitive):
    """Grasp the object by its upper part (`offer_grasp_height`: the lower part is for the hand that takes
    it), carry it upright (slowly: it may be a full glass) to the hand-over zone, hold it out until the wrist
    feels the person take it (`WaitForTake`), let go, withdraw."""

    name = "hand_over"

    def __init__(self, robot, obj="glass", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout
        self.held_at = offer_grasp_height(obj, robot.gripper)

    def phases(self):
        return reach_and_grasp_phases(self) + offer_phases(self.timeout)

    def interrupted(self, phase) -> str:
        return hand_not_free(self, phase)
