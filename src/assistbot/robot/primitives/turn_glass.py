"""TurnGlass: grasp the inverted glass, roll it 180 deg in the air, put it down upright."""

from __future__ import annotations

import math

from assistbot.robot.phases import Move, Open, Phase, SetCarrying
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import LIFT, PRE_GRASP_BACK, side_grasp_pose
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, retract_phases


def seen_upright(prim: Primitive, phase: Phase) -> str:
    """Why a turn of the glass must not go on: the cameras see it upright already (turned by the person,
    or inverted only in a misreading), until the hand closes in on it (then it hides the glass)."""
    if not prim.before("pre-grasp"):
        return ""
    state = prim.seen_state("glass")
    return "the glass is already upright" if state is not None and state != "inverted" else ""


def turn_phases() -> list[Phase]:
    # the inverted glass is grasped at its middle too (its height is symmetric)
    return [
        Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2),
        Move("turn half", lambda p: side_grasp_pose(p, up=LIFT, roll=math.pi / 2), duration=1.2),
        Move("turn", lambda p: side_grasp_pose(p, up=LIFT, roll=math.pi), duration=1.2),
    ]


def set_down_turned() -> list[Phase]:
    """Set the glass turned in the hand down upright where it was taken (the hand still rolled), let go,
    and back off."""
    return [
        Move("lower", lambda p: side_grasp_pose(p, up=0.008, roll=math.pi), duration=1.2),
        Open("release"),
        SetCarrying(False),
        Move("back off", lambda p: side_grasp_pose(p, back=PRE_GRASP_BACK, up=0.03, roll=math.pi), duration=1.0, tolerance=0.04),
    ]


class TurnGlass(Primitive):
    """Grasp the inverted glass, lift, roll it 180 deg about the approach axis, put it down upright, let go."""

    name = "turn_glass"

    def __init__(self, robot, obj="glass", **kw):
        super().__init__(robot, obj, **kw)

    def interrupted(self, phase: Phase) -> str:
        return seen_upright(self, phase)

    def phases(self):
        return reach_and_grasp_phases(self) + turn_phases() + set_down_turned() + retract_phases()
