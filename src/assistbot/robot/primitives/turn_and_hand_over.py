"""TurnAndHandOver: turn the inverted glass in the air, set it down upright, and give it to the person by its upper part."""

from __future__ import annotations

from assistbot.robot.phases import HoldAt
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import offer_grasp_height
from assistbot.robot.primitives.hand_over import offer_phases
from assistbot.robot.primitives.handing_over import hand_not_free
from assistbot.robot.primitives.reaching import reach_and_grasp_phases
from assistbot.robot.primitives.turn_glass import seen_upright, set_down_turned, turn_phases


class TurnAndHandOver(Primitive):
    """Turn the inverted glass in the air (as `TurnGlass`) and set it down upright; take it again by its upper
    part and give it to the human (as `HandOver`). The turn holds the glass by its middle (the hand grasps the
    inverted glass standing on the table, its palm above the table), and a glass held out by its middle
    leaves the person's fingers no room beside the robot's palm (docs/measurements.md, "Letting go where the
    other's hand is")."""

    name = "turn_and_hand_over"

    def __init__(self, robot, obj="glass", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout

    def interrupted(self, phase) -> str:
        # (a glass seen upright before the turn is not turned; after it, it is upright)
        return (seen_upright(self, phase) if self.before("turn") else "") or hand_not_free(self, phase)

    def phases(self):
        return (reach_and_grasp_phases(self) + turn_phases() + set_down_turned()
                + [HoldAt(offer_grasp_height(self.object or "glass", self.robot.gripper))]
                + reach_and_grasp_phases(self) + offer_phases(self.timeout))
