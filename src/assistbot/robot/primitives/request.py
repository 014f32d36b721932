"""Request: an open hand held out palm up near the middle line, asking for an object."""

from __future__ import annotations

import math

import mink
import numpy as np

from assistbot.robot import poses
from assistbot.robot.phases import BackOff, Move, Open, Rise, Wait
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.reaching import retract_phases
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Distance from point p to the segment a-b (any dimension)."""
    ab = b - a
    s = float(np.clip(np.dot(p - a, ab) / max(float(np.dot(ab, ab)), 1e-12), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + s * ab)))


class Request(Primitive):
    """Hold an open hand out, palm up, near the middle line toward the target object's side (a request),
    for SHOW_SECONDS, then withdraw it.

    The palm faces up and toward the human (its normal 60 deg above the horizontal): a fully
    upturned palm puts the wrist pitch at its limit on the robot's far (-y) side. The hand
    goes toward the object's side within y in Y_RANGE (the shoulder is on the +y side), moved
    aside from objects that ``locate`` reports standing in the RWS (the forearm would hit them)."""

    name = "request"
    HEIGHT = 0.20  # above the table
    OVER_HEIGHT = 0.33  # above the table: the hand goes out and back at this height
    HAND_X = 0.06  # table x of the held-out hand, just on the robot's side of the middle line
    SHOW_SECONDS = 2.0
    DRAW_BACK = 0.16  # m the shown hand is drawn back, level, before it rises (a hand held out over it)
    PALM_UP = math.radians(60)
    Y_RANGE = (-0.12, 0.30)

    #: an object standing in the RWS closer than this (m, seen from above) to the line from the
    #: shoulder to the hand would meet the forearm, which comes up from below to a palm-up hand
    CLEAR = 0.11
    #: the hand's y positions tried across Y_RANGE for one that clears them (1 cm apart)
    Y_CANDIDATES = 43

    def _y(self) -> float:
        """The hand's y: toward the target's side, moved to where the arm clears the objects seen standing in the RWS.

        The arm is checked along the line from the shoulder to the hand, not just at the hand:
        a hand put on the far side of an object pulls the forearm across it."""
        y = float(np.clip(self.xy()[1], *self.Y_RANGE))
        obstacles = [np.asarray(xy, float) for xy in (self.locate(n) for n in OBJECTS) if xy is not None and xy[0] > 0.0]
        shoulder = np.asarray(self.robot.shoulder[:2], float)

        def clear(c: float) -> bool:
            return all(_segment_distance(o, shoulder, np.array([self.HAND_X, c])) >= self.CLEAR for o in obstacles)

        if clear(y):
            return y
        free = [c for c in np.linspace(*self.Y_RANGE, self.Y_CANDIDATES) if clear(c)]
        return float(min(free, key=lambda c: abs(c - y))) if free else y

    def phases(self):
        def goal(p, height=self.HEIGHT):
            if getattr(p, "_request_y", None) is None:
                p._request_y = p._y()
            pos = np.array([self.HAND_X, p._request_y, TABLE_Z + height])
            # palm up: the palm normal (gripper -x) turned from horizontal toward world +z
            rot = poses.side_rotation(pos, p.robot.shoulder) @ mink.SO3.from_y_radians(self.PALM_UP)
            return poses.pose(rot, pos)
        self._request_y = None
        # the hand travels over the objects of the RWS, both ways: high enough that the palm-up
        # hand, which hangs below its TCP, passes over a bottle with its stopper; a gesture: shown,
        # then withdrawn, so that it does not hide from the robot's own cameras the object the
        # person now holds out toward it
        return [Open("open"), Rise("rise", TABLE_Z + self.OVER_HEIGHT),
                Move("over", lambda p: goal(p, self.OVER_HEIGHT), duration=1.5, tolerance=0.04),
                Move("hold out open hand", goal, duration=1.0, tolerance=0.03),
                Wait("show the open hand", self.SHOW_SECONDS),
                # drawn back level first: the person may already hold the object out over the open hand, and a
                # hand rising from there goes up through her fingers
                BackOff("draw back", distance=self.DRAW_BACK), *retract_phases(over_at=TABLE_Z + self.OVER_HEIGHT)]
