"""Vision perception for episodes: the robot's head cameras through `assistbot.vision`.

Each perception tick takes a stereo pair and turns pixels into a Percept; the robot's
proprioception (what its gripper holds, its action and status, where its hand is) is added
from the robot side, as a real robot knows its own body.

Pipelined (the default): the pair taken at one perception tick is drawn on a render thread
while the world steps on, and processed at the next tick, so cognition sees the world as it
was one perception period (100 ms at 10 Hz) before -- the latency of a camera that streams to
a processing computer.  What vision needs of the robot's own body (the hand's position, what
it holds) is taken with the pair.  ``pipelined=False`` renders and processes at the tick
itself (no latency, and no second core at work).
"""

from __future__ import annotations

import time

import numpy as np

from assistbot.cognition.percept import Percept, RobotPercept
from assistbot.vision import CaptureConfig, StereoCapture, StereoFrame, Vision
from assistbot.world import TABLE_Z


class VisionPerception:
    """The episode's `Perception` through the robot's head cameras."""

    name = "vision"
    label = "perception: vision"

    def __init__(self, world, seed: int = 0, dropout: float = 0.0, width: int = 320, height: int = 240,
                 pipelined: bool = True) -> None:
        self.world = world
        self.vision = Vision()  # a missing template library is a UserError naming `assistbot templates`
        self.pipelined = bool(pipelined)
        self.capture = StereoCapture(world.model, CaptureConfig(width=width, height=height, dropout=dropout, seed=seed),
                                     threaded=self.pipelined)
        self._tcp_site = world.model.site("robot_tcp").id
        self._frame = None
        self._percept: Percept | None = None
        self._taken = None  # the pair started at the last tick (pipelined)
        self.render_seconds = 0.0  # of the last call: the time the caller spent on rendering
        self.drawn_seconds = 0.0  # the renderer's own time over all pairs (on its thread when pipelined)

    def _body(self, robot: RobotPercept) -> dict:
        tcp = self.world.data.site_xpos[self._tcp_site].copy()  # forward kinematics of the robot's own arm
        tcp[2] -= TABLE_Z
        return {"tcp": tcp, "holding": robot.holding}

    def perceive(self, t: float, robot: RobotPercept) -> Percept:
        t0 = time.perf_counter()
        if self.pipelined:
            frame = self.capture.collect(self._taken) if self._taken is not None else None
            self.world.sync_liquid()
            self._taken = self.capture.start(self.world.data, meta=self._body(robot))
            if frame is None:  # the first tick: nothing has been drawn yet
                frame = StereoFrame(t, None, None, self._taken.cams, dropped=True)
        else:
            self.world.sync_liquid()
            frame = self.capture.grab(self.world.data)
            frame.meta.update(self._body(robot))
        self.render_seconds = time.perf_counter() - t0
        self.drawn_seconds += frame.render_ms / 1000.0
        p = self.vision.perceive(frame, robot_holding=frame.meta.get("holding"), robot_tcp=frame.meta.get("tcp"))
        p.t = t  # delivered now, whatever instant the pixels show
        p.robot = RobotPercept(holding=robot.holding, action=robot.action, status=robot.status)
        self._frame, self._percept = frame, p
        return p.validate()

    def overlay(self) -> np.ndarray | None:
        if self._frame is None or self._percept is None:
            return None
        return self.vision.overlay(self._frame, self._percept)

    def close(self) -> None:
        self.capture.close()
