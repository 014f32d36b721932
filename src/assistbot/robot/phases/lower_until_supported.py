"""Lowering the held object onto the table until the table is felt to carry it."""

from __future__ import annotations

import numpy as np

from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.phases.base import Phase


class LowerUntilSupported(Phase):
    """Lower the held object until the table is felt to carry it: the wrist force moves SUPPORT_N away from
    what it was once the hand had come to rest (the object's weight leaves the hand), or the hand can go no
    lower (the arm keeps the hand off the table): the grip is then eased so that the object slides down
    between the fingers onto the table. Where the object was grasped lower or higher than assumed (a
    held-out object placed a few cm off by vision), the put-down still ends with it standing on the table."""

    name = "lower until supported"
    SUPPORT_N = 0.8
    REST_SECONDS = 0.3    # held still first: the force at rest is read after the last move's jolt
    FORCE_TAU = 0.1       # s: the force is low-passed, the arm's own servo jitter (~0.7 N) is not the table
    FELT_TICKS = 3        # in a row
    SPEED = 0.03          # m/s
    MAX_DROP = 0.07       # m below where the put-down ended
    STALL_SECONDS = 0.3   # no progress this long: the hand is as low as it goes
    LOOSEN = 0.35         # how far the grip opens to let the object slide down (fraction of fully open)
    SLIDE_SECONDS = 0.8
    PROGRESS_M = 0.002    # the hand is still going down while it gets this much lower than it has been
    TIMEOUT_MARGIN_S = 1.0  # beyond the time the whole drop and the slide take

    def start(self, prim):
        self.origin = prim.robot.commanded_tcp_pose()
        self.f0: np.ndarray | None = None
        self.force = prim.robot.gripper.wrist_force()
        self.felt = 0
        self.best_z, self.since = float(prim.robot.tcp_pose().translation()[2]), self.REST_SECONDS
        self.loosened: float | None = None
        self.timeout = self.REST_SECONDS + self.MAX_DROP / self.SPEED + self.TIMEOUT_MARGIN_S + self.SLIDE_SECONDS

    def tick(self, prim, dt, t):
        self.force += (prim.robot.gripper.wrist_force() - self.force) * min(1.0, dt / self.FORCE_TAU)
        if t < self.REST_SECONDS:
            prim.robot.hold()
            return Status.RUNNING, ""
        if self.f0 is None:
            self.f0 = self.force.copy()
        self.felt = self.felt + 1 if np.linalg.norm(self.force - self.f0) > self.SUPPORT_N else 0
        if self.felt >= self.FELT_TICKS:
            prim.robot.hold()
            prim.supported = True
            return Status.SUCCEEDED, ""
        z = float(prim.robot.tcp_pose().translation()[2])
        if z < self.best_z - self.PROGRESS_M:
            self.best_z, self.since = z, t
        if self.loosened is not None:
            # the grip eased: the object slides down between the fingers onto the table
            prim.robot.hold()
            if t - self.loosened < self.SLIDE_SECONDS:
                return Status.RUNNING, ""
            prim.supported = True
            return Status.SUCCEEDED, ""
        if t - self.since > self.STALL_SECONDS or t >= self.timeout:
            # as low as the hand goes and not yet on the table (grasped lower than assumed): ease the grip
            # rather than drop it from there
            prim.robot.gripper.open(self.LOOSEN)
            self.loosened = t
            return Status.RUNNING, ""
        pos = self.origin.translation() - [0.0, 0.0, min(self.MAX_DROP, self.SPEED * (t - self.REST_SECONDS))]
        prim.robot.move_toward(poses.pose(self.origin.rotation(), pos), dt)
        return Status.RUNNING, ""
