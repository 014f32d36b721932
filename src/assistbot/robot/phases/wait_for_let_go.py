"""Holding an object the person still holds until she lets go: felt as its weight coming onto the hand."""

from __future__ import annotations

from assistbot.robot.phases.wait import WaitFor
from assistbot.robot.phases.wait_for_take import WaitForTake


class WaitForLetGo(WaitFor):
    """Both hold the object: wait until the person lets go, felt as the wrist's vertical force moving PULL_N
    (as a pull is felt, `WaitForTake`) from what it was when this wait began: the load her grip carried comes
    onto the robot's hand. Only after SEEN_AFTER s is her hand, seen not holding it, taken as let go (a
    let-go felt too little, or before the wait began): the robot's hand round the object hides her fingers
    on it, and the cameras read her hand as open while it still holds, so that a hand going by the cameras
    alone carried the object off through her fingers."""

    PULL_N = WaitForTake.PULL_N
    FELT_TICKS = WaitForTake.FELT_TICKS
    SEEN_AFTER = 3.0

    def __init__(self, timeout: float) -> None:
        super().__init__("wait for the human to let go", self._let_go, timeout, "the human did not let go")

    def start(self, prim):
        super().start(prim)
        self._rest: float | None = None
        self._felt = 0
        self._t = 0.0

    def _let_go(self, prim) -> bool:
        return self._felt >= self.FELT_TICKS or (self._t >= self.SEEN_AFTER and not prim.human_holds())

    def tick(self, prim, dt, t):
        self._t = t
        fz = float(prim.robot.gripper.wrist_force_world()[2])
        if self._rest is None:
            self._rest = fz
        self._felt = self._felt + 1 if abs(fz - self._rest) > self.PULL_N else 0
        return super().tick(prim, dt, t)
