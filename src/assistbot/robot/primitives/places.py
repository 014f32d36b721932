"""Where the robot holds an object out for the person, puts one down in its workspace, or shows a spot both reach."""

from __future__ import annotations

from typing import TYPE_CHECKING

import mink
import numpy as np

from assistbot import catalogue
from assistbot.robot import poses
from assistbot.robot.controller import REACH, TCP_MIN_X
from assistbot.robot.placement import put_down_spot
from assistbot.robot.primitives.geometry import REACH_SLACK, held_centre
from assistbot.robot.primitives.reaching import READY_POSE_POS, REST_POSE_POS
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: the farthest a spot shared with the person may lie (m from the shoulder, at grasp height): just beyond
#: REACH, within the slack, since the person's arm stops at the middle line
SHARED_REACH = REACH + REACH_SLACK - 0.012
#: the way (table x, y, from and to) the hand goes down from the ready pose to rest after every action, its
#: open fingers pointing at the table: what the robot sets down near it is swept over
TO_REST = (READY_POSE_POS[:2], REST_POSE_POS[:2])
#: where an object is held out for the human to take: its centre (table x, y) and its base height above the table
HOLD_OUT_XY = (-0.04, -0.04)
HOLD_OUT_BASE = 0.11
#: how low and how high an offered object's base is held above the table (m), whatever the hand it is
#: offered to: a hand shown higher takes it from the side no higher than a seated arm reaches well
OFFER_BASE = (0.05, 0.12)
#: m within REACH, and on the robot's side of TCP_MIN_X, that an offered object's centre is kept
OFFER_REACH_MARGIN = 0.03
OFFER_X_MARGIN = 0.01
#: m the object held out is brought nearer a person whose reach stopped short of it, at a time; the least
#: move worth making; and the farthest from it (m) a hand seen stopped may be and still reach for it
MEET_STEP = 0.06
MEET_MIN = 0.01
MEET_MAX = 0.20


def offer_point(prim: "Primitive") -> np.ndarray:
    """Where to hold an object out for the person to take (world centre at grasp height): toward their
    open hand where it was last seen held out (the object's middle at the hand, its base within
    OFFER_BASE), else HOLD_OUT_XY at HOLD_OUT_BASE; never deeper into the HWS than the hand may go, nor
    out of reach. Chosen once."""
    if prim._offer is None:
        hand = prim.partner_hand()
        obj = prim.object
        if hand is None:
            c = np.array([HOLD_OUT_XY[0], HOLD_OUT_XY[1], TABLE_Z + HOLD_OUT_BASE + prim.grasp_height])
        else:
            base = float(np.clip(float(hand[2]) - 0.5 * catalogue.height(obj), *OFFER_BASE))
            c = np.array([float(hand[0]), float(hand[1]), TABLE_Z + base + prim.grasp_height])
        prim._offer = within_offer_limits(prim, c)
    return prim._offer


def within_offer_limits(prim: "Primitive", c: np.ndarray) -> np.ndarray:
    """An offered object's centre ``c`` (world, at grasp height) kept on the robot's side of TCP_MIN_X and
    within its reach: out of reach, brought back toward the robot at the same height (a hand takes it
    where it was shown)."""
    c = np.array(c, float)
    sh, reach = prim.robot.shoulder, REACH - OFFER_REACH_MARGIN
    c[0] = max(c[0], TCP_MIN_X + OFFER_X_MARGIN)
    flat = reach ** 2 - (c[2] - sh[2]) ** 2
    off = c[:2] - sh[:2]
    if float(np.linalg.norm(c - sh)) > reach and flat > 0:
        c[:2] = sh[:2] + off * np.sqrt(flat) / float(np.linalg.norm(off))
    elif float(np.linalg.norm(c - sh)) > reach:
        c = sh + (c - sh) * reach / float(np.linalg.norm(c - sh))
    return c


def meet_goal(prim: "Primitive", hand) -> mink.SE3 | None:
    """The hand pose that brings the object held out nearer the person, whose hand has been seen reaching for it
    and stopping at table ``hand`` (x, y, z) without taking it: the object MEET_STEP farther toward the
    person's side, and by as much at most toward the hand's height and side, the robot's hand turned as it is,
    within `within_offer_limits`. Not all the way to the hand as seen: where the robot's arm hides the hand's
    end vision places the hand several cm off, even at the object; the person's reach is from their side, and
    the hand's side and height say the rest. None when the hand is too far off to be reaching for it
    (MEET_MAX) or the arm cannot bring the object nearer."""
    tcp = prim.robot.tcp_pose()
    obj = prim.object
    up = np.array([0.0, 0.0, prim.grasp_height - 0.5 * catalogue.height(obj)])   # the middle to the grasp height
    centre = held_centre(tcp, obj)
    middle = centre - up
    at = np.asarray(hand, float) + np.array([0.0, 0.0, TABLE_Z])
    if float(np.linalg.norm(at - middle)) > MEET_MAX:
        return None
    to = middle + np.array([-MEET_STEP, *np.clip(at[1:] - middle[1:], -MEET_STEP, MEET_STEP)])
    to[2] = max(to[2], TABLE_Z + OFFER_BASE[0] + 0.5 * catalogue.height(obj))
    c = within_offer_limits(prim, to + up)
    if float(np.linalg.norm(c - centre)) < MEET_MIN:
        return None
    prim._offer = c
    return poses.pose(tcp.rotation(), tcp.translation() + (c - centre))


def free_rws_spot(p: "Primitive") -> np.ndarray:
    """Where to put the object in the hand down in the RWS (`placement.put_down_spot`): clear of the
    corridor to the hand-over place, of the way the hand goes down from the ready pose to rest, and of the
    other objects seen standing in the RWS (``p.locate``)."""
    standing = [np.asarray(xy, float) for xy in (p.locate(n) for n in OBJECTS if n != p.object)
                if xy is not None and xy[0] > 0.0]
    return put_down_spot(p.robot.shoulder, REACH, HOLD_OUT_XY, standing, p.grasp_height,
                         ways=(TO_REST,))
