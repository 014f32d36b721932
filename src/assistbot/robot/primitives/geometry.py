"""The objects as the robot's hand grasps them, and the hand's poses for a side grasp.

Body origins are at the bottom centre of the objects; heights are above the object's base."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import mink
import numpy as np

from assistbot import catalogue
from assistbot.robot import poses
from assistbot.robot.controller import OPEN_HAND_REACH, REACH
from assistbot.world.layout import BOTTLE_BODY_TOP, TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.gripper import Gripper
    from assistbot.robot.primitives.base import Primitive


#: the height (m above its base) at which the hand grasps each object standing on the table: its
#: MJCF grasp site; "held_out": an object held out by the person, whichever it is
GRASP_HEIGHT = {**{o: catalogue.grasp_height(o) for o in catalogue.TASK_OBJECTS}, "held_out": 0.06}
#: the objects' radii (the MJCF's); "held_out": either, unseen which
RADIUS = {**{o: catalogue.radius(o) for o in catalogue.TASK_OBJECTS},
          "held_out": sum(catalogue.radius(o) for o in catalogue.TASK_OBJECTS) / len(catalogue.TASK_OBJECTS)}
#: how far (m) beyond REACH a grasp point may lie and still be grasped, short of the hand's middle
REACH_SLACK = 0.025
#: such a grasp stops this far (m) inside REACH, backing along the approach, which counts as no more
#: oblique to the line from the shoulder than MIN_APPROACH_COS (the cosine between them)
INSIDE_REACH = 0.003
MIN_APPROACH_COS = 0.3
#: m back along the approach from the grasp pose at which the open hand stops before closing in
PRE_GRASP_BACK = 0.16
TCP_CYLINDER_RADIUS = 0.035  # the TCP is the centre of a 70 mm cylinder touching the palm
#: how high (m) the hand lifts an object off the table to carry it
LIFT = 0.12
#: the top of each object's side wall, where a side grasp's upper finger must stay below (m above the base):
#: the glass's rim, the bottle's shoulder
WALL_TOP = {"glass": catalogue.height("glass"), "bottle": BOTTLE_BODY_TOP}
#: m between a finger's edge and the wall's top for it to press the wall, not the rim's edge
ON_THE_WALL = 0.005


def offer_grasp_height(obj: str, hand: "Gripper") -> float:
    """Grasp height (m above the base) of an object the robot takes from the table to give to the person:
    as high as the middle finger still closes on the wall (the upper finger may close over the top), so
    that the hand holds it by its upper part and leaves the lower part to the hand that takes it, as a
    person hands over a glass. Never lower than the table grasp (GRASP_HEIGHT)."""
    if obj not in WALL_TOP:
        return GRASP_HEIGHT.get(obj, GRASP_HEIGHT["held_out"])
    return max(GRASP_HEIGHT[obj], WALL_TOP[obj] - hand.middle_reach - ON_THE_WALL)


def closes_short(obj: str) -> float:
    """How far (m) short of its grasp, along the approach, the open hand may stop and still close on ``obj``
    held up by the person: as far as its far side stays within the open fingers' reach (OPEN_HAND_REACH
    beyond the TCP). The person's grip steadies it while the fingers close round it."""
    return OPEN_HAND_REACH - (2.0 * RADIUS[obj] - TCP_CYLINDER_RADIUS)


def held_grasp_height(obj: str, hand: "Gripper", from_above: bool = False) -> float:
    """Grasp height (m above the base) of an object held up by the person: the middle of the band in
    which the whole hand lies along the object's wall (palm above the base, upper finger below the
    wall's top), since the base is seen only to a cm or two there. The glass's band is 2 cm wide: its
    rim lies 10 cm up, and a finger above it curls over the top onto the palm (and, opened, catches
    inside the glass). Unknown which object ("held_out"): the band both share.

    Held ``from_above``, her fingers hang down the upper part of the wall: the band's lower end (the
    palm's lower edge at the base), each hand on the part the other leaves free. Where the base is seen
    too low, the put-down lets the object slide down the loosened grip (`LowerUntilSupported`)."""
    if from_above:
        return hand.reach_below
    top = WALL_TOP[obj] if obj in WALL_TOP else min(WALL_TOP.values())
    return 0.5 * (hand.reach_below + top - hand.reach_above)


def held_centre(pose: mink.SE3, obj: str) -> np.ndarray:
    """Where the axis of ``obj``, held in a side grasp with the TCP at ``pose``, passes at grasp height (world):
    beyond the TCP along the approach (the inverse of `grasp_pose_at`)."""
    return pose.translation() + poses.approach_axis(pose.rotation()) * (RADIUS[obj] - TCP_CYLINDER_RADIUS)


def grasp_pose_at(prim: Primitive, centre: np.ndarray, obj: str, back: float = 0.0, roll: float = 0.0) -> mink.SE3:
    """Side grasp of ``obj`` whose axis passes through ``centre`` (world, at grasp height)."""
    rot = poses.side_rotation(centre, prim.robot.shoulder)
    ax = poses.approach_axis(rot)
    pos = centre - ax * (RADIUS[obj] - TCP_CYLINDER_RADIUS + back)
    to = pos - prim.robot.shoulder
    dist = float(np.linalg.norm(to))
    if REACH < dist <= REACH + REACH_SLACK:
        # just beyond the arm's reach (an object held out at the person's own limit): stop short along the
        # approach; the object then sits nearer the fingertips of the open hand (94 mm), which still close on it
        pos = pos - ax * (dist - REACH + INSIDE_REACH) / max(MIN_APPROACH_COS, float(ax @ to) / dist)
    return poses.pose(rot @ mink.SO3.from_x_radians(roll), pos)


def side_grasp_pose(prim: Primitive, back: float = 0.0, up: float = 0.0, roll: float = 0.0,
                     height: float | None = None, held_up: bool = False) -> mink.SE3:
    """Side grasp of the target at its grasp height above its base: on the table, or ``held_up`` by the
    person at the height perception gives (`Primitive.base_z`)."""
    obj = prim.object or "glass"
    x, y = prim.xy()
    if held_up:
        # which object the person holds out, as seen, for where the hand fits on it
        seen = prim.identify() if obj == "held_out" else obj
        base_z, h = prim.base_z(), held_grasp_height(seen or obj, prim.robot.gripper, prim.holder_grip() == "ag")
    else:
        base_z, h = TABLE_Z, prim.grasp_height
    c = np.array([x, y, base_z + (height if height is not None else h) + up])
    return grasp_pose_at(prim, c, obj, back, roll)


def half_turn(p: Primitive) -> float:
    """The hand's roll about its approach axis to the nearest half turn: 0, or pi once it has turned the
    glass in it. Carried either way, what it holds stands upright."""
    return math.pi if poses.upside_down(p.robot.commanded_tcp_pose().rotation()) else 0.0
