"""HoldBottleForStopper: hold the closed bottle out for the person to pull the stopper."""

from __future__ import annotations

import numpy as np

from assistbot.robot.controller import TCP_MIN_X
from assistbot.robot.phases import Move, RememberPlace, Wait, WaitFor
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import LIFT, side_grasp_pose
from assistbot.robot.primitives.handing_over import (
    close_in_only_while_held_out,
    hold_out,
    no_longer_held_out,
    waiting_for_the_person_to_let_go,
)
from assistbot.robot.primitives.places import OFFER_BASE, OFFER_X_MARGIN, free_rws_spot
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, reachable_on_table, retract_phases
from assistbot.robot.primitives.receive import OFFER_PATIENCE


class HoldBottleForStopper(Primitive):
    """Grasp the closed bottle, hold it out upright near the middle line where the human can pull the
    stopper, keep it there until ``stopper_removed()`` (perception), put it back where it stood, let go.

    A bottle seen in the HWS (target x < 0) is one the human holds out (``human_holds()``), or will hold
    out (standing beyond the arm's reach): the robot reaches out for it at the human's hold-out height
    and waits until the human's hand lets go; or one the human put down near the line: grasped from
    the table. Either way it is afterwards put down at a free place in the RWS (`free_rws_spot`). The grip
    holds the bottle by friction against the pull; the world decides when the fit gives."""

    name = "hold_bottle_for_stopper"
    # the person reaches the stopper from above: held as deep into her side and as low as anything the robot
    # offers, the stopper is within the reach of a short or stiff arm too (docs/measurements.md,
    # "The tremor as drawn, and the stopper within reach")
    HOLD_XY = (TCP_MIN_X + OFFER_X_MARGIN, -0.02)
    HOLD_BASE = OFFER_BASE[0]

    def __init__(self, robot, obj="bottle", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout
        self.home_xy: np.ndarray | None = None
        self._from_her_hand = False     # the bottle taken from the person's hand (else from the table)

    def _home(self) -> np.ndarray:
        """Where a bottle taken from the human's hand goes: a free place in the RWS (chosen once)."""
        if self.home_xy is None:
            self.home_xy = free_rws_spot(self)
        return self.home_xy

    def _wait_for_the_stopper(self) -> WaitFor:
        """Hold the bottle steady until the stopper is seen off it. Not seen off within ``timeout`` s (she does not
        pull it, or the hand hides the bottle's top from the cameras once she has), the hold fails, and the bottle
        is set down (`Primitive`'s safe end) where the cameras see whether it is open: sooner than an episode
        with the arm held still is judged stalled (`episode.judge.STALL_SECONDS`)."""
        return WaitFor("hold steady for the stopper", lambda p: p.stopper_removed(), self.timeout, "the stopper was not removed")

    def interrupted(self, phase) -> str:
        return no_longer_held_out(self, phase) if self._from_her_hand else ""

    def phases(self):
        self._from_her_hand = False
        hold = [*hold_out(self.HOLD_BASE, self.HOLD_XY), self._wait_for_the_stopper(), Wait("settle", 0.3)]
        if self.xy()[0] < 0.0 and not self.human_holds() and reachable_on_table(self):
            # standing on the person's side, put down there for the robot: from the table, back to the RWS.
            # Beyond the arm's reach it is not the robot's to take from there: she is about to pick it
            # up to hand it over (the fields decide on her reach for it), so the hand is held out for it
            return reach_and_grasp_phases(self) + [
                RememberPlace(),
                Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2),
                *hold,
                *put_down_at(lambda p: p._home()),
                *retract_phases(),
            ]
        if self.xy()[0] < 0.0:  # held out by the human
            # decided while she picks it up: the hand waits above its workspace until she holds it out
            # (there, and still), so that it does not meet the bottle on its way (her grip gives way to a
            # knock); a hand still short of the hand-over zone is reached out to after OFFER_PATIENCE s (she
            # brings what she holds into the open hand held out for it)
            reach = reach_and_grasp_phases(self, held_up=True)
            k = next(i for i, ph in enumerate(reach) if ph.name == "above pre-grasp")
            reach.insert(k, WaitFor("wait until it is held out", lambda p: p.held_out() and p.offered(), OFFER_PATIENCE, None))
            # ... and closes in while she still holds it out: one who puts it down instead is not reached after
            # (it is then standing on her side, for the next decision to take from the table)
            close_in_only_while_held_out(reach)
            self._from_her_hand = True
            return reach + [
                waiting_for_the_person_to_let_go(10.0),
                *hold,
                *put_down_at(lambda p: p._home()),
                *retract_phases(),
            ]
        return reach_and_grasp_phases(self) + [
            RememberPlace(),
            Move("lift", lambda p: side_grasp_pose(p, up=LIFT), duration=1.2),
            *hold_out(self.HOLD_BASE, self.HOLD_XY),
            self._wait_for_the_stopper(),
            Wait("settle", 0.3),
            *put_down_at(lambda p: p.home_xy),
            *retract_phases(),
        ]
