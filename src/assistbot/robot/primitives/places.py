"""Where the robot holds an object out for the person, puts one down in its workspace, or shows a spot both reach."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from assistbot import catalogue
from assistbot.robot.controller import REACH, TCP_MIN_X
from assistbot.robot.placement import put_down_spot
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, REACH_SLACK
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: the farthest a spot shared with the person may lie (m from the shoulder, at grasp height): just beyond
#: REACH, within the slack, since the person's arm stops at the middle line
SHARED_REACH = REACH + REACH_SLACK - 0.012
#: where an object is held out for the human to take: its centre (table x, y) and its base height above the table
HOLD_OUT_XY = (-0.04, -0.04)
HOLD_OUT_BASE = 0.11
#: how low and how high an offered object's base is held above the table (m), whatever the hand it is
#: offered to: a hand shown higher takes it from the side no higher than a seated arm reaches well
OFFER_BASE = (0.05, 0.12)
#: m within REACH, and on the robot's side of TCP_MIN_X, that an offered object's centre is kept
OFFER_REACH_MARGIN = 0.03
OFFER_X_MARGIN = 0.01


def offer_point(prim: "Primitive") -> np.ndarray:
    """Where to hold an object out for the person to take (world centre at grasp height): toward their
    open hand where it was last seen held out (the object's middle at the hand, its base within
    OFFER_BASE), else HOLD_OUT_XY at HOLD_OUT_BASE; never deeper into the HWS than the hand may go, nor
    out of reach. Chosen once."""
    if prim._offer is None:
        hand = prim.partner_hand()
        obj = prim.object
        if hand is None:
            c = np.array([HOLD_OUT_XY[0], HOLD_OUT_XY[1], TABLE_Z + HOLD_OUT_BASE + GRASP_HEIGHT[obj]])
        else:
            base = float(np.clip(float(hand[2]) - 0.5 * catalogue.height(obj), *OFFER_BASE))
            c = np.array([float(hand[0]), float(hand[1]), TABLE_Z + base + GRASP_HEIGHT[obj]])
        # out of reach: brought back toward the robot at the same height (a hand takes it where it was shown)
        sh, reach = prim.robot.shoulder, REACH - OFFER_REACH_MARGIN
        c[0] = max(c[0], TCP_MIN_X + OFFER_X_MARGIN)
        flat = reach ** 2 - (c[2] - sh[2]) ** 2
        off = c[:2] - sh[:2]
        if float(np.linalg.norm(c - sh)) > reach and flat > 0:
            c[:2] = sh[:2] + off * np.sqrt(flat) / float(np.linalg.norm(off))
        elif float(np.linalg.norm(c - sh)) > reach:
            c = sh + (c - sh) * reach / float(np.linalg.norm(c - sh))
        prim._offer = c
    return prim._offer


def free_rws_spot(p: "Primitive") -> np.ndarray:
    """Where to put the object in the hand down in the RWS (`placement.put_down_spot`): clear of the
    corridor to the hand-over place and of the other objects seen standing in the RWS (``p.locate``)."""
    standing = [np.asarray(xy, float) for xy in (p.locate(n) for n in OBJECTS if n != p.object)
                if xy is not None and xy[0] > 0.0]
    return put_down_spot(p.robot.shoulder, REACH, HOLD_OUT_XY, standing, GRASP_HEIGHT.get(p.object, GRASP_HEIGHT["held_out"]))
