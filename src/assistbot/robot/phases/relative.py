"""Moves of the hand relative to where it is when they start: up, by an offset, back along its approach."""

from __future__ import annotations

import numpy as np

from assistbot.robot import poses
from assistbot.robot.phases.move import Move, unreachable
from assistbot.robot.primitives.geometry import WALL_TOP
from assistbot.world.layout import TABLE_Z


class Rise(Move):
    """Straight up from where the hand is to ``z`` (world, m), keeping its orientation."""

    def __init__(self, name: str, z: float, duration: float = 1.0) -> None:
        super().__init__(name, lambda p: self._goal, duration=duration, tolerance=0.08, settle=0.5)
        self.z = z

    def start(self, prim):
        super().start(prim)
        pos = self.origin.translation().copy()
        pos[2] = max(pos[2], self.z)
        self._goal = poses.pose(self.origin.rotation(), pos)


class Relative(Move):
    """Minimum-jerk move by ``offset`` (world, m) from the commanded pose at the phase's start, same orientation."""

    def __init__(self, name: str, offset, duration: float = 1.0, tolerance: float = 0.03) -> None:
        super().__init__(name, lambda p: self._goal, duration=duration, tolerance=tolerance)
        self.offset = np.asarray(offset, float)

    def start(self, prim):
        super().start(prim)
        self._goal = poses.pose(self.origin.rotation(), self.origin.translation() + self.offset)


class BackOff(Relative):
    """Withdraw the open hand along its approach axis (back toward the robot), level by default: the open
    fingers may still touch what they let go of (the glass fills their widest opening), and a hand that
    rises as it withdraws presses them against the wall and drags the object along."""

    def __init__(self, name: str = "back off", distance: float = 0.14, up: float = 0.0, duration: float = 1.0) -> None:
        super().__init__(name, np.zeros(3), duration=duration, tolerance=0.04)
        self.distance, self.up = distance, up

    def start(self, prim):
        Move.start(self, prim)
        ax = poses.approach_axis(self.origin.rotation())
        ax[2] = 0.0
        ax /= max(np.linalg.norm(ax), 1e-9)
        self._goal = poses.pose(self.origin.rotation(), self.origin.translation() - self.distance * ax + [0, 0, self.up])


class TakeFromUnder(BackOff):
    """Down by ``drop`` m, and ``back`` m level toward the robot, with what the hand has just taken from the
    person's hand: out from under her fingers, which a grip from above hangs down the object's side between it
    and the palm (taken back level, the robot's fingers round the object's far side sweep through hers). As far
    down as the object's base (as seen when it was grasped, `Primitive.base_z`) stays ``clear`` m above the
    table, and as the arm reaches: a hand at the arm's reach held out and straight down would go beyond it,
    which the way back makes up for."""

    STEPS = 6     # the drops tried, from the whole down to none

    def __init__(self, name: str = "take from under", drop: float = 0.05, back: float = 0.04, clear: float = 0.02,
                 duration: float = 1.0) -> None:
        super().__init__(name, distance=back, duration=duration)
        self.drop, self.clear = drop, clear

    def start(self, prim):
        room = max(0.0, min(self.drop, prim.base_z() - (TABLE_Z + self.clear)))
        for down in np.linspace(room, 0.0, self.STEPS):
            self.up = -float(down)
            super().start(prim)
            if not unreachable(prim, self._goal):
                return


class RiseClear(Rise):
    """After letting go of an object set down on the table, when the hand held it so high that its upper
    finger stood above the object's wall (`WALL_TOP`: the glass's rim), rise straight up until the hand's
    lowest edge clears that top, before backing off: the open finger then hangs over the mouth, and a level
    back-off hooks the rim from inside and drags the object over. How high it held the object is felt: the
    table carries the object (`LowerUntilSupported`), so the hand stands at its grasp height above the
    table. Held lower, the hand backs off level (`BackOff`) at once."""

    def __init__(self, name: str = "rise clear of the top", duration: float = 1.5) -> None:
        super().__init__(name, 0.0, duration=duration)

    def start(self, prim):
        obj = prim.let_go_of
        g = prim.robot.gripper
        z = float(prim.robot.tcp_pose().translation()[2])
        self.idle = obj not in WALL_TOP or z + g.reach_above <= TABLE_Z + WALL_TOP[obj]
        self.z = TABLE_Z + WALL_TOP.get(obj, 0.0) + g.reach_below
        super().start(prim)
