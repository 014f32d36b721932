"""Holding an object out until the person takes it: seen holding it, or felt pulling."""

from __future__ import annotations

import numpy as np

from assistbot.robot.phases.wait import WaitFor


class WaitForTake(WaitFor):
    """Hold the object out until the person takes it: felt, as the wrist's force moves PULL_N away from
    what it was once the held-out hand had come to rest, the person's grip taking up part of the load.

    Not seen: the cameras read a hand closing around the object as holding it before it does (the
    fingers hide the object in the robot's hand), and a hand let go of too soon drops the object."""

    PULL_N = 0.8
    REST_SECONDS = 0.3   # the force at rest is read after this
    FELT_TICKS = 2       # in a row: one jolt is not a pull

    def __init__(self, name: str, timeout: float, reason: str) -> None:
        super().__init__(name, lambda p: self._felt >= self.FELT_TICKS, timeout, reason)

    def start(self, prim):
        super().start(prim)
        self._rest = None
        self._felt = 0

    def tick(self, prim, dt, t):
        force = prim.robot.gripper.wrist_force()
        if self._rest is None:
            if t >= self.REST_SECONDS:
                self._rest = force
        elif np.linalg.norm(force - self._rest) > self.PULL_N:
            self._felt += 1
        else:
            self._felt = 0
        return super().tick(prim, dt, t)
