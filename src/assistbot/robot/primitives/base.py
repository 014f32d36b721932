"""The primitive: a list of phases run in order, with the target the arm goes to.

``start(target_xy)`` begins it; ``tick(dt, target_xy) -> Progress`` is called once per control tick
with the current perception of the action's target (table x, y of the object or the human's hand, or
None when it is not seen). The perception feeds the primitive's `TargetField`; the field's peak is the
x, y the arm goes to, while heights and approach orientations come from the primitive's phases. While
the hand carries an object, the primitive checks that it stays there; a phase that fails ends the
primitive, safely first when the hand holds something (`Phase.fallback`).
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from assistbot.interfaces import Status
from assistbot.robot.controller import RobotController
from assistbot.robot.phases import BackOff, Grip, Phase
from assistbot.robot.primitives.geometry import GRASP_HEIGHT, RADIUS, held_centre
from assistbot.robot.primitives.putting_down import set_down_what_is_carried
from assistbot.robot.progress import Progress
from assistbot.robot.target_field import TargetField
from assistbot.world.layout import TABLE_Z

#: the height (m above the table) assumed for the base of an object held up by the person until it is seen
LIFT_GUESS = 0.10
#: time constant (s) over which the perceived height of a held-up object is followed
LIFT_TAU = 0.2
#: m above its grasp height on the table beyond which an object let go of is in the air (given to the person), not set down
IN_THE_AIR_ABOVE = 0.04
#: m above the table that the head looks at a target on it
LOOK_ABOVE_TABLE = 0.05
#: table x, y a primitive started without a perceived target aims at until it sees one
DEFAULT_TARGET_XY = (0.25, 0.0)
#: s the target field is given to form its peak on the first perception
PEAK_FORMING_SECONDS = 0.3


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
                 offered: Callable[[], bool] | None = None,
                 held_out: Callable[[], bool] | None = None,
                 hand_busy: Callable[[], bool] | None = None,
                 seen_state: Callable[[str], str | None] | None = None,
                 reaching_hand: Callable[[], tuple[float, float, float] | None] | None = None,
                 holder_grip: Callable[[], str | None] | None = None) -> None:
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
          held_out()         True while the person's hand is seen, steadily, held out toward the robot (not
                             on its way there, not paused on the way); without perception: True.
          hand_busy()        True while the person's hand is seen, steadily, holding something other than
                             the object acted on: it is not free to take that; without perception: False.
          seen_state(name)   the state of object ``name`` ("inverted", "open", ...) as the cameras have
                             seen it steadily of late, or None (not seen, or read one way and another).
          reaching_hand()    table (x, y, z) of the person's hand as seen in this frame reaching or
                             closing on something, or None.
          holder_grip()      how the person was last seen holding what she holds, during this action: "ag"
                             (from above), "sg" (from the side), or None (not seen holding anything).
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
        self.held_out = held_out or (lambda: True)
        self.hand_busy = hand_busy or (lambda: False)
        self.seen_state = seen_state or (lambda name: None)
        self.reaching_hand = reaching_hand or (lambda: None)
        self.holder_grip = holder_grip or (lambda: None)
        self._offer: np.ndarray | None = None
        #: m above the object's base at which the hand takes it from the table and holds it (None: GRASP_HEIGHT)
        self.held_at: float | None = None
        self._failure: Progress | None = None    # a failure being ended safely (Phase.fallback)
        self.released: tuple[str, tuple[float, float]] | None = None  # the object let go of last, and where
        self.set_down: str | None = None         # the object this primitive set on the table, once the hand backed off it
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
    @property
    def grasp_height(self) -> float:
        """Where (m above its base) the hand takes the target from the table and holds it while carrying it:
        ``held_at`` when the primitive chose it, else the object's GRASP_HEIGHT."""
        if self.held_at is not None:
            return self.held_at
        return GRASP_HEIGHT.get(self.object or "glass", GRASP_HEIGHT["held_out"])

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
            self.robot.look_at(np.array([x, y, TABLE_Z + LOOK_ABOVE_TABLE]))

    # --- running -------------------------------------------------------
    def start(self, target_xy=None) -> None:
        self._xy0 = target_xy if target_xy is not None else DEFAULT_TARGET_XY
        self.field.reset()
        if target_xy is not None:
            # let the field form its peak on the first perception
            self.field.observe(target_xy)
            self.field.advance(PEAK_FORMING_SECONDS)
        self._peak = None
        self._lift, self._lift_frozen = None, False
        self._see_lift(1.0)
        self.robot.reset_command()
        self._held_xy = None
        self.carrying = False
        self._let_go_of: str | None = None
        self.supported = False      # the table carries what the hand holds (`LowerUntilSupported`)
        self.set_down = None
        self._phases = self.phases()
        self._t, self._t_total = 0.0, 0.0
        self._failure = None
        self._k = self._start_from(0)
        self.progress = (Progress(Status.RUNNING, self._phases[self._k].name) if self._k < len(self._phases)
                         else Progress(Status.SUCCEEDED, self._phases[-1].name))   # nothing to do at all

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
                fallback = set_down_what_is_carried
            if fallback is not None:
                # end safely first, then report
                self._failure = Progress(Status.FAILED, phase.name, reason, self._t_total)
                self._phases = self._phases[:self._k + 1] + fallback(self)
                status = Status.SUCCEEDED
        if status is Status.FAILED:
            self.progress = Progress(Status.FAILED, phase.name, reason, self._t_total)
        elif status is Status.SUCCEEDED:
            self._after(phase)
            self._k = self._start_from(self._k + 1)
            if self._k >= len(self._phases) and self._failure is not None:
                self.progress = Progress(Status.FAILED, self._failure.phase, self._failure.reason, self._t_total)
            elif self._k >= len(self._phases):
                self.progress = Progress(Status.SUCCEEDED, phase.name, "", self._t_total)
            else:
                self._t = 0.0
                self.progress = Progress(Status.RUNNING, self._phases[self._k].name, "", self._t_total)
        else:
            self.progress = Progress(Status.RUNNING, phase.name, "", self._t_total)
        return self.progress

    def _start_from(self, k: int) -> int:
        """Start the phases from ``k`` on until one has something to do (`Phase.idle`); its index."""
        while k < len(self._phases):
            self._phases[k].start(self)
            if not self._phases[k].idle:
                break
            k += 1
        return k

    def before(self, name: str) -> bool:
        """Whether a phase named ``name`` is still to come (not yet started, nor left out by a fallback)."""
        return any(ph.name == name for ph in self._phases[self._k + 1:])

    def interrupted(self, phase: Phase) -> str:
        """Why ``phase`` must stop now, from what is perceived ("" to go on); its fallback then ends it safely."""
        return ""

    def _after(self, phase: Phase) -> None:
        if isinstance(phase, BackOff) and self._let_go_of is not None:
            self.set_down = self._let_go_of
        if isinstance(phase, Grip):
            self.carrying = phase.close
            if phase.close:
                self._held_xy = self.xy().copy()
                self._lift_frozen = True

    @property
    def let_go_of(self) -> str | None:
        """The object this action has let go of standing on the table, if any (`note_set_down`)."""
        return self._let_go_of

    def note_set_down(self) -> None:
        """Letting go of an object set down on the table: where it stands, as the robot's own body knows it
        (the axis of a side grasp lies beyond the TCP along the approach), for when its arm hides it. On the
        table when the hand felt the table carry it, or is as low as a grasp of it standing there."""
        pose = self.robot.tcp_pose()
        obj = self.object
        on_table, self.supported = self.supported, False
        if obj not in RADIUS or obj == "held_out" or (
                not on_table and pose.translation()[2] > TABLE_Z + self.grasp_height + IN_THE_AIR_ABOVE):
            return      # let go of in the air: into the person's hand
        c = held_centre(pose, obj)
        self.released = (obj, (float(c[0]), float(c[1])))
        self._let_go_of = obj
