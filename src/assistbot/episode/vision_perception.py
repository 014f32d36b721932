"""Vision perception for episodes: the robot's head cameras through `assistbot.vision`.

Each perception tick renders both head cameras and turns the pixels into a
Percept; the robot's proprioception (what its gripper holds, its action and
status, where its hand is) is added from the robot side, as a real robot
knows its own body.
"""

from __future__ import annotations

import numpy as np

from assistbot.cognition.percept import Percept, RobotPercept
from assistbot.world import TABLE_Z


class VisionPerception:
    label = "vision"

    def __init__(self, world, seed: int = 0, dropout: float = 0.0, width: int = 320, height: int = 240) -> None:
        from assistbot.vision import CaptureConfig, StereoCapture, Vision

        self.world = world
        self.vision = Vision()  # a missing template library is a UserError naming `assistbot templates`
        self.capture = StereoCapture(world.model, CaptureConfig(width=width, height=height, dropout=dropout, seed=seed))
        self._tcp_site = world.model.site("robot_tcp").id
        self._frame = None
        self._percept: Percept | None = None
        self.render_seconds = 0.0

    def perceive(self, t: float, robot: dict) -> Percept:
        self.world.sync_liquid()
        frame = self.capture.grab(self.world.data)
        self.render_seconds = frame.render_ms / 1000.0  # of this call, for the episode's wall-time split
        tcp = self.world.data.site_xpos[self._tcp_site].copy()  # forward kinematics of the robot's own arm
        tcp[2] -= TABLE_Z
        p = self.vision.perceive(frame, robot_holding=robot.get("holding"), robot_tcp=tcp)
        p.robot = RobotPercept(holding=robot.get("holding"), action=robot.get("action"), status=robot.get("status", "idle"))
        self._frame, self._percept = frame, p
        return p.validate()

    def overlay(self) -> np.ndarray | None:
        if self._frame is None or self._percept is None:
            return None
        return self.vision.overlay(self._frame, self._percept)

    def close(self) -> None:
        self.capture.close()
