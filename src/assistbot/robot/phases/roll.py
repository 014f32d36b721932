"""Roll: turning the hand about its approach axis in place (the glass turned upright, the bottle tilted to pour)."""

from __future__ import annotations

import mink
import numpy as np

from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.phases.base import Phase
from assistbot.robot.phases.move import MAX_FAILED_TICKS


class Roll(Phase):
    """Roll the hand about its approach axis by ``angle`` (rad), minimum jerk, the TCP staying in place."""

    #: how close to the rolled pose the hand must come for the roll to have succeeded
    ROTATION_TOLERANCE_RAD = 0.12
    POSITION_TOLERANCE_M = 0.03

    def __init__(self, name: str, angle: float, duration: float = 1.5, settle: float = 1.5) -> None:
        self.name, self.angle, self.duration = name, angle, duration
        self.timeout = duration + settle

    def start(self, prim):
        self.origin = prim.robot.commanded_tcp_pose()
        self.failures = 0

    def _pose(self, s: float) -> mink.SE3:
        return poses.pose(self.origin.rotation() @ mink.SO3.from_x_radians(s * self.angle), self.origin.translation())

    def tick(self, prim, dt, t):
        res = prim.robot.move_toward(self._pose(poses.min_jerk(t / self.duration)), dt)
        if not res.ok:
            self.failures += 1
            if self.failures >= MAX_FAILED_TICKS:
                return Status.FAILED, f"{self.name}: {res.reason}"
        if t >= self.duration:
            goal = self._pose(1.0)
            now = prim.robot.tcp_pose()
            rot_err = float(np.linalg.norm((goal.rotation().inverse() @ now.rotation()).log()))
            pos_err = float(np.linalg.norm(now.translation() - goal.translation()))
            if rot_err < self.ROTATION_TOLERANCE_RAD and pos_err < self.POSITION_TOLERANCE_M:
                return Status.SUCCEEDED, ""
            if t >= self.timeout:
                return Status.FAILED, f"{self.name}: the wrist did not turn ({np.degrees(rot_err):.0f} deg, {100 * pos_err:.1f} cm off)"
        return Status.RUNNING, ""


class Unroll(Roll):
    """An empty hand left upside down (it turned the glass, +pi about its approach axis) rolls back by -pi in
    place, the way it came. Going straight for the upright rest pose, the IK would take the short way on, into
    the wrist joints' limits, and stop there short of the pose. Upright already, or holding something (whose
    orientation the roll would change), it is `idle`."""

    def __init__(self, name: str = "unroll", duration: float = 1.5) -> None:
        super().__init__(name, -np.pi, duration=duration)

    def start(self, prim):
        super().start(prim)
        self.idle = not poses.upside_down(self.origin.rotation()) or prim.carrying
