"""Motion primitives: small objects that realise the robot's AEL actions in the physics.

A primitive is a list of phases (move the TCP along a minimum-jerk profile,
close or open the hand, wait for a condition). ``start(target_xy)`` begins
it; ``tick(dt, target_xy) -> Progress`` is called once per control tick with
the current perception of the action's target (table x, y of the object or
the human's hand, or None when it is not seen). The perception feeds the
primitive's `TargetField`; the field's peak is the x, y the arm goes to,
while heights and approach orientations come from the primitive.

Every phase has a time limit; a primitive that cannot do its job ends
FAILED with a reason (unreachable target, target beyond the hand-over zone,
IK without solution, nothing in the hand, object slipped, human did not take
the object, stopper not removed, glass not seen).

The primitives (all friction grasps from the side, no welds):
  ReachAndGrasp, ReachGraspLift   grasp (and lift) an object standing in the RWS
  TurnGlass                       grasp the inverted glass, roll it 180 deg in the air, put it down upright
  PlaceInRWS                      grasp, carry, put down upright at ``spot``
  Pour                            grasp the open bottle, tilt it 140 deg beside and above the glass at
                                  ``locate("glass")`` (mouth over the glass centre), hold, tilt back,
                                  put the bottle back where it stood
  HoldBottleForStopper            grasp the closed bottle, hold it out upright at the middle line, wait
                                  for ``stopper_removed()``, put it back
  HandOver, TurnAndHandOver       carry (turn first) and hold out in the hand-over zone; let go once
                                  ``human_holds()``; withdraw
  Receive                         grasp what the human holds out (target: the human's hand), wait until
                                  the human lets go, put it down in the RWS
  Request, Retract                open hand held out palm up near the middle line; back to rest

Callbacks a caller passes as keywords (every primitive accepts them; see `Primitive.__init__`):
``human_holds()``, ``locate(name)``, ``stopper_removed()``. They come from perception.
"""

from __future__ import annotations

import math
from typing import Callable

import mink
import numpy as np

from assistbot.robot import poses
from assistbot.robot.controller import REACH, TCP_MIN_X, RobotController
from assistbot.robot.gripper import Gripper
from assistbot.robot.phases import (
    BackOff,
    Grip,
    LowerUntilSupported,
    Move,
    Open,
    Phase,
    Relative,
    RememberPlace,
    Rise,
    Roll,
    SetCarrying,
    Wait,
    WaitFor,
    WaitForTake,
)
from assistbot.robot.placement import put_down_spot, segment_distance, shared_spot
from assistbot.robot.progress import Progress, Status
from assistbot.robot.target_field import TargetField
from assistbot.task import OBJECTS
from assistbot.world.layout import BOTTLE_BODY_TOP, OBJECT_HEIGHT, OBJECT_RADIUS, STOPPER_HEIGHT, TABLE_Z

READY_POSE_POS = np.array([0.30, 0.05, 1.00])


class Primitive:
    """Base: runs ``phases()`` in order; checks that a grasped object stays in the hand while ``carrying``."""

    name = "primitive"

    def __init__(self, robot: RobotController, obj: str | None = None, field_: TargetField | None = None,
                 human_holds: Callable[[], bool] | None = None,
                 locate: Callable[[str], tuple[float, float] | None] | None = None,
                 stopper_removed: Callable[[], bool] | None = None,
                 lifted: Callable[[], float | None] | None = None,
                 partner_hand: Callable[[], tuple[float, float, float] | None] | None = None,
                 identify: Callable[[], str | None] | None = None,
                 seen_elsewhere: Callable[[], bool] | None = None,
                 offered: Callable[[], bool] | None = None) -> None:
        """``obj``: the object acted on ("bottle", "glass", "held_out" for whatever the human holds out).

        Callbacks (all from perception, never from the physics' ground truth):
          human_holds()      True while the human's hand holds the object (hand-overs).
          locate(name)       table (x, y) of another object, e.g. the glass to pour into; None if unseen.
          stopper_removed()  True once the stopper is seen off the bottle (holding the bottle for it).
          lifted()           height (m above the table) of the target's base as seen now, when the
                             person holds it up; None when it is not seen. Grasps from the person's
                             hand go to that height (`base_z`).
          partner_hand()     table (x, y, z) where the person's open hand was last seen held out, or
                             None; objects are offered there (`offer_point`).
          identify()         the object the person was seen holding out ("bottle", "glass"), or None:
                             what a grasp of "held_out" closed on (the hand feels only that it holds).
          seen_elsewhere()   True when the cameras have kept seeing the object the hand believes it
                             carries away from the hand: the grasp closed on something else.
          offered()          True while the person still holds the object out (not seen doing something
                             else with it, e.g. pouring); without perception: True.
        """
        self.robot = robot
        self.object = obj
        self.field = field_ or TargetField()
        self.human_holds = human_holds or (lambda: False)
        self.locate = locate or (lambda name: None)
        self.stopper_removed = stopper_removed or (lambda: False)
        self.lifted = lifted or (lambda: None)
        self.partner_hand = partner_hand or (lambda: None)
        self.identify = identify or (lambda: None)
        self.seen_elsewhere = seen_elsewhere or (lambda: False)
        self.offered = offered or (lambda: True)
        self._offer: np.ndarray | None = None
        self._failure: Progress | None = None    # a failure being ended safely (Phase.fallback)
        self.released: tuple[str, tuple[float, float]] | None = None  # the object let go of last, and where
        self._lift: float | None = None          # the target's base height above the table, smoothed
        self._lift_frozen = False                # ... and kept once the object is in the hand
        self.carrying = False
        self._held_xy: np.ndarray | None = None  # target x, y frozen while the object is in the hand
        self._peak: np.ndarray | None = None     # the field's peak this control tick
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
        if self._peak is None:  # read the field once per control tick
            peak = self.field.target()
            self._peak = np.array(peak if peak is not None else self._xy0, float)
        return self._peak

    def base_z(self) -> float:
        """World z of the base of a target held up by the person: as perceived (smoothed over
        LIFT_TAU), LIFT_GUESS above the table until it is first seen."""
        return TABLE_Z + (self._lift if self._lift is not None else LIFT_GUESS)

    def _see_lift(self, dt: float) -> None:
        if self._lift_frozen:
            return
        h = self.lifted()
        if h is not None:
            self._lift = float(h) if self._lift is None else self._lift + min(1.0, dt / LIFT_TAU) * (float(h) - self._lift)

    def phases(self) -> list[Phase]:
        raise NotImplementedError

    def _look(self) -> None:
        """Gaze: the head looks at the hand while it carries something, else at the target on the table."""
        if self.carrying:
            self.robot.look_at(self.robot.tcp_pose().translation())
        else:
            x, y = self.xy()
            self.robot.look_at(np.array([x, y, TABLE_Z + 0.05]))

    # --- running -------------------------------------------------------
    def start(self, target_xy=None) -> None:
        self._xy0 = target_xy if target_xy is not None else (0.25, 0.0)
        self.field.reset()
        if target_xy is not None:
            # let the field form its peak on the first perception
            self.field.observe(target_xy)
            self.field.advance(0.3)
        self._peak = None
        self._lift, self._lift_frozen = None, False
        self._see_lift(1.0)
        self.robot.reset_command()
        self._held_xy = None
        self.carrying = False
        self._phases = self.phases()
        self._k, self._t, self._t_total = 0, 0.0, 0.0
        self._failure = None
        self.progress = Progress(Status.RUNNING, self._phases[0].name)
        self._phases[0].start(self)

    def tick(self, dt: float, target_xy=None) -> Progress:
        if self.progress.status is not Status.RUNNING:
            self.robot.hold()
            return self.progress
        self.field.observe(target_xy)
        self.field.advance(dt)
        self._peak = None
        self._see_lift(dt)
        self._look()
        self._t += dt
        self._t_total += dt
        phase = self._phases[self._k]
        status, reason = phase.tick(self, dt, self._t)
        if status is Status.RUNNING and self.carrying and self.object and not self.robot.gripper.grasps():
            status, reason = Status.FAILED, f"{phase.name}: {self.object} slipped out of the hand"
        elif status is Status.RUNNING and self.carrying and self.object and self.seen_elsewhere():
            status, reason = Status.FAILED, f"{phase.name}: the {self.object} is not in the hand (seen away from it)"
        elif status is Status.RUNNING and self._failure is None and (why := self.interrupted(phase)):
            status, reason = Status.FAILED, f"{phase.name}: {why}"
        if status is Status.FAILED and self._failure is None:
            fallback = phase.fallback
            if fallback is None and self.carrying and self.robot.gripper.grasps():
                # whatever failed, nothing stays in the hand: the next action may start by opening it
                fallback = _set_down_what_is_carried
            if fallback is not None:
                # end safely first, then report
                self._failure = Progress(Status.FAILED, phase.name, reason, self._t_total)
                self._phases = self._phases[:self._k + 1] + fallback(self)
                status = Status.SUCCEEDED
        if status is Status.FAILED:
            self.progress = Progress(Status.FAILED, phase.name, reason, self._t_total)
        elif status is Status.SUCCEEDED:
            self._after(phase)
            self._k += 1
            if self._k >= len(self._phases) and self._failure is not None:
                self.progress = Progress(Status.FAILED, self._failure.phase, self._failure.reason, self._t_total)
            elif self._k >= len(self._phases):
                self.progress = Progress(Status.SUCCEEDED, phase.name, "", self._t_total)
            else:
                self._t = 0.0
                self._phases[self._k].start(self)
                self.progress = Progress(Status.RUNNING, self._phases[self._k].name, "", self._t_total)
        else:
            self.progress = Progress(Status.RUNNING, phase.name, "", self._t_total)
        return self.progress

    def interrupted(self, phase: Phase) -> str:
        """Why ``phase`` must stop now, from what is perceived ("" to go on); its fallback then ends it safely."""
        return ""

    def _after(self, phase: Phase) -> None:
        if isinstance(phase, Grip):
            self.carrying = phase.close
            if phase.close:
                self._held_xy = self.xy().copy()
                self._lift_frozen = True

    def note_set_down(self) -> None:
        """Letting go of an object set down on the table: where it stands, as the robot's own body knows it
        (the axis of a side grasp lies beyond the TCP along the approach), for when its arm hides it."""
        pose = self.robot.tcp_pose()
        obj = self.object
        if obj not in RADIUS or obj == "held_out" or pose.translation()[2] > TABLE_Z + GRASP_HEIGHT[obj] + 0.04:
            return      # let go of in the air: into the person's hand
        c = pose.translation() + poses.approach_axis(pose.rotation()) * (RADIUS[obj] - TCP_CYLINDER_RADIUS)
        self.released = (obj, (float(c[0]), float(c[1])))


# ---------------------------------------------------------------------------
# geometry of the objects (body origin at the bottom centre)
GRASP_HEIGHT = {"glass": 0.05, "bottle": 0.08, "held_out": 0.06}
#: the objects' radii (the MJCF's, through world.layout); "held_out": either, unseen which
RADIUS = {**{o: OBJECT_RADIUS[o] for o in ("glass", "bottle")}, "held_out": (OBJECT_RADIUS["glass"] + OBJECT_RADIUS["bottle"]) / 2}
#: how far (m) beyond REACH a grasp point may lie and still be grasped, short of the hand's middle
REACH_SLACK = 0.025
#: the farthest a spot shared with the person may lie (m from the shoulder, at grasp height): just beyond
#: REACH, within the slack, since the person's arm stops at the middle line
SHARED_REACH = REACH + REACH_SLACK - 0.012
TCP_CYLINDER_RADIUS = 0.035  # the TCP is the centre of a 70 mm cylinder touching the palm
LIFT = 0.12
#: the bottle's mouth above its grasp point (m)
BOTTLE_MOUTH_ABOVE_GRASP = OBJECT_HEIGHT["bottle"] - GRASP_HEIGHT["bottle"]
#: where an object is held out for the human to take: its centre (table x, y) and its base height above the table
HOLD_OUT_XY = (-0.04, -0.04)
HOLD_OUT_BASE = 0.11
#: how low and how high an offered object's base is held above the table (m), whatever the hand it is
#: offered to: a hand shown higher takes it from the side no higher than a seated arm reaches well
OFFER_BASE = (0.05, 0.12)
#: m above the table that a put-down goes to by position before lowering the rest of the way by feel:
#: an object is not always held at the height assumed (one taken from the person's hand)
SET_DOWN_ABOVE = 0.025
#: m by which what the robot carries passes over the objects standing in its way
CARRY_CLEARANCE = 0.03
#: s the hand waits beside the person's before reaching in, for them to hold the object out again
OFFER_PATIENCE = 4.0
#: the height (m above the table) assumed for the base of an object held up by the person until it is seen
LIFT_GUESS = 0.10
#: time constant (s) over which the perceived height of a held-up object is followed
LIFT_TAU = 0.2
#: the top of each object's side wall, where a side grasp's upper finger must stay below (m above the base):
#: the glass's rim, the bottle's shoulder
WALL_TOP = {"glass": OBJECT_HEIGHT["glass"], "bottle": BOTTLE_BODY_TOP}


def held_grasp_height(obj: str, hand: "Gripper") -> float:
    """Grasp height (m above the base) of an object held up by the person: the middle of the band in
    which the whole hand lies along the object's wall (palm above the base, upper finger below the
    wall's top), since the base is seen only to a cm or two there. The glass's band is 2 cm wide: its
    rim lies 10 cm up, and a finger above it curls over the top onto the palm (and, opened, catches
    inside the glass). Unknown which object ("held_out"): the band both share."""
    top = WALL_TOP[obj] if obj in WALL_TOP else min(WALL_TOP.values())
    return 0.5 * (hand.reach_below + top - hand.reach_above)


def _point(prim: Primitive, z: float) -> np.ndarray:
    x, y = prim.xy()
    return np.array([x, y, TABLE_Z + z])


def _grasp_pose_at(prim: Primitive, centre: np.ndarray, obj: str, back: float = 0.0, roll: float = 0.0) -> mink.SE3:
    """Side grasp of ``obj`` whose axis passes through ``centre`` (world, at grasp height)."""
    rot = poses.side_rotation(centre, prim.robot.shoulder)
    ax = poses.approach_axis(rot)
    pos = centre - ax * (RADIUS[obj] - TCP_CYLINDER_RADIUS + back)
    to = pos - prim.robot.shoulder
    dist = float(np.linalg.norm(to))
    if REACH < dist <= REACH + REACH_SLACK:
        # just beyond the arm's reach (an object held out at the person's own limit): stop short along the
        # approach; the object then sits nearer the fingertips of the open hand (94 mm), which still close on it
        pos = pos - ax * (dist - REACH + 0.003) / max(0.3, float(ax @ to) / dist)
    return poses.pose(rot @ mink.SO3.from_x_radians(roll), pos)


def _side_grasp_pose(prim: Primitive, back: float = 0.0, up: float = 0.0, roll: float = 0.0,
                     height: float | None = None, held_up: bool = False) -> mink.SE3:
    """Side grasp of the target at its grasp height above its base: on the table, or ``held_up`` by the
    person at the height perception gives (`Primitive.base_z`)."""
    obj = prim.object or "glass"
    x, y = prim.xy()
    if held_up:
        # which object the person holds out, as seen, for where the hand fits on it
        seen = prim.identify() if obj == "held_out" else obj
        base_z, h = prim.base_z(), held_grasp_height(seen or obj, prim.robot.gripper)
    else:
        base_z, h = TABLE_Z, GRASP_HEIGHT.get(obj, GRASP_HEIGHT["held_out"])
    c = np.array([x, y, base_z + (height if height is not None else h) + up])
    return _grasp_pose_at(prim, c, obj, back, roll)


def _retract(over_at: float | None = None) -> list[Phase]:
    """Up, then back to the ready pose; with ``over_at`` (world z, m) the hand first rises to that
    height and crosses to above the ready pose there, so it passes over the objects on its way."""
    if over_at is None:
        return [Rise("rise", 1.0),
                Move("retract", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04)]
    above = READY_POSE_POS.copy()
    above[2] = max(above[2], over_at)
    return [Rise("rise", over_at),
            Move("withdraw over", lambda p: poses.pose(mink.SO3.identity(), above), duration=1.2, tolerance=0.04),
            Move("retract", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=0.6, tolerance=0.04)]


def _reach_and_grasp(prim: Primitive, height: float | None = None, held_up: bool = False) -> list[Phase]:
    """Reach and grasp the target from the side: standing on the table, or ``held_up`` by the person (the
    hand then reaches out for it as far as it can, and waits for it there: `Move.reach_out`)."""
    return [
        Open("open"),
        Rise("rise", 1.0),
        Move("ready", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
        Move("above pre-grasp", lambda p: _side_grasp_pose(p, back=0.16, up=0.10, height=height, held_up=held_up), duration=1.5,
             reach_out=held_up),
        Move("pre-grasp", lambda p: _side_grasp_pose(p, back=0.16, up=0.0, height=height, held_up=held_up), duration=0.8,
             reach_out=held_up),
        Move("approach", lambda p: _side_grasp_pose(p, height=height, held_up=held_up), duration=1.0, tolerance=0.025,
             reach_out=held_up),
        Grip(True, "grasp"),
    ]


def free_rws_spot(p: "Primitive") -> np.ndarray:
    """Where to put the object in the hand down in the RWS (`placement.put_down_spot`): clear of the
    corridor to the hand-over place and of the other objects seen standing in the RWS (``p.locate``)."""
    standing = [np.asarray(xy, float) for xy in (p.locate(n) for n in OBJECTS if n != p.object)
                if xy is not None and xy[0] > 0.0]
    return put_down_spot(p.robot.shoulder, REACH, HOLD_OUT_XY, standing, GRASP_HEIGHT.get(p.object, GRASP_HEIGHT["held_out"]))


def _half_turn(p: Primitive) -> float:
    """The hand's roll about its approach axis to the nearest half turn: 0, or pi once it has turned the
    glass in it. Carried either way, what it holds stands upright."""
    return 0.0 if p.robot.commanded_tcp_pose().rotation().as_matrix()[2, 2] >= 0.0 else math.pi


def _put_down_at(xy_of: Callable[[Primitive], np.ndarray], lift: float = LIFT) -> list[Phase]:
    """Carry the held object (upright, the hand keeping its half turn) above a table spot, lower it onto
    the table, let go, back off."""

    def at(p, up):
        x, y = xy_of(p)
        c = np.array([x, y, TABLE_Z + GRASP_HEIGHT[p.object] + up])
        return _grasp_pose_at(p, c, p.object, roll=_half_turn(p))
    return [
        CarryOver(lambda p: at(p, lift)),
        Move("carry", lambda p: at(p, lift), duration=1.8),
        # down to just above where the object would touch if held as assumed; the rest by feel
        Move("put down", lambda p: at(p, SET_DOWN_ABOVE), duration=1.2, tolerance=0.025),
        LowerUntilSupported(),
        Open("release"), SetCarrying(False),
        BackOff(),
    ]


def _waiting_for_the_person_to_let_go(timeout: float) -> WaitFor:
    """Both hold the object: wait until the person lets go. Not let go in time, it stays theirs: the hand
    opens and withdraws (no tug of war)."""
    wait = WaitFor("wait for the human to let go", lambda p: not p.human_holds(), timeout, "the human did not let go")
    wait.fallback = lambda p: [Open("leave it to the person"), SetCarrying(False), BackOff(), *_retract()]
    return wait


def _set_down_what_is_carried(p: Primitive) -> list[Phase]:
    """A failed action's safe end while the hand holds something: put it down at a free spot in the RWS
    and withdraw."""
    return _put_down_at(free_rws_spot) + _retract()


def offer_point(prim: "Primitive") -> np.ndarray:
    """Where to hold an object out for the person to take (world centre at grasp height): toward their
    open hand where it was last seen held out (the object's middle at the hand, its base within
    OFFER_BASE), else HOLD_OUT_XY at HOLD_OUT_BASE; never deeper into the HWS than the hand may go, nor
    out of reach. Chosen once."""
    if prim._offer is None:
        hand = prim.partner_hand()
        obj = prim.object
        if hand is None:
            c = np.array([HOLD_OUT_XY[0], HOLD_OUT_XY[1], TABLE_Z + HOLD_OUT_BASE + GRASP_HEIGHT[obj]])
        else:
            base = float(np.clip(float(hand[2]) - 0.5 * OBJECT_HEIGHT[obj], *OFFER_BASE))
            c = np.array([float(hand[0]), float(hand[1]), TABLE_Z + base + GRASP_HEIGHT[obj]])
        # out of reach: brought back toward the robot at the same height (a hand takes it where it was shown)
        sh, reach = prim.robot.shoulder, REACH - 0.03
        c[0] = max(c[0], TCP_MIN_X + 0.01)
        flat = reach ** 2 - (c[2] - sh[2]) ** 2
        off = c[:2] - sh[:2]
        if float(np.linalg.norm(c - sh)) > reach and flat > 0:
            c[:2] = sh[:2] + off * np.sqrt(flat) / float(np.linalg.norm(off))
        elif float(np.linalg.norm(c - sh)) > reach:
            c = sh + (c - sh) * reach / float(np.linalg.norm(c - sh))
        prim._offer = c
    return prim._offer


class CarryOver(Phase):
    """Before carrying the object in the hand to ``goal(prim)``: if the straight way passes by an object
    standing on the table (``locate``), first rise until what the hand carries clears that object's top
    by CARRY_CLEARANCE, and cross at that height; nothing to do otherwise. The IK keeps the arm clear of
    standing objects, not what it carries."""

    name = "carry over"

    def __init__(self, goal: Callable[["Primitive"], mink.SE3]) -> None:
        self.goal = goal

    def start(self, prim):
        self.moves: list[Move] = []
        obj = prim.object
        if obj not in OBJECT_HEIGHT:
            return
        here = prim.robot.commanded_tcp_pose()
        goal = self.goal(prim)
        a, b = here.translation(), goal.translation()
        below = GRASP_HEIGHT[obj]          # the carried object's base below the TCP
        need = -np.inf
        for other in OBJECTS:
            xy = prim.locate(other) if other != obj else None
            if xy is None:
                continue
            d = float(segment_distance(np.asarray(xy, float), a[:2], b[:2]))
            if d < RADIUS[obj] + RADIUS[other] + CARRY_CLEARANCE:
                top = TABLE_Z + OBJECT_HEIGHT[other] + (STOPPER_HEIGHT if other == "bottle" else 0.0)
                need = max(need, top + CARRY_CLEARANCE + below)
        if need <= max(a[2], b[2]) - 0.005:
            return
        rot = here.rotation()
        self.moves = [Move("carry over: rise", lambda p, q=np.array([a[0], a[1], need]): poses.pose(rot, q), duration=1.0,
                           tolerance=0.03),
                      Move("carry over: across", lambda p, q=np.array([b[0], b[1], need]): poses.pose(goal.rotation(), q),
                           duration=1.8, tolerance=0.03)]
        self.moves[0].start(prim)
        self.t0 = 0.0

    def tick(self, prim, dt, t):
        if not self.moves:
            prim.robot.hold()
            return Status.SUCCEEDED, ""
        status, reason = self.moves[0].tick(prim, dt, t - self.t0)
        if status is Status.SUCCEEDED:
            self.moves.pop(0)
            if self.moves:
                self.moves[0].start(prim)
                self.t0 = t
            return Status.RUNNING, ""
        return status, reason


def _hold_out(base: float | None = None, xy=None, duration: float = 2.5) -> list[Phase]:
    """Hold the object in the hand out: at ``xy`` with its base ``base`` above the table, or where the
    person will take it (`offer_point`); over what stands in the way (`CarryOver`)."""
    def goal(p):
        if xy is None:
            return _grasp_pose_at(p, offer_point(p), p.object)
        c = np.array([xy[0], xy[1], TABLE_Z + base + GRASP_HEIGHT[p.object]])
        return _grasp_pose_at(p, c, p.object)
    return [CarryOver(goal), Move("hold out", goal, duration=duration, tolerance=0.03)]


#: the phase of a hand-over in which the object is held out for the person to take
OFFER_PHASE = "wait for the human to take it"


def _set_down_for_the_person(p: Primitive) -> list[Phase]:
    """Not taken: set the object down on the table where the person can take it (`shared_spot`), let go, withdraw."""
    def spot(q):
        if getattr(q, "_shared", None) is None:
            standing = [xy for xy in (q.locate(n) for n in OBJECTS if n != q.object) if xy is not None]
            q._shared = shared_spot(q.robot.shoulder, SHARED_REACH, HOLD_OUT_XY, standing, min(GRASP_HEIGHT[o] for o in OBJECTS))
        return q._shared
    return _put_down_at(spot) + _retract()


def _give(timeout: float) -> list[Phase]:
    """The object is held out: wait until the human holds it, let go, withdraw. Not taken in time, it is set
    down on the table within the person's reach before the hand-over is reported failed."""
    wait = WaitForTake(OFFER_PHASE, timeout, "the human did not take it")
    wait.fallback = _set_down_for_the_person
    return [
        wait,
        Wait("feel the pull", 0.3),
        Open("let go"), SetCarrying(False),
        BackOff("back off", distance=0.16, up=0.0, duration=1.2),
        *_retract(),
    ]


# ---------------------------------------------------------------------------
# the primitives
class ReachAndGrasp(Primitive):
    """Reach the object from the side and grasp it (ends holding it, on the table)."""

    name = "reach_and_grasp"

    def phases(self):
        return _reach_and_grasp(self)


class ReachGraspLift(Primitive):
    name = "reach_grasp_lift"

    def phases(self):
        return _reach_and_grasp(self) + [Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2)]


def _turn_phases() -> list[Phase]:
    # the inverted glass is grasped at its middle too (its height is symmetric)
    return [
        Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
        Move("turn half", lambda p: _side_grasp_pose(p, up=LIFT, roll=math.pi / 2), duration=1.2),
        Move("turn", lambda p: _side_grasp_pose(p, up=LIFT, roll=math.pi), duration=1.2),
    ]


class TurnGlass(Primitive):
    """Grasp the inverted glass, lift, roll it 180 deg about the approach axis, put it down upright, let go."""

    name = "turn_glass"

    def __init__(self, robot, obj="glass", **kw):
        super().__init__(robot, obj, **kw)

    def phases(self):
        return _reach_and_grasp(self) + _turn_phases() + [
            Move("lower", lambda p: _side_grasp_pose(p, up=0.008, roll=math.pi), duration=1.2),
            Open("release"),
            SetCarrying(False),
            Move("back off", lambda p: _side_grasp_pose(p, back=0.16, up=0.03, roll=math.pi), duration=1.0, tolerance=0.04),
            *_retract(),
        ]


class Retract(Primitive):
    """Back to the rest posture above the robot's side of the table (hand open unless carrying)."""

    name = "retract"

    def phases(self):
        return _retract()


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Distance from point p to the segment a-b (any dimension)."""
    ab = b - a
    s = float(np.clip(np.dot(p - a, ab) / max(float(np.dot(ab, ab)), 1e-12), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + s * ab)))


class Request(Primitive):
    """Hold an open hand out, palm up, near the middle line toward the target object's side (a request),
    for SHOW_SECONDS, then withdraw it.

    The palm faces up and toward the human (its normal 60 deg above the horizontal): a fully
    upturned palm puts the wrist pitch at its limit on the robot's far (-y) side. The hand
    goes toward the object's side within y in Y_RANGE (the shoulder is on the +y side), moved
    aside from objects that ``locate`` reports standing in the RWS (the forearm would hit them)."""

    name = "request"
    HEIGHT = 0.20  # above the table
    OVER_HEIGHT = 0.33  # above the table: the hand goes out and back at this height
    HAND_X = 0.06  # table x of the held-out hand, just on the robot's side of the middle line
    SHOW_SECONDS = 2.0
    PALM_UP = math.radians(60)
    Y_RANGE = (-0.12, 0.30)

    #: an object standing in the RWS closer than this (m, seen from above) to the line from the
    #: shoulder to the hand would meet the forearm, which comes up from below to a palm-up hand
    CLEAR = 0.11

    def _y(self) -> float:
        """The hand's y: toward the target's side, moved to where the arm clears the objects seen standing in the RWS.

        The arm is checked along the line from the shoulder to the hand, not just at the hand:
        a hand put on the far side of an object pulls the forearm across it."""
        y = float(np.clip(self.xy()[1], *self.Y_RANGE))
        obstacles = [np.asarray(xy, float) for xy in (self.locate(n) for n in ("bottle", "glass")) if xy is not None and xy[0] > 0.0]
        shoulder = np.asarray(self.robot.shoulder[:2], float)

        def clear(c: float) -> bool:
            return all(_segment_distance(o, shoulder, np.array([self.HAND_X, c])) >= self.CLEAR for o in obstacles)

        if clear(y):
            return y
        free = [c for c in np.linspace(*self.Y_RANGE, 43) if clear(c)]
        return float(min(free, key=lambda c: abs(c - y))) if free else y

    def phases(self):
        def goal(p, height=self.HEIGHT):
            if getattr(p, "_request_y", None) is None:
                p._request_y = p._y()
            pos = np.array([self.HAND_X, p._request_y, TABLE_Z + height])
            # palm up: the palm normal (gripper -x) turned from horizontal toward world +z
            rot = poses.side_rotation(pos, p.robot.shoulder) @ mink.SO3.from_y_radians(self.PALM_UP)
            return poses.pose(rot, pos)
        self._request_y = None
        # the hand travels over the objects of the RWS, both ways: high enough that the palm-up
        # hand, which hangs below its TCP, passes over a bottle with its stopper; a gesture: shown,
        # then withdrawn, so that it does not hide from the robot's own cameras the object the
        # person now holds out toward it
        return [Open("open"), Rise("rise", TABLE_Z + self.OVER_HEIGHT),
                Move("over", lambda p: goal(p, self.OVER_HEIGHT), duration=1.5, tolerance=0.04),
                Move("hold out open hand", goal, duration=1.0, tolerance=0.03),
                Wait("show the open hand", self.SHOW_SECONDS), *_retract(over_at=TABLE_Z + self.OVER_HEIGHT)]


class PlaceInRWS(Primitive):
    """Grasp the object and put it down at ``spot`` (table x, y in the RWS), then let go and back off."""

    name = "place"

    def __init__(self, robot, obj, spot=(0.25, 0.0), **kw):
        super().__init__(robot, obj, **kw)
        self.spot = np.array(spot, float)

    def phases(self):
        return (_reach_and_grasp(self) + [Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2)]
                + _put_down_at(lambda p: p.spot) + _retract())


class HoldBottleForStopper(Primitive):
    """Grasp the closed bottle, hold it out upright near the middle line where the human can pull the
    stopper, keep it there until ``stopper_removed()`` (perception), put it back where it stood, let go.

    A bottle seen in the HWS (target x < 0) is one the human holds out (``human_holds()``): the robot
    grasps it at the human's hold-out height and waits until the human's hand lets go; or one the
    human put down near the line: grasped from the table. Either way it is afterwards put down at a
    free place in the RWS (`free_rws_spot`). The grip holds the bottle by friction against
    the pull; the world decides when the fit gives."""

    name = "hold_bottle_for_stopper"
    HOLD_XY = (-0.045, -0.02)
    HOLD_BASE = 0.10

    def __init__(self, robot, obj="bottle", timeout: float = 30.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout
        self.home_xy: np.ndarray | None = None

    def _home(self) -> np.ndarray:
        """Where a bottle taken from the human's hand goes: a free place in the RWS (chosen once)."""
        if self.home_xy is None:
            self.home_xy = free_rws_spot(self)
        return self.home_xy

    def phases(self):
        hold = [
            *_hold_out(self.HOLD_BASE, self.HOLD_XY),
            WaitFor("hold steady for the stopper", lambda p: p.stopper_removed(), self.timeout,
                    "the stopper was not removed"),
            Wait("settle", 0.3),
        ]
        if self.xy()[0] < 0.0 and not self.human_holds():
            # standing on the person's side, put down there for the robot: from the table, back to the RWS
            return _reach_and_grasp(self) + [
                RememberPlace(),
                Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
                *hold,
                *_put_down_at(lambda p: p._home()),
                *_retract(),
            ]
        if self.xy()[0] < 0.0:  # held out by the human
            return _reach_and_grasp(self, held_up=True) + [
                Wait("hold", 1.5),
                _waiting_for_the_person_to_let_go(10.0),
                *hold,
                *_put_down_at(lambda p: p._home()),
                *_retract(),
            ]
        return _reach_and_grasp(self) + [
            RememberPlace(),
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
            *_hold_out(self.HOLD_BASE, self.HOLD_XY),
            WaitFor("hold steady for the stopper", lambda p: p.stopper_removed(), self.timeout,
                    "the stopper was not removed"),
            Wait("settle", 0.3),
            *_put_down_at(lambda p: p.home_xy),
            *_retract(),
        ]


class Pour(Primitive):
    """Grasp the open bottle, bring it beside and above the upright glass (``locate("glass")``), roll it
    until the mouth points down into the glass, hold while the liquid runs, roll back, put the bottle
    back where it stood, let go and retract."""

    name = "pour"
    TILT = math.radians(140)
    POUR_SECONDS = 2.5
    MOUTH_ABOVE_RIM = 0.035

    def __init__(self, robot, obj="bottle", glass_xy=None, **kw):
        super().__init__(robot, obj, **kw)
        self.glass_xy = None if glass_xy is None else np.asarray(glass_xy, float)
        self.home_xy: np.ndarray | None = None

    def start(self, target_xy=None) -> None:
        super().start(target_xy)
        if self.glass_xy is None:
            g = self.locate("glass")
            if g is None:
                self.progress = Progress(Status.FAILED, "locate glass", "the glass is not seen: nowhere to pour")
                return
            self._glass = np.asarray(g, float)
        else:
            self._glass = self.glass_xy
        self._tilt_k = next(i for i, ph in enumerate(self._phases) if ph.name == "tilt")

    def tick(self, dt: float, target_xy=None) -> Progress:
        # where the glass is, as seen, until the bottle tilts over it: at the start it may be hidden (behind
        # the arm) and known only from where the robot set it down, which is off by the offset at which the
        # hand held it
        if self.glass_xy is None and self.progress.status is Status.RUNNING and self._k < self._tilt_k:
            g = self.locate("glass")
            if g is not None:
                self._glass = np.asarray(g, float)
        return super().tick(dt, target_xy)

    def _pour_pose(self, tilt: float) -> mink.SE3:
        """TCP pose holding the bottle rolled by ``tilt`` with the mouth, at the full tilt, over the glass centre."""
        mouth = np.array([self._glass[0], self._glass[1], TABLE_Z + OBJECT_HEIGHT["glass"] + self.MOUTH_ABOVE_RIM])
        rot0 = poses.side_rotation(mouth, self.robot.shoulder)
        rot_full = rot0 @ mink.SO3.from_x_radians(self.TILT)
        tcp = mouth - rot_full.as_matrix() @ np.array([0.0, 0.0, BOTTLE_MOUTH_ABOVE_GRASP])
        return poses.pose(rot0 @ mink.SO3.from_x_radians(tilt), tcp)

    def phases(self):
        return _reach_and_grasp(self) + [
            RememberPlace(),
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
            Move("over the glass", lambda p: p._pour_pose(0.0), duration=1.8),
            Roll("tilt", self.TILT, duration=1.5),
            Wait("pour", self.POUR_SECONDS),
            Roll("tilt back", -self.TILT, duration=1.2),
            *_put_down_at(lambda p: p.home_xy),
            *_retract(),
        ]


class HandOver(Primitive):
    """Grasp the object, carry it upright (slowly: it may be a full glass) to the hand-over zone, hold it
    out until ``human_holds()``, let go, withdraw."""

    name = "hand_over"

    def __init__(self, robot, obj="glass", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout

    def phases(self):
        return _reach_and_grasp(self) + [
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.5),
            *_hold_out(duration=3.0),
            *_give(self.timeout),
        ]


class TurnAndHandOver(Primitive):
    """Turn the inverted glass in the air (as `TurnGlass`), then hold it out upright and give it to the human."""

    name = "turn_and_hand_over"

    def __init__(self, robot, obj="glass", timeout: float = 20.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout

    def phases(self):
        # after the roll the gripper is upside down: keep that roll while holding out
        def hold(p):
            return _grasp_pose_at(p, offer_point(p), p.object, roll=math.pi)
        return _reach_and_grasp(self) + _turn_phases() + [
            CarryOver(hold), Move("hold out", hold, duration=2.5, tolerance=0.03),
            *_give(self.timeout),
        ]


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
        reach = _reach_and_grasp(self, held_up=True)
        # from the pre-grasp on, the hand closes in on the person's: only while they still hold it out
        # (a hand lifting the bottle to pour passes through the hand-over zone, and may pause there)
        k, approach = next((i, ph) for i, ph in enumerate(reach) if ph.name == "approach")
        reach.insert(k, WaitFor("wait while it is held out", lambda p: p.offered(), OFFER_PATIENCE,
                                "the person did not hold it out"))
        # ... and while it closes in (`interrupted`): a person who starts to pour instead is not reached
        # into; the open hand backs off the way it came
        approach.fallback = lambda p: [BackOff("back off from the hand", distance=0.16)]
        return reach + [
            Wait("hold", 1.5),  # the human feels the robot's grip before letting go
            _waiting_for_the_person_to_let_go(self.timeout),
            Relative("take back", [0.06, 0.0, 0.03], duration=1.0),
            *_put_down_at(lambda p: p.free_spot()),
            *_retract(),
        ]


    def interrupted(self, phase: Phase) -> str:
        if phase.name == "approach" and not self.offered():
            return "the person no longer holds it out"
        return ""


class TakeFromTable(Primitive):
    """The other way to take what the person cannot hand over: show, with the open hand held above it, a
    spot on the table that both reach (`placement.shared_spot`); wait until an object is seen set down
    there and let go of; take it from the table, put it down at a free spot in the RWS, retract.

    ``obj`` is None: which object it is follows from what perception sees set down under the hand."""

    name = "take_from_table"
    #: how high (m above the table) the open hand shows the spot: above the bottle with its stopper
    SHOW_HEIGHT = 0.30
    #: an object seen standing this close (m) to the spot has been set down there
    PLACED_NEAR = 0.09

    def __init__(self, robot, obj=None, timeout: float = 25.0, **kw):
        super().__init__(robot, obj, **kw)
        self.timeout = timeout
        self.spot: np.ndarray | None = None
        self._home_xy: np.ndarray | None = None

    def start(self, target_xy=None) -> None:
        standing = [xy for xy in (self.locate(n) for n in OBJECTS) if xy is not None and xy[0] > -0.2]
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
            c = np.array([p.spot[0], p.spot[1], TABLE_Z + (self.SHOW_HEIGHT if up is None else up)])
            return _grasp_pose_at(p, c, "glass", back=back)

        def grasp_at(p, back=0.0, up=0.0):
            return _side_grasp_pose(p, back=back, up=up)
        return [
            Open("open"), Rise("rise", 1.0),
            Move("ready", lambda p: poses.pose(mink.SO3.identity(), READY_POSE_POS), duration=1.2, tolerance=0.04),
            Move("show the spot", show, duration=1.8, tolerance=0.04),
            WaitFor("wait for it to be set down", lambda p: p._placed(), self.timeout, "nothing was set down"),
            Move("back from above", lambda p: show(p, back=0.16), duration=1.0, tolerance=0.04),
            Move("pre-grasp", lambda p: grasp_at(p, back=0.16), duration=1.2),
            Move("approach", lambda p: grasp_at(p), duration=1.0, tolerance=0.025),
            Grip(True, "grasp"),
            Move("lift", lambda p: _side_grasp_pose(p, up=LIFT), duration=1.2),
            *_put_down_at(lambda p: p._home()),
            *_retract(),
        ]

    def _home(self) -> np.ndarray:
        """Where the object taken goes: a free spot in the RWS (chosen once)."""
        if self._home_xy is None:
            self._home_xy = free_rws_spot(self)
        return self._home_xy
