"""Move: a minimum-jerk motion of the hand (TCP) to a goal pose, re-read every tick."""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import mink
import numpy as np

from assistbot.interfaces import Status
from assistbot.robot import poses
from assistbot.robot.controller import REACH, TCP_MIN_X
from assistbot.robot.gripper import GRASP_N
from assistbot.robot.phases.base import Phase

if TYPE_CHECKING:
    from assistbot.robot.primitives import Primitive


UNREACHABLE_PATIENCE = 0.3  # s in all that a Move's target may be out of reach before the move fails (3 perception ticks)
REACH_WAIT = 12.0           # s a reaching-out move waits for its goal to come within reach
#: s a reaching-out move holds the open hand still at its reach before it closes on a goal lying within it
#: (`Move.close_short`): time for the person to bring what they hold in deeper, as they do when they can
CLOSE_SHORT_WAIT = 4.0
#: control ticks (in all) on which the IK may find no step toward the goal before a move of the arm fails
MAX_FAILED_TICKS = 10
#: m short of REACH that a hand reaching out toward an unreachable goal stops
REACH_OUT_MARGIN = 0.005
#: m beyond TCP_MIN_X (into the HWS) a goal may lie and still count as within the hand-over zone
HANDOVER_X_SLACK = 0.01


def unreachable(prim, goal: mink.SE3, name: str = "target") -> str:
    """Why the hand cannot go to ``goal``: beyond the arm's reach, or deeper into the person's workspace than
    the hand-over zone; "" when it can."""
    dist = prim.robot.reach_distance(goal.translation())
    if dist > REACH:
        return (f"{name}: target {np.round(goal.translation(), 2).tolist()} out of reach "
                f"({dist:.2f} m from the shoulder > {REACH:.2f} m)")
    if goal.translation()[0] < TCP_MIN_X - HANDOVER_X_SLACK:
        return (f"{name}: target x {goal.translation()[0]:.2f} m is beyond the hand-over zone "
                f"(the hand may reach x >= {TCP_MIN_X:.2f} m)")
    return ""


class Move(Phase):
    """Minimum-jerk TCP motion from the current commanded pose to ``goal(prim)`` (re-read every tick).

    ``reach_out``: a goal out of the arm's reach (an object the person holds out too far) is not a
    failure at once: the hand goes as far toward it as it can and waits there, open, up to REACH_WAIT
    s, for the goal to come within reach (the person, seeing the hand held out for what they hold,
    brings it closer); the move then goes on to the goal itself.

    ``close_short``: for a reaching-out move, how far (m) beyond the hand held out at its reach, along the
    approach, the goal may lie and still be taken there (None: never): an object that lies that deep in the
    open hand is within its fingers, and a person whose arm can bring it no nearer leaves it there. After
    CLOSE_SHORT_WAIT s still at its reach the move ends there, and the grasp closes short of the palm.

    ``arrive_on_touch``: a move that ends sooner, on the palm feeling something pressed into it as firmly
    as a grasp holds (GRASP_N): a person who sees the open hand held out for what they hold brings it into
    the hand, where the cameras, the hand in front, often no longer see it to follow.

    ``may_stop_above``: a move down that may end sooner, on the object in the hand meeting the table (it sits
    higher in the hand than assumed): a hand still above its goal when the settle time is up, but over it
    within ``tolerance``, has arrived; it then holds where it stopped, not pressing on."""

    def __init__(self, name: str, goal: Callable[["Primitive"], mink.SE3], duration: float = 1.5,
                 tolerance: float = 0.02, settle: float = 1.5, check_reach: bool = True, reach_out: bool = False,
                 may_stop_above: bool = False, arrive_on_touch: bool = False,
                 close_short: Callable[["Primitive"], float] | None = None) -> None:
        self.name, self.goal, self.duration = name, goal, duration
        self.close_short = close_short
        self.arrive_on_touch = arrive_on_touch
        self.tolerance, self.settle, self.check_reach, self.reach_out = tolerance, settle, check_reach, reach_out
        self.may_stop_above = may_stop_above
        self.timeout = duration + settle

    def start(self, prim: "Primitive") -> None:
        self.origin = prim.robot.commanded_tcp_pose()
        self.failures = 0
        self.unreachable = 0.0  # s this move's target has been out of reach
        self.waited = 0.0       # s spent reaching out toward an unreachable goal
        self.reaching = False   # reaching out right now
        self.t0 = 0.0           # phase time the move (re)started at

    @staticmethod
    def _within_reach(prim, goal: mink.SE3) -> mink.SE3:
        """The goal moved back along the line to the shoulder until the arm reaches it, never deeper into the
        HWS than TCP_MIN_X: the open hand held out in front of what it reaches for, fingers toward it."""
        pos = goal.translation().copy()
        sh = prim.robot.shoulder
        d = float(np.linalg.norm(pos - sh))
        if d > REACH - REACH_OUT_MARGIN:
            pos = sh + (pos - sh) * (REACH - REACH_OUT_MARGIN) / d
        pos[0] = max(pos[0], TCP_MIN_X)
        return poses.pose(goal.rotation(), pos)

    def _lies_in_the_hand(self, prim, goal: mink.SE3, held_out: mink.SE3, t: float) -> bool:
        """The hand, held out at its reach (``held_out``) for CLOSE_SHORT_WAIT s, has ``goal`` within
        `close_short` of it along the approach, and no farther aside than the tolerance."""
        if self.close_short is None or self.waited < CLOSE_SHORT_WAIT or t - self.t0 < self.duration:
            return False
        tcp = prim.robot.tcp_pose().translation()
        if np.linalg.norm(tcp - held_out.translation()) > self.tolerance:
            return False
        off = goal.translation() - tcp
        ax = poses.approach_axis(goal.rotation())
        depth = float(off @ ax)
        aside = off - depth * ax
        return bool(0.0 <= depth <= self.close_short(prim) and np.hypot(aside[0], aside[1]) <= self.tolerance)

    def _stopped_above(self, prim, goal: mink.SE3) -> bool:
        off = prim.robot.tcp_pose().translation() - goal.translation()
        return bool(off[2] > 0.0 and float(np.hypot(off[0], off[1])) < self.tolerance)

    def tick(self, prim, dt, t):
        if self.arrive_on_touch and prim.robot.gripper.pressure()["palm"] > GRASP_N:
            prim.robot.hold()
            return Status.SUCCEEDED, ""
        goal = self.goal(prim)
        why = unreachable(prim, goal, self.name) if self.check_reach else ""
        if why and self.reach_out:
            self.waited += dt
            held_out = self._within_reach(prim, goal)
            if self._lies_in_the_hand(prim, goal, held_out, t):
                return Status.SUCCEEDED, ""
            if self.waited >= REACH_WAIT:
                return Status.FAILED, why
            via = poses.interpolate(self.origin, held_out, poses.min_jerk((t - self.t0) / self.duration))
            prim.robot.move_toward(via, dt)
            self.reaching = True
            return Status.RUNNING, ""
        if self.reaching:   # the goal has come within reach: a move of its own from where the hand is
            self.reaching, self.origin, self.t0 = False, prim.robot.commanded_tcp_pose(), t
        t -= self.t0
        if why:
            # one misread frame must not end the action: the arm waits where it is, and the move
            # fails once its target has been out of reach for UNREACHABLE_PATIENCE in all
            self.unreachable += dt
            if self.unreachable >= UNREACHABLE_PATIENCE - 1e-9:
                return Status.FAILED, why
            prim.robot.hold()
            return Status.RUNNING, ""
        via = poses.interpolate(self.origin, goal, poses.min_jerk(t / self.duration))
        res = prim.robot.move_toward(via, dt)
        if not res.ok:
            self.failures += 1
            if self.failures >= MAX_FAILED_TICKS:
                return Status.FAILED, f"{self.name}: {res.reason}"
        if t >= self.duration:
            err = float(np.linalg.norm(prim.robot.tcp_pose().translation() - goal.translation()))
            if err < self.tolerance:
                return Status.SUCCEEDED, ""
            if t >= self.timeout and self.may_stop_above and self._stopped_above(prim, goal):
                prim.robot.reset_command()
                return Status.SUCCEEDED, ""
            if t >= self.timeout:
                return Status.FAILED, f"{self.name}: did not reach the target (TCP {100 * err:.1f} cm away)"
        return Status.RUNNING, ""
