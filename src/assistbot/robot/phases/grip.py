"""Closing the hand on the object (felt through contacts), or opening it to let go."""

from __future__ import annotations

from assistbot.interfaces import Status
from assistbot.robot.gripper import PRESS_N
from assistbot.robot.phases.base import Phase

#: finger angle (rad) below which the hand counts as open after a release
OPENED = 0.1
#: s a release first holds the fingers where they are, so the squeeze drops before anything moves, then
#: s over which it opens them: fingers snapping open from a firm grip kick what they let go of (a glass held
#: a little tilted, or with a finger curled beside it, falls over)
RELAX_S = 0.25
EASE_S = 0.5

class Grip(Phase):
    """Close the hand until it holds ``prim.object`` (from contacts), or open it (release)."""

    def __init__(self, close: bool, name: str | None = None, timeout: float = 1.5, settle: float = 0.4) -> None:
        self.close, self.timeout, self.settle = close, timeout, settle
        self.name = name or ("close" if close else "open")

    def start(self, prim):
        g = prim.robot.gripper
        self.since: float | None = None
        if self.close:
            g.close()
            return
        if prim.carrying:
            prim.note_set_down()
        prim.carrying = False
        self._from = g.finger_angles()
        # a hand already open has nothing to let go of gently
        self._relax, self._ease = (RELAX_S, EASE_S) if float(self._from.max()) >= OPENED else (0.0, 0.0)

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
        # let go: stop squeezing, open gently, wait until the fingers are open (the hand then backs off
        # without dragging the object)
        eased = t >= self._relax + self._ease
        g.ease_open(1.0 if eased else max(0.0, (t - self._relax) / self._ease), self._from)
        if eased and t >= self.settle and (float(g.finger_angles().max()) < OPENED or t >= self._relax + self._ease + self.timeout):
            return Status.SUCCEEDED, ""
        return Status.RUNNING, ""


class Open(Grip):
    """Open the hand (it settles sooner than after a grasp)."""

    def __init__(self, name="open"):
        super().__init__(False, name, settle=0.2)


class FreeIdleFingers(Phase):
    """Before setting down what the hand carries, open the fingers that closed past it onto the palm (the
    others keep their grip): such a finger may be curled under the object."""

    name = "free idle fingers"
    SECONDS = 0.4

    def start(self, prim):
        g = prim.robot.gripper
        self.idle = not (prim.carrying and bool(g.idle_fingers().any()))
        if not self.idle:
            g.open_idle_fingers()

    def tick(self, prim, dt, t):
        prim.robot.hold()
        return (Status.SUCCEEDED if t >= self.SECONDS else Status.RUNNING), ""
