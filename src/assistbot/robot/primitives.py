"""Motion primitives: small objects that realise the robot's AEL actions in the physics.

A primitive is a list of phases (move the TCP along a minimum-jerk profile,
close or open the hand, wait for a condition). ``start(target_xy)`` begins
it; ``tick(dt, target_xy) -> Progress`` is called once per control tick with
the current perception of the action's target (table x, y of the object or
the human's hand, or None when it is not seen). The perception feeds the
primitive's `TargetField`; the field's peak is the x, y the arm goes to,
while heights and approach orientations come from the primitive.

Every phase has a time limit; a primitive that cannot do its job ends
FAILED with a reason (unreachable target, IK without solution, nothing in the
hand, object slipped, human did not take the object).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Callable

import mink
import numpy as np

from assistbot.robot import poses
from assistbot.robot.controller import HANDOVER_DEPTH, REACH, RobotController
from assistbot.robot.ik import READY_POSTURE
from assistbot.robot.target_field import TargetField

TABLE_Z = 0.75


class Status(enum.Enum):
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"


@dataclass
class Progress:
    status: Status
    phase: str = ""
    reason: str = ""
    t: float = 0.0


class Phase:
    name = "phase"
    timeout = 5.0

    def start(self, prim: "Primitive") -> None:
        pass

    def tick(self, prim: "Primitive", dt: float, t: float) -> tuple[Status, str]:
        raise NotImplementedError


class Move(Phase):
    """Minimum-jerk TCP motion from the current commanded pose to ``goal(prim)`` (re-read every tick)."""

    def __init__(self, name: str, goal: Callable[["Primitive"], mink.SE3], duration: float = 1.5,
                 tolerance: float = 0.02, settle: float = 1.5, check_reach: bool = True) -> None:
        self.name, self.goal, self.duration = name, goal, duration
        self.tolerance, self.settle, self.check_reach = tolerance, settle, check_reach
        self.timeout = duration + settle

    def start(self, prim: "Primitive") -> None:
        self.origin = prim.robot.commanded_tcp_pose()
        self.failures = 0

    def tick(self, prim, dt, t):
        goal = self.goal(prim)
        if self.check_reach:
            dist = prim.robot.reach_distance(goal.translation())
            if dist > REACH:
                return Status.FAILED, f"{self.name}: target {np.round(goal.translation(), 2).tolist()} out of reach ({dist:.2f} m from the shoulder > {REACH:.2f} m)"
        via = poses.interpolate(self.origin, goal, poses.min_jerk(t / self.duration))
        res = prim.robot.move_toward(via, dt)
        if not res.ok:
            self.failures += 1
            if self.failures >= 10:
                return Status.FAILED, f"{self.name}: {res.reason}"
        if t >= self.duration:
            err = float(np.linalg.norm(prim.robot.tcp_pose().translation() - goal.translation()))
            if err < self.tolerance:
                return Status.SUCCEEDED, ""
            if t >= self.timeout:
                return Status.FAILED, f"{self.name}: did not reach the target (TCP {100 * err:.1f} cm away)"
        return Status.RUNNING, ""


class Grip(Phase):
    """Close the hand until it holds ``prim.object`` (from contacts), or open it (release)."""

    def __init__(self, close: bool, name: str | None = None, timeout: float = 1.5, settle: float = 0.4) -> None:
        self.close, self.timeout, self.settle = close, timeout, settle
        self.name = name or ("close" if close else "open")

    def start(self, prim):
        g = prim.robot.gripper
        g.close() if self.close else g.open()
        if not self.close:
            prim.carrying = False
        self.since: float | None = None

    def tick(self, prim, dt, t):
        prim.robot.hold()
        g = prim.robot.gripper
        if self.close:
            held = g.holding()
            if held is not None and (prim.object is None or held == prim.object):
                self.since = t if self.since is None else self.since
                if t - self.since >= self.settle:
                    return Status.SUCCEEDED, ""
            else:
                self.since = None
            if g.fully_closed():
                return Status.FAILED, f"{self.name}: the hand closed on nothing"
            if t >= self.timeout:
                return Status.FAILED, f"{self.name}: no grasp of {prim.object} after {self.timeout:.1f} s (touching {[x.body for x in g.touches()]})"
            return Status.RUNNING, ""
        if t >= self.settle:
            return Status.SUCCEEDED, ""
        return Status.RUNNING, ""


class WaitFor(Phase):
    """Hold still until ``condition(prim)`` is true."""

    def __init__(self, name: str, condition: Callable[["Primitive"], bool], timeout: float, reason: str) -> None:
        self.name, self.condition, self.timeout, self.reason = name, condition, timeout, reason

    def tick(self, prim, dt, t):
        prim.robot.move_toward(prim.robot.commanded_tcp_pose(), dt)
        if self.condition(prim):
            return Status.SUCCEEDED, ""
        if t >= self.timeout:
            return Status.FAILED, f"{self.name}: {self.reason} within {self.timeout:.0f} s"
        return Status.RUNNING, ""


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


READY_POSE_POS = np.array([0.30, 0.05, 1.00])


class MoveJoints(Phase):
    """Minimum-jerk motion of the arm in joint space to a posture (no IK: always feasible within limits)."""

    def __init__(self, name: str, q_goal: np.ndarray, duration: float = 2.0, tolerance: float = 0.08,
                 settle: float = 1.5) -> None:
        self.name, self.q_goal, self.duration = name, np.asarray(q_goal, float), duration
        self.tolerance, self.timeout = tolerance, duration + settle

    def start(self, prim):
        self.q0 = prim.robot.q_cmd.copy()
        # no faster than 60 % of the joint speed limits (peak min-jerk speed = 1.875 x mean)
        span = np.max(np.abs(self.q_goal - self.q0) * 1.875 / (0.6 * prim.robot.ik.max_speed))
        self.duration = max(self.duration, float(span))
        self.timeout = self.duration + 1.5

    def tick(self, prim, dt, t):
        s = poses.min_jerk(t / self.duration)
        prim.robot.q_cmd = self.q0 + s * (self.q_goal - self.q0)
        prim.robot.hold()
        if t >= self.duration:
            err = float(np.max(np.abs(prim.robot.q() - self.q_goal)))
            if err < self.tolerance:
                return Status.SUCCEEDED, ""
            if t >= self.timeout:
                return Status.FAILED, f"{self.name}: the arm is held back ({err:.2f} rad from the posture)"
        return Status.RUNNING, ""


class Primitive:
    """Base: runs ``phases()`` in order; checks that a grasped object stays in the hand while ``carrying``."""

    name = "primitive"

    def __init__(self, robot: RobotController, obj: str | None = None, field_: TargetField | None = None,
                 human_holds: Callable[[], bool] | None = None) -> None:
        self.robot = robot
        self.object = obj
        self.field = field_ or TargetField()
        self.human_holds = human_holds or (lambda: False)
        self.carrying = False
        self._held_xy: np.ndarray | None = None  # target x, y frozen while the object is in the hand
        self._phases: list[Phase] = []
        self._k = 0
        self._t = 0.0
        self._t_total = 0.0
        self.progress = Progress(Status.RUNNING)

    # --- targets -------------------------------------------------------
    def xy(self) -> np.ndarray:
        """The target's table position: the target field's peak (fallback: the first perception)."""
        if self._held_xy is not None:
            return self._held_xy
        peak = self.field.target()
        return np.array(peak if peak is not None else self._xy0, float)

    def phases(self) -> list[Phase]:
        raise NotImplementedError

    # --- running -------------------------------------------------------
    def start(self, target_xy=None) -> None:
        self._xy0 = target_xy if target_xy is not None else (0.25, 0.0)
        self.field.reset()
        if target_xy is not None:
            # let the field form its peak on the first perception
            self.field.observe(target_xy)
            self.field.advance(0.3)
        self.robot.reset_command()
        self._held_xy = None
        self.carrying = False
        self._phases = self.phases()
        self._k, self._t, self._t_total = 0, 0.0, 0.0
        self.progress = Progress(Status.RUNNING, self._phases[0].name)
        self._phases[0].start(self)

    def tick(self, dt: float, target_xy=None) -> Progress:
        if self.progress.status is not Status.RUNNING:
            self.robot.hold()
            return self.progress
        self.field.observe(target_xy)
        self.field.advance(dt)
        self._t += dt
        self._t_total += dt
        phase = self._phases[self._k]
        status, reason = phase.tick(self, dt, self._t)
        if status is Status.RUNNING and self.carrying and self.object and self.robot.gripper.holding() != self.object:
            status, reason = Status.FAILED, f"{phase.name}: {self.object} slipped out of the hand"
        if status is Status.FAILED:
            self.progress = Progress(Status.FAILED, phase.name, reason, self._t_total)
        elif status is Status.SUCCEEDED:
            self._after(phase)
            self._k += 1
            if self._k >= len(self._phases):
                self.progress = Progress(Status.SUCCEEDED, phase.name, "", self._t_total)
            else:
                self._t = 0.0
                self._phases[self._k].start(self)
                self.progress = Progress(Status.RUNNING, self._phases[self._k].name, "", self._t_total)
        else:
            self.progress = Progress(Status.RUNNING, phase.name, "", self._t_total)
        return self.progress

    def _after(self, phase: Phase) -> None:
        if isinstance(phase, Grip):
            self.carrying = phase.close
            if phase.close:
                self._held_xy = self.xy().copy()


# ---------------------------------------------------------------------------
# geometry of the objects (body origin at the bottom centre)
GRASP_HEIGHT = {"glass": 0.05, "bottle": 0.08}
RADIUS = {"glass": 0.040, "bottle": 0.035}
TCP_CYLINDER_RADIUS = 0.035  # the TCP is the centre of a 70 mm cylinder touching the palm
LIFT = 0.12
REST_POSE_POS = np.array([0.32, 0.05, 1.00])


def _point(prim: Primitive, z: float) -> np.ndarray:
    x, y = prim.xy()
    return np.array([x, y, TABLE_Z + z])


def _side_grasp_pose(prim: Primitive, back: float = 0.0, up: float = 0.0, roll: float = 0.0,
                     height: float | None = None) -> mink.SE3:
    obj = prim.object or "glass"
    c = _point(prim, (height if height is not None else GRASP_HEIGHT[obj]) + up)
    rot = poses.side_rotation(c, prim.robot.shoulder)
    ax = poses.approach_axis(rot)
    pos = c - ax * (RADIUS[obj] - TCP_CYLINDER_RADIUS + back)
    return poses.pose(rot @ mink.SO3.from_x_radians(roll), pos)


def _retract() -> list[Phase]:
    return [Rise("rise", 1.0),
            Move("retract", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04)]


def _reach_and_grasp(prim: Primitive, height: float | None = None) -> list[Phase]:
    return [
        _Open("open"),
        Rise("rise", 1.0),
        Move("ready", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
        Move("above pre-grasp", lambda p: _side_grasp_pose(p, back=0.16, up=0.10, height=height), duration=1.5),
        Move("pre-grasp", lambda p: _side_grasp_pose(p, back=0.16, up=0.0, height=height), duration=0.8),
        Move("approach", lambda p: _side_grasp_pose(p, height=height), duration=1.0, tolerance=0.025),
        Grip(True, "grasp"),
    ]


class _Open(Grip):
    def __init__(self, name="open"):
        super().__init__(False, name, settle=0.2)


class _Frozen:
    """A pose captured when a phase starts (lift from where the object was grasped)."""

    def __init__(self) -> None:
        self.pose: mink.SE3 | None = None


def _capture(prim: Primitive) -> mink.SE3:
    return prim.robot.commanded_tcp_pose()


class ReachAndGrasp(Primitive):
    """Reach the object from the side and grasp it (ends holding it, on the table)."""

    name = "reach_and_grasp"

    def phases(self):
        return _reach_and_grasp(self)


class ReachGraspLift(Primitive):
    name = "reach_grasp_lift"

    def phases(self):
        return _reach_and_grasp(self) + [Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2)]


class TurnGlass(Primitive):
    """Grasp the inverted glass, lift, roll it 180 deg about the approach axis, put it down upright, let go."""

    name = "turn_glass"

    def __init__(self, robot, obj="glass", **kw):
        super().__init__(robot, obj, **kw)

    def phases(self):
        # the inverted glass is grasped at its middle too (its height is symmetric)
        return _reach_and_grasp(self) + [
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
            Move("turn half", lambda p: _side_grasp_pose(p, up=LIFT, roll=math.pi / 2), duration=1.2),
            Move("turn", lambda p: _side_grasp_pose(p, up=LIFT, roll=math.pi), duration=1.2),
            Move("lower", lambda p: _side_grasp_pose(p, up=0.008, roll=math.pi), duration=1.2),
            _Open("release"),
            _Carry(False),
            Move("back off", lambda p: _side_grasp_pose(p, back=0.16, up=0.03, roll=math.pi), duration=1.0, tolerance=0.04),
            *_retract(),
        ]


class _Carry(Phase):
    """Marks the end of carrying (after a release) without moving."""

    def __init__(self, carrying: bool) -> None:
        self.carrying, self.name = carrying, "release done"

    def tick(self, prim, dt, t):
        prim.carrying = self.carrying
        prim.robot.hold()
        return Status.SUCCEEDED, ""


class Retract(Primitive):
    """Back to the rest posture above the robot's side of the table (hand open unless carrying)."""

    name = "retract"

    def phases(self):
        return _retract()


class Request(Primitive):
    """Hold an open hand out, palm up, near the middle line toward the target object's side (a request)."""

    name = "request"
    HEIGHT = 0.20  # above the table

    def phases(self):
        def goal(p):
            y = float(np.clip(p.xy()[1], -0.3, 0.3))
            pos = np.array([0.06, y, TABLE_Z + self.HEIGHT])
            # palm up: the palm normal (gripper -x) points to world +z
            rot = poses.side_rotation(pos, p.robot.shoulder) @ mink.SO3.from_y_radians(math.pi / 2)
            return poses.pose(rot, pos)
        return [_Open("open"), Move("hold out open hand", goal, duration=2.0, tolerance=0.03)]


class PlaceInRWS(Primitive):
    """Grasp the object and put it down at ``spot`` (table x, y in the RWS), then let go and back off."""

    name = "place"

    def __init__(self, robot, obj, spot=(0.25, 0.0), **kw):
        super().__init__(robot, obj, **kw)
        self.spot = np.array(spot, float)

    def phases(self):
        spot = self.spot

        def at_spot(p, up):
            c = np.array([spot[0], spot[1], TABLE_Z + GRASP_HEIGHT[p.object] + up])
            rot = poses.side_rotation(c, p.robot.shoulder)
            return poses.pose(rot, c - poses.approach_axis(rot) * (RADIUS[p.object] - TCP_CYLINDER_RADIUS))
        return _reach_and_grasp(self) + [
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
            Move("carry", lambda p: at_spot(p, LIFT), duration=1.5),
            Move("put down", lambda p: at_spot(p, 0.008), duration=1.2),
            _Open("release"), _Carry(False),
            *_retract(),
        ]
