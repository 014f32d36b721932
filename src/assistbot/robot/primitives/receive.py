"""Receive: take the object the person holds out."""

from __future__ import annotations

import numpy as np

from assistbot.robot.phases import Phase, Relative, TakeFromUnder, WaitFor
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.handing_over import close_in_only_while_held_out, no_longer_held_out, waiting_for_the_person_to_let_go
from assistbot.robot.primitives.places import free_rws_spot
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, retract_phases

#: s the hand waits beside the person's before reaching in, for them to hold the object out again
OFFER_PATIENCE = 4.0


class Receive(Primitive):
    """Take the object the human holds out (target: the human's hand), wait until the human lets go,
    put it down at ``spot`` in the RWS, let go, retract."""

    name = "receive"

    def __init__(self, robot, obj="held_out", spot=None, timeout: float = 10.0, **kw):
        """``spot``: where to put the object down; None: a free spot (`free_rws_spot`), so that a
        later hand-over, pour or grasp has room."""
        super().__init__(robot, obj, **kw)
        self.spot = None if spot is None else np.array(spot, float)
        self.timeout = timeout

    def free_spot(self) -> np.ndarray:
        if self.spot is None:
            self.spot = free_rws_spot(self)
        return self.spot

    def phases(self):
        reach = reach_and_grasp_phases(self, held_up=True)
        # from the pre-grasp on, the hand closes in on the person's: only while they still hold it out
        # (a hand lifting the bottle to pour passes through the hand-over zone, and may pause there)
        k = next(i for i, ph in enumerate(reach) if ph.name == "approach")
        reach.insert(k, WaitFor("wait while it is held out", lambda p: p.offered(), OFFER_PATIENCE,
                                "the person did not hold it out"))
        # ... and while it closes in (a person who starts to pour instead is not reached into)
        close_in_only_while_held_out(reach)
        return reach + [
            waiting_for_the_person_to_let_go(self.timeout),
            TakeFromUnder(),
            Relative("take back", [0.06, 0.0, 0.03], duration=1.0),
            *put_down_at(lambda p: p.free_spot()),
            *retract_phases(),
        ]

    def interrupted(self, phase: Phase) -> str:
        return no_longer_held_out(self, phase)
