"""Holding an object out until the person takes it: seen holding it, or felt pulling; brought nearer a hand that
stops short of it."""

from __future__ import annotations

from typing import Callable

import mink
import numpy as np

from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.phases.wait import WaitFor


class WaitForTake(WaitFor):
    """Hold the object out until the person takes it: felt, as the wrist's force moves PULL_N away from
    what it was once the held-out hand had come to rest, the person's grip taking up part of the load.

    Not seen: the cameras read a hand closing around the object as holding it before it does (the
    fingers hide the object in the robot's hand), and a hand let go of too soon drops the object.

    ``meet(prim, hand)``: the pose that brings the object nearer the person's hand seen at ``hand``, or None.
    A hand seen reaching for the object and keeping still for MEET_STILL s without touching it (felt: the
    wrist's force within TOUCH_N of rest) has gone as far as this person reaches: the object is brought
    nearer them (`meet_goal`, MEET_SECONDS), MEET_TRIES times at most, as a person hands a thing to someone
    who cannot quite reach it."""

    PULL_N = 0.8
    REST_SECONDS = 0.3   # the force at rest is read after this (and compared again this long after a bring)
    FELT_TICKS = 2       # in a row: one jolt is not a pull
    MEET_STILL = 2.5     # s the reaching hand keeps still before the object is brought to it (longer than
                         # a reach pauses on its way, at the approach pose)
    TOUCH_N = 0.3        # N the wrist's force moves from rest when the person's hand touches the object: a
                         # hand at it, holding it, is not brought anything (moving it would pull it away)
    STILL_WITHIN = 0.02   # m from the median of those frames that STILL_SHARE of them lie within (the posture
    STILL_SHARE = 0.7     # read flickers from frame to frame, and each class places the hand a little apart)
    SEEN_SHARE = 0.7     # of the control ticks of those MEET_STILL s that must show the reaching hand
    NOW_FRAMES = 10      # the latest control ticks showing it, which must all lie within STILL_WITHIN
    MEET_SECONDS = 1.0
    MEET_TRIES = 3
    MOVED = 0.04          # m from that stop that a hand seen since has moved: it reaches again
    RETRY_SECONDS = 6.0   # added to the wait for each time: the person reaches again once the object is still

    def __init__(self, name: str, timeout: float, reason: str,
                 meet: Callable[[object, np.ndarray], mink.SE3 | None] | None = None) -> None:
        super().__init__(name, lambda p: self._felt >= self.FELT_TICKS, timeout, reason)
        self.meet = meet
        self.base_timeout = timeout

    def start(self, prim):
        super().start(prim)
        self._rest = None
        self._rest_at = self.REST_SECONDS
        self._felt = 0
        self._hand: list[tuple[float, np.ndarray | None]] = []
        self._meets = 0
        self._met: np.ndarray | None = None   # where the hand had stopped when the object was last brought to it
        self._bringing: tuple[mink.SE3, mink.SE3, float] | None = None
        self.timeout = self.base_timeout

    def _stopped_hand(self, prim, t: float) -> np.ndarray | None:
        """Where the hand reaching for the object has kept still for MEET_STILL s, or None."""
        hand = prim.reaching_hand()
        if hand is not None and self._met is not None and float(np.abs(np.asarray(hand) - self._met).max()) > self.MOVED:
            self._met = None    # the hand has moved since: it reaches again
        self._hand.append((t, None if hand is None else np.asarray(hand, float)))
        while self._hand and self._hand[0][0] < t - self.MEET_STILL:
            self._hand.pop(0)
        seen = np.array([h for _, h in self._hand if h is not None])
        if t - self._hand[0][0] < self.MEET_STILL - 0.05 or len(seen) < self.SEEN_SHARE * len(self._hand):
            return None
        median = np.median(seen, axis=0)
        near = np.abs(seen - median).max(axis=1) <= self.STILL_WITHIN
        if near.mean() < self.STILL_SHARE or not near[-self.NOW_FRAMES:].all():
            return None     # moving, or has just moved off (the latest frames say where it is now)
        if self._met is not None and float(np.abs(seen - self._met).max()) <= self.MOVED:
            return None     # still the stop the object was brought to: the person has not reached again yet
        return median

    def _bring(self, prim, dt: float, t: float) -> None:
        origin, goal, t0 = self._bringing
        s = (t - t0) / self.MEET_SECONDS
        prim.robot.move_toward(poses.interpolate(origin, goal, poses.min_jerk(min(1.0, s))), dt)
        if s >= 1.0:
            # the hand is there: the force at rest (in the world's axes) stays what it was (read anew, it would
            # take in a grip that closed while the object came, and her pull would never be felt); it is compared
            # again once the bring's jolt has settled, and the person's hand is watched anew
            self._bringing, self._rest_at, self._hand = None, t + self.REST_SECONDS, []

    def tick(self, prim, dt, t):
        if self._bringing is not None:
            self._bring(prim, dt, t)
            return Status.RUNNING, ""
        force = prim.robot.gripper.wrist_force_world()
        off_rest: float | None = None   # N the wrist's force lies from rest, once that is read
        if self._rest is None:
            if t >= self._rest_at:
                self._rest, off_rest = force, 0.0
        elif t >= self._rest_at:
            off_rest = float(np.linalg.norm(force - self._rest))
            self._felt = self._felt + 1 if off_rest > self.PULL_N else 0
        if self.meet is not None and self._meets < self.MEET_TRIES and off_rest is not None and off_rest <= self.TOUCH_N:
            hand = self._stopped_hand(prim, t)
            goal = self.meet(prim, hand) if hand is not None else None
            if goal is not None:
                self._met = hand
                self._meets += 1
                self.timeout += self.MEET_SECONDS + self.RETRY_SECONDS
                self._bringing = (prim.robot.commanded_tcp_pose(), goal, t)
                self._bring(prim, dt, t)
                return Status.RUNNING, ""
        return super().tick(prim, dt, t)
