"""TakeFromTable: show a spot both reach, and take from the table what the person sets down there."""

from __future__ import annotations

import mink
import numpy as np

from assistbot.robot import poses
from assistbot.robot.phases import Move, Open, Rise, WaitFor
from assistbot.robot.placement import shared_spot
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, LIFT, PRE_GRASP_BACK, grasp_pose_at, side_grasp_pose
from assistbot.robot.primitives.places import HOLD_OUT_XY, SHARED_REACH, free_rws_spot
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import READY_POSE_POS, TALLEST, grasp_phase, retract_phases
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z


class TakeFromTable(Primitive):
    """The other way to take what the person cannot hand over: show, with the open hand held above it, a
    spot on the table that both reach (`placement.shared_spot`); wait until an object is seen set down
    there and let go of; take it from the table, put it down at a free spot in the RWS, retract.

    ``obj`` is None: which object it is follows from what perception sees set down under the hand."""

    name = "take_from_table"
    #: m between the hand showing the spot and the top of the tallest object (the bottle with its stopper):
    #: room for the person to bring what she holds in under the hand
    SHOW_ROOM = 0.10
    #: an object seen standing this close (m) to the spot has been set down there
    PLACED_NEAR = 0.09
    #: the spot keeps clear of the objects seen standing at table x (m) beyond this: the RWS and the
    #: person's side near the middle line
    CLEAR_OF_X = -0.2

    def __init__(self, robot, obj=None, timeout: float = 25.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout
        self.spot: np.ndarray | None = None
        self._home_xy: np.ndarray | None = None

    def start(self, target_xy=None) -> None:
        standing = [xy for xy in (self.locate(n) for n in OBJECTS) if xy is not None and xy[0] > self.CLEAR_OF_X]
        self.spot = shared_spot(self.robot.shoulder, SHARED_REACH, HOLD_OUT_XY, standing, min(GRASP_HEIGHT[o] for o in OBJECTS))
        super().start(tuple(self.spot))

    def _placed(self) -> bool:
        for name in OBJECTS:
            xy = self.locate(name)
            if xy is not None and np.hypot(xy[0] - self.spot[0], xy[1] - self.spot[1]) < self.PLACED_NEAR:
                self.object = name
                return not self.human_holds()
        return False

    def tick(self, dt, target_xy=None):
        if self.object is not None and target_xy is None:
            target_xy = self.locate(self.object)
        return super().tick(dt, target_xy)

    def phases(self):
        def show(p, back=0.0, up=None):
            c = np.array([p.spot[0], p.spot[1], TABLE_Z + (self.show_height() if up is None else up)])
            return grasp_pose_at(p, c, "glass", back=back)

        def grasp_at(p, back=0.0, up=0.0):
            return side_grasp_pose(p, back=back, up=up)
        return [
            Open("open"), Rise("rise", READY_POSE_POS[2]),
            Move("ready", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
            Move("show the spot", show, duration=1.8, tolerance=0.04),
            WaitFor("wait for it to be set down", lambda p: p._placed(), self.timeout, "nothing was set down"),
            Move("back from above", lambda p: show(p, back=PRE_GRASP_BACK), duration=1.0, tolerance=0.04),
            Move("pre-grasp", lambda p: grasp_at(p, back=PRE_GRASP_BACK), duration=1.2),
            Move("approach", lambda p: grasp_at(p), duration=1.0, tolerance=0.025),
            grasp_phase(),
            Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2),
            *put_down_at(lambda p: p._home()),
            *retract_phases(),
        ]

    def show_height(self) -> float:
        """How high (m above the table) the open hand shows the spot: its lowest edge SHOW_ROOM above the
        top of the tallest object."""
        return TALLEST + self.robot.gripper.reach_below + self.SHOW_ROOM

    def _home(self) -> np.ndarray:
        """Where the object taken goes: a free spot in the RWS (chosen once)."""
        if self._home_xy is None:
            self._home_xy = free_rws_spot(self)
        return self._home_xy
