"""Closing the hand on the object (felt through contacts), or opening it to let go."""

from __future__ import annotations

from assistbot.interfaces import Status
from assistbot.robot.gripper import PRESS_N
from assistbot.robot.phases.base import Phase

#: finger angle (rad) below which the hand counts as open after a release
OPENED = 0.1

class Grip(Phase):
    """Close the hand until it holds ``prim.object`` (from contacts), or open it (release)."""

    def __init__(self, close: bool, name: str | None = None, timeout: float = 1.5, settle: float = 0.4) -> None:
        self.close, self.timeout, self.settle = close, timeout, settle
        self.name = name or ("close" if close else "open")

    def start(self, prim):
        g = prim.robot.gripper
        g.close() if self.close else g.open()
        if not self.close and prim.carrying:
            prim.note_set_down()
        if not self.close:
            prim.carrying = False
        self.since: float | None = None

    def tick(self, prim, dt, t):
        prim.robot.hold()
        g = prim.robot.gripper
        if self.close:
            if g.grasps():
                if prim.object == "held_out":
                    # the hand feels that it holds, not what: what the person was seen holding out
                    prim.object = prim.identify() or "held_out"
                self.since = t if self.since is None else self.since
                if t - self.since >= self.settle:
                    return Status.SUCCEEDED, ""
            else:
                self.since = None
            if g.fully_closed():
                return Status.FAILED, f"{self.name}: the hand closed on nothing"
            if t >= self.timeout:
                pressing = [part for part, f in g.pressure().items() if f > PRESS_N]
                return (Status.FAILED,
                        f"{self.name}: no grasp of {prim.object} after {self.timeout:.1f} s (pressing: {pressing or 'nothing'})")
            return Status.RUNNING, ""
        # let go: wait until the fingers are open (the hand then backs off without dragging the object)
        if t >= self.settle and (float(g.finger_angles().max()) < OPENED or t >= self.timeout):
            return Status.SUCCEEDED, ""
        return Status.RUNNING, ""


class Open(Grip):
    """Open the hand (it settles sooner than after a grasp)."""

    def __init__(self, name="open"):
        super().__init__(False, name, settle=0.2)
