"""Pour: fill the glass from the open bottle."""

from __future__ import annotations

import math

import mink
import numpy as np

from assistbot import catalogue
from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.phases import Move, RememberPlace, Roll, Wait
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, LIFT, side_grasp_pose
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, retract_phases
from assistbot.robot.progress import Progress
from assistbot.world.layout import TABLE_Z

#: the bottle's mouth above its grasp point (m)
BOTTLE_MOUTH_ABOVE_GRASP = catalogue.height("bottle") - GRASP_HEIGHT["bottle"]


class Pour(Primitive):
    """Grasp the open bottle, bring it beside and above the upright glass (``locate("glass")``), roll it
    until the mouth points down into the glass, hold while the liquid runs, roll back, put the bottle
    back where it stood, let go and retract."""

    name = "pour"
    TILT = math.radians(140)
    POUR_SECONDS = 2.5
    MOUTH_ABOVE_RIM = 0.035

    def __init__(self, robot, obj="bottle", glass_xy=None, **kw):
        super().__init__(robot, obj, **kw)
        self.glass_xy = None if glass_xy is None else np.asarray(glass_xy, float)
        self.home_xy: np.ndarray | None = None

    def start(self, target_xy=None) -> None:
        super().start(target_xy)
        if self.glass_xy is None:
            g = self.locate("glass")
            if g is None:
                self.progress = Progress(Status.FAILED, "locate glass", "the glass is not seen: nowhere to pour")
                return
            self._glass = np.asarray(g, float)
        else:
            self._glass = self.glass_xy

    def tick(self, dt: float, target_xy=None) -> Progress:
        # where the glass is, as seen, until the bottle tilts over it: at the start it may be hidden (behind
        # the arm) and known only from where the robot set it down, which is off by the offset at which the
        # hand held it
        if self.glass_xy is None and self.progress.status is Status.RUNNING and self.before("tilt"):
            g = self.locate("glass")
            if g is not None:
                self._glass = np.asarray(g, float)
        return super().tick(dt, target_xy)

    def interrupted(self, phase) -> str:
        # look before pouring: a glass seen upside down (turned back, or never turned: a state misread
        # while the person held it) gets nothing; the bottle is set down again (the phase's fallback)
        if self.before("tilt") and self.seen_state("glass") == "inverted":
            return "the glass is upside down: nothing to pour into"
        return ""

    def _pour_pose(self, tilt: float) -> mink.SE3:
        """TCP pose holding the bottle rolled by ``tilt`` with the mouth, at the full tilt, over the glass centre."""
        mouth = np.array([self._glass[0], self._glass[1], TABLE_Z + catalogue.height("glass") + self.MOUTH_ABOVE_RIM])
        rot0 = poses.side_rotation(mouth, self.robot.shoulder)
        rot_full = rot0 @ mink.SO3.from_x_radians(self.TILT)
        tcp = mouth - rot_full.as_matrix() @ np.array([0.0, 0.0, BOTTLE_MOUTH_ABOVE_GRASP])
        return poses.pose(rot0 @ mink.SO3.from_x_radians(tilt), tcp)

    def phases(self):
        return reach_and_grasp_phases(self) + [
            RememberPlace(),
            Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2),
            Move("over the glass", lambda p: p._pour_pose(0.0), duration=1.8),
            Roll("tilt", self.TILT, duration=1.5),
            Wait("pour", self.POUR_SECONDS),
            Roll("tilt back", -self.TILT, duration=1.2),
            *put_down_at(lambda p: p.home_xy),
            *retract_phases(),
        ]
