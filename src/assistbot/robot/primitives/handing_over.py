"""The phases of a hand-over between the robot and the person: holding the object out, letting go once it is
taken, and waiting for the person to let go of one the robot takes."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from assistbot.robot.phases import BackOff, Move, Open, Phase, SetCarrying, Wait, WaitFor, WaitForLetGo, WaitForTake
from assistbot.robot.placement import shared_spot
from assistbot.robot.primitives.carry_over import CarryOver
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, grasp_pose_at
from assistbot.robot.primitives.places import HOLD_OUT_XY, SHARED_REACH, meet_goal, offer_point
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reaching import retract_phases
from assistbot.task import OBJECTS
from assistbot.world.layout import TABLE_Z

if TYPE_CHECKING:
    from assistbot.robot.primitives.base import Primitive


#: the phase of a hand-over in which the object is held out for the person to take
OFFER_PHASE = "wait for the human to take it"


#: the phases of a hand-over from carrying the object toward the person to holding it out for them
TOWARD_THE_PERSON = ("carry over", "hold out", OFFER_PHASE)


def close_in_only_while_held_out(reach: list[Phase]) -> None:
    """A reach for what the person holds out closes in on their hand (the "approach") only while they still
    hold it out (`no_longer_held_out`): one who puts it down or starts to pour instead is not reached into;
    the open hand backs off the way it came."""
    approach = next(ph for ph in reach if ph.name == "approach")
    approach.fallback = lambda p: [BackOff("back off from the hand", distance=0.16)]


def no_longer_held_out(p: Primitive, phase: Phase) -> str:
    """Why a reach closing in on what the person holds out must stop (`close_in_only_while_held_out`)."""
    if phase.name == "approach" and not p.offered():
        return "the person no longer holds it out"
    return ""


def hand_not_free(p: Primitive, phase: Phase) -> str:
    """Why a hand-over to the person must not go on: on its way to them, or held out, the cameras see
    their hand holding something else (held out to the robot, say), which cannot take it; going on
    would carry the object into what they hold."""
    if phase.name in TOWARD_THE_PERSON and p.carrying and p.hand_busy():
        return "the person's hand is not free"
    return ""


def hold_out(base: float | None = None, xy=None, duration: float = 2.5) -> list[Phase]:
    """Hold the object in the hand out: at ``xy`` with its base ``base`` above the table, or where the
    person will take it (`offer_point`); over what stands in the way (`CarryOver`)."""
    def goal(p):
        if xy is None:
            return grasp_pose_at(p, offer_point(p), p.object)
        c = np.array([xy[0], xy[1], TABLE_Z + base + p.grasp_height])
        return grasp_pose_at(p, c, p.object)
    return [CarryOver(goal), Move("hold out", goal, duration=duration, tolerance=0.03)]


def set_down_for_the_person(p: Primitive) -> list[Phase]:
    """Not taken: set the object down on the table where the person can take it (`shared_spot`), let go, withdraw."""
    def spot(q):
        if getattr(q, "_shared", None) is None:
            standing = [xy for xy in (q.locate(n) for n in OBJECTS if n != q.object) if xy is not None]
            q._shared = shared_spot(q.robot.shoulder, SHARED_REACH, HOLD_OUT_XY, standing, min(GRASP_HEIGHT[o] for o in OBJECTS))
        return q._shared
    return put_down_at(spot) + retract_phases()


def give(timeout: float) -> list[Phase]:
    """The object is held out: wait until the human holds it (brought nearer a hand that stops short of it:
    `meet_goal`), let go, withdraw. Not taken in time, it is set down on the table within the person's reach
    before the hand-over is reported failed."""
    wait = WaitForTake(OFFER_PHASE, timeout, "the human did not take it", meet=meet_goal)
    wait.fallback = set_down_for_the_person
    return [
        wait,
        Wait("feel the pull", 0.3),
        Open("let go"), SetCarrying(False),
        BackOff("back off", distance=0.16, duration=1.2),
        *retract_phases(),
    ]


def waiting_for_the_person_to_let_go(timeout: float) -> WaitFor:
    """Both hold the object: wait until the person lets go (`WaitForLetGo`). Not let go in time, it stays
    theirs: the hand opens and withdraws (no tug of war)."""
    wait = WaitForLetGo(timeout)
    wait.fallback = lambda p: [Open("leave it to the person"), SetCarrying(False), BackOff(), *retract_phases()]
    return wait
