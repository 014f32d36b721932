"""The phases that reach for an object and grasp it from the side, and those that take the hand back to rest."""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import mink
import numpy as np

from assistbot import catalogue
from assistbot.robot import poses
from assistbot.robot.phases import BackOff, Grip, Move, Open, Phase, Rise, Unroll, unreachable
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, PRE_GRASP_BACK, closes_short, side_grasp_pose
from assistbot.task import OBJECTS

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: where a reach starts and a retraction passes (world, m): above the robot's workspace, at a height over what
#: stands on the table, which the hand first rises to
READY_POSE_POS = np.array([0.30, 0.05, 1.00])
#: where the hand waits between actions (world, m): beside the table's near edge, low, outside the head
#: cameras' view of the table; waiting at the ready pose it hid what the robot had just set down in its
#: workspace (benchmarks/arm_occlusion.py measures both)
REST_POSE_POS = np.array([0.55, -0.20, 0.88])
#: m above its grasp that the hand comes in at, before going down to the pre-grasp beside the object
ABOVE_GRASP = 0.10
#: m that the hand's lowest edge passes over the top of an object standing on the table on its way in
TOP_CLEARANCE = 0.01
#: m above the table of the top of the tallest object (the bottle with its stopper)
TALLEST = max(catalogue.top(o) for o in OBJECTS)
#: m short of the object's wall that the palm stops taking what the person holds from above: her fingers
#: hang down its side toward the robot there (the fingers still close from that far: `closes_short`; the
#: hand then takes the object low, `held_grasp_height`, so that its fingers close under hers)
ROOM_FOR_HER_FINGERS = 0.02


def room_for_her_fingers(p: Primitive) -> float:
    """How far short of the wall the palm stops on what the person holds (m): ROOM_FOR_HER_FINGERS when she
    was seen holding it from above, else 0 (a side grip leaves the robot's side of the object free)."""
    return ROOM_FOR_HER_FINGERS if p.holder_grip() == "ag" else 0.0


def retract_phases(over_at: float | None = None) -> list[Phase]:
    """Up, back to the ready pose, then down aside to rest (out of the cameras' view); with ``over_at`` (world
    z, m) the hand first rises to that height and crosses to above the ready pose there, so it passes over
    the objects on its way."""
    rest = Move("rest", lambda p: poses.pose(mink.SO3.identity(), REST_POSE_POS), duration=1.0, tolerance=0.04)
    if over_at is None:
        return [Rise("rise", READY_POSE_POS[2]), Unroll(),
                Move("retract", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
                rest]
    above = READY_POSE_POS.copy()
    above[2] = max(above[2], over_at)
    return [Rise("rise", over_at), Unroll(),
            Move("withdraw over", lambda p: poses.pose(mink.SO3.identity(), above), duration=1.2, tolerance=0.04),
            Move("retract", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=0.6, tolerance=0.04),
            rest]


def above_pre_grasp(p: Primitive, height: float | None = None, held_up: bool = False) -> mink.SE3:
    """Where the hand comes in above the pre-grasp: ABOVE_GRASP over the grasp, and for an object standing
    on the table at least so high that the hand's lowest edge (`Gripper.reach_below`) passes TOP_CLEARANCE
    over the object's top: turning from the ready pose toward an object standing near it, the open
    fingers sweep round at that height (a bottle's neck stands higher than the hand's usual approach)."""
    up = ABOVE_GRASP
    if not held_up and p.object in GRASP_HEIGHT and p.object != "held_out":
        h = height if height is not None else p.grasp_height
        up = max(up, catalogue.height(p.object) + p.robot.gripper.reach_below + TOP_CLEARANCE - h)
    return side_grasp_pose(p, back=PRE_GRASP_BACK, up=up, height=height, held_up=held_up)


def _reach_goals(height: float | None, held_up: bool) -> list[tuple[str, Callable[[Primitive], mink.SE3], float, float]]:
    """The poses a reach goes through from the ready pose to the grasp (name, goal, duration, tolerance): over
    the pre-grasp, the pre-grasp beside the object, the grasp."""
    return [
        ("above pre-grasp", lambda p: above_pre_grasp(p, height, held_up), 1.5, 0.02),
        ("pre-grasp", lambda p: side_grasp_pose(p, back=PRE_GRASP_BACK, up=0.0, height=height, held_up=held_up), 0.8, 0.02),
        ("approach", lambda p: side_grasp_pose(p, back=room_for_her_fingers(p) if held_up else 0.0, height=height,
                                               held_up=held_up), 1.0, 0.025),
    ]


def _closes_short(p: Primitive) -> float:
    """How far short of the grasp the hand may close on what the person holds up (`closes_short`): for the
    object seen, or the one the hand fits least deep when unseen which."""
    obj = p.identify() if p.object == "held_out" else p.object
    short = closes_short(obj) if obj in catalogue.TASK_OBJECTS else min(closes_short(o) for o in catalogue.TASK_OBJECTS)
    return short - room_for_her_fingers(p)   # the approach's goal already stops that much short


def grasp_phase() -> Grip:
    """Close the hand on the object it has come to. A grasp that closes on nothing (the object was not where it
    was seen: put down or dropped meanwhile, say) opens and backs off level before the arm withdraws: the
    closed fingers may lie around the object's neck, and the next action's first move, straight up, would
    lift or tip it."""
    grasp = Grip(True, "grasp")
    grasp.fallback = lambda p: [Open("open"), BackOff("back off from the failed grasp"), *retract_phases()]
    return grasp


def reach_and_grasp_phases(prim: Primitive, height: float | None = None, held_up: bool = False) -> list[Phase]:
    """Reach and grasp the target from the side: standing on the table, or ``held_up`` by the person (the
    hand then reaches out for it as far as it can, and waits for it there: `Move.reach_out`; held where
    the arm cannot reach, but within the open hand held out, it closes on it there: `Move.close_short`)."""
    return [
        Open("open"),
        Rise("rise", READY_POSE_POS[2]),
        Unroll(),
        Move("ready", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
        *(Move(name, goal, duration=duration, tolerance=tolerance, reach_out=held_up,
               arrive_on_touch=held_up and name == "approach",
               close_short=_closes_short if held_up and name == "approach" else None)
          for name, goal, duration, tolerance in _reach_goals(height, held_up)),
        grasp_phase(),
    ]


def reachable_on_table(prim: Primitive, height: float | None = None) -> bool:
    """The target, standing on the table where it is seen, can be grasped from there: every pose of the
    reach (`reach_and_grasp_phases`) lies within the arm's reach and the hand-over zone."""
    return not any(unreachable(prim, goal(prim)) for _, goal, _, _ in _reach_goals(height, False))
