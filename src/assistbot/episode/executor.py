"""The robot side of an episode: AEL decisions become motion primitives or speech acts.

An action that moves the arm runs its primitive (`assistbot.robot.actions`)
with targets from perception; a speech act (Communicate-Error, Suggest-drink,
Wait) lasts as long as it takes to say. Either way the executor reports its
`Status` (running, succeeded, failed) as proprioception, which is how the
agent learns that its decision was carried out. The episode's `Actor`.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from assistbot import catalogue
from assistbot.cognition.percept import STANDING_Z, HandPercept, Percept, RobotPercept, away_from_hand
from assistbot.interfaces import ActionRecord, Status
from assistbot.robot.actions import ACTION_PRIMITIVES
from assistbot.robot.controller import RobotController
from assistbot.speech import reading_time
from assistbot.task import OBJECTS

# How long the robot keeps still for an action that is only speech.
WAIT_SECONDS = 2.0
#: Wait lasts at least WAIT_SECONDS, then until the partner's hand has been seen at rest (or away)
#: for WAIT_REST s, the act it waited for being over, and at most WAIT_MAX s
WAIT_REST = 1.0
WAIT_MAX = 20.0
#: s for which an open hand seen held out still says where the partner wants things handed
OPEN_HAND_MEMORY = 30.0
#: s for which what the hand believes it holds must be seen away from the hand before the grasp counts as lost
AWAY_SECONDS = 1.0
#: s of the frames showing the person's hand that say whether she still holds something out to the robot
#: (`_offered`), and m within which a hand held still stays in them
OFFER_WINDOW = 1.0
STILL_HAND = 0.02
#: s over which every frame that saw an object's state must have read it the same for the state to count
#: as seen steadily (`_seen_state`), and s after which the last such frame is too old to go by
STEADY_STATE = 0.3
STATE_FRESH = 0.5
#: postures in which the hand uses what it holds for itself
USING = ("pour", "drink")
#: postures of a hand holding something, and the grip each is (`Primitive.holder_grip`)
HELD_GRIPS = {"grasp_ag": "ag", "grasp_sg": "sg"}
#: postures of a hand reaching for an object or closing on it
REACHING = ("reach", "grasp_ag", "grasp_sg")
#: s after the hand was last seen pouring or drinking in which it offers nothing: it first puts down what it used
AFTER_USE = 3.0
#: s for which the base of an object held up, as last seen with the object placed, stands for it while the robot's
#: approaching hand hides it (the hand holding it, seen alone, puts it several cm off)
LIFTED_MEMORY = 5.0


def lost_frame(percept: Percept) -> bool:
    """A frame that saw neither the hand nor any object (a dropped frame, or the robot's own arm across
    both cameras): it says nothing of the scene, not that the scene is empty."""
    return not percept.hand.seen and not any(o.seen for o in percept.objects.values())


class RobotExecutor:
    def __init__(self, world) -> None:
        self.world = world
        self.robot = RobotController(world.model, world.data)
        self.primitive = None
        self.action: str | None = None
        self.status = Status.IDLE
        self.reason = ""
        self._speech_until = 0.0
        self._wait_until = 0.0
        self._rest_since: float | None = None
        self.records: list[ActionRecord] = []
        self._percept: Percept | None = None
        self._last_seen: dict[str, tuple[float, float]] = {}
        self._standing: dict[str, tuple[float, float]] = {}   # objects last seen standing on the table
        self._lifted_seen: dict[str, tuple[float, float]] = {}  # object held up -> (t, its base's height) last placed
        self._open_hand: tuple[float, tuple[float, float, float]] | None = None  # (t, where) the open hand was seen held out
        self._held_out_seen = False  # the object the person holds out has been seen during this action
        self._aim: str | None = None  # what the action's target is perceived as: an object, or "held_out"
        self._in_hand: str | None = None       # what the hand closed on (`holding`)
        self._held_out_name: str | None = None  # what the person was last seen holding, during this action
        self._held_grip: str | None = None      # ... and with which grip ("ag", "sg")
        self._away_since: float | None = None   # since when what the hand believes it holds is seen elsewhere
        self._lost = False                       # ... long enough: this action's grasp is not of it
        # the frames of the last OFFER_WINDOW showing the hand, each with what the hand holds in it (`_hand_busy`)
        self._hand_seen: deque[tuple[float, HandPercept, str | None]] = deque()
        self._used_at = -float("inf")   # when the hand was last seen using what it holds (`USING`)
        self._states: dict[str, tuple[str, float, float]] = {}   # object -> (state, first, last frame read so)

    # -- what the robot knows of its own body ------------------------------------------------
    def holding(self) -> str | None:
        """What the hand holds: the object it closed on (what it set out to grasp, or what it saw the
        person hold out), while its fingers still feel something; the hand's skin does not tell what."""
        if not self.robot.gripper.grasps():
            self._in_hand = None
        return self._in_hand

    def proprioception(self) -> RobotPercept:
        return RobotPercept(holding=self.holding(), action=self.action, status=self.status)

    # -- targets from perception ---------------------------------------------------------------
    def _target_xy(self, obj: str | None):
        p = self._percept
        if p is None or obj is None:
            return None
        if obj == "held_out":
            if not p.hand.seen:
                return None
            held = p.objects.get(p.hand.object_in_hand) if p.hand.object_in_hand else None
            if held is not None and held.seen:   # grasp the object itself, placed better than the hand
                return (held.position[0], held.position[1])
            if self._held_out_seen:
                # the object hidden for a moment (often by the robot's own approaching hand): the target
                # field keeps where it was; the hand's position is too rough to reach for (~6 cm)
                return None
            return tuple(p.hand.position[:2])
        o = p.objects.get(obj)
        if o is None or not o.seen:
            return None
        h = p.hand
        if h.seen and h.object_in_hand == obj and not h.held_out:
            # the person holds it for themselves (to drink, to pour): not a target to follow toward
            # them; the target field keeps where it was
            return None
        return (o.position[0], o.position[1])

    def _locate(self, obj: str | None):
        """Where another object is (an obstacle to keep clear of, the glass to pour into): as seen
        now, else where it was last seen (the robot's arm often hides what stands behind it)."""
        xy = self._target_xy(obj)
        if xy is not None or obj == self.holding():   # what is in the hand stands nowhere
            return xy
        return self._last_seen.get(obj)

    def _human_holds(self, obj: str | None) -> bool:
        p = self._percept
        if p is None or not p.hand.seen or obj is None:
            return False
        if obj == "held_out":
            return p.hand.object_in_hand is not None
        return p.hand.object_in_hand == obj

    @staticmethod
    def _lift_seen(p: Percept, name: str | None) -> tuple[float | None, float | None]:
        """The base height of ``name`` held up, as this frame shows it: (the higher of its own triangulated base and
        the hand's, when the object itself is placed; the hand's alone)."""
        h = p.hand
        o = p.objects.get(name) if name else None
        by_hand = None
        if h.seen and name is not None and h.object_in_hand == name:
            height = catalogue.height(name)
            by_hand = float(h.position[2]) - (height if h.posture == "grasp_ag" else height / 2)
        if o is not None and o.seen and o.position[2] > STANDING_Z:
            return (float(o.position[2]) if by_hand is None else max(float(o.position[2]), by_hand)), by_hand
        return None, by_hand

    def _lifted(self, obj: str | None) -> float | None:
        """Height (m above the table) of the base of ``obj`` held up by the person, as seen now: the higher of the
        object's own triangulated base and the one from the hand that holds it (at the object's top for a grip
        from above, at its middle for one from the side); while the object itself is not placed (the robot's
        approaching hand hides it), that height as last seen with it, for LIFTED_MEMORY s; then the hand's alone;
        None when none is seen. The higher of the two: a hand over the top hides part of the object and vision
        then places it low, and a grasp too low cannot set the object down again (a finger closes under its base).
        The hand's alone, read at times 5 cm low, put such a finger under the glass of partner 1070."""
        p = self._percept
        if p is None or obj is None:
            return None
        name = p.hand.object_in_hand if obj == "held_out" else obj
        seen, by_hand = self._lift_seen(p, name)
        if seen is not None:
            return seen
        last = self._lifted_seen.get(name) if name else None
        if last is not None and p.t - last[0] <= LIFTED_MEMORY:
            return last[1]
        return by_hand

    def _offered(self) -> bool:
        """The person still holds something out to the robot, as the frames of the last OFFER_WINDOW that
        show the hand say: it has kept still (within STILL_HAND), or most of them show it held out; and
        none of the last AFTER_USE s showed it pouring or drinking (a hand that has just poured holds the
        bottle still above the table a moment, on its way to put it down). A hand on its way (lifting the
        bottle to pour, say) passes through the hand-over zone and may be seen held out in a frame or two;
        a hand holding out keeps still, at the zone's edge too, and its posture flickers between classes from frame to frame
        (so stillness is read from the hand's end, which the posture read does not move: most frames within STILL_HAND of
        their median). A hand not seen at all, or whose end the robot's own arm hides (its approaching
        hand, mostly: the end seen then falls short and the outline is partly the robot's), is given the
        benefit of the doubt."""
        if self._percept is not None and self._percept.t - self._used_at < AFTER_USE:
            return False
        frames = [h for _, h, _ in self._hand_seen if not h.end_hidden]
        if not frames:
            return True
        ends = np.array([h.end for h in frames], float)
        near = np.abs(ends - np.median(ends, axis=0)).max(axis=1) <= STILL_HAND
        still = 2 * int(near.sum()) > len(frames)
        return still or 2 * sum(h.held_out for h in frames) >= len(frames)

    def _held_out(self) -> bool:
        """Most of the frames of the last OFFER_WINDOW that show the person's hand show it held out toward the
        robot: it has got there (a hand paused on its way, lifting what it holds first, is still and
        `_offered`, but not held out)."""
        frames = [h for _, h, _ in self._hand_seen]
        return bool(frames) and 2 * sum(h.held_out for h in frames) > len(frames)

    def _hand_busy(self, obj: str | None) -> bool:
        """Most of the frames of the last OFFER_WINDOW that show the person's hand show it holding an object
        other than ``obj`` (one frame's misreading does not count); a hand read as holding an object that the
        same frame sees standing on the table is beside it (it has just put it down), not holding it."""
        frames = [held for _, _, held in self._hand_seen]
        other = sum(held is not None and held != obj for held in frames)
        return bool(frames) and 2 * other > len(frames)

    def _seen_elsewhere(self) -> bool:
        """What the hand believes it holds has been seen away from the hand (vision places an object in
        the robot's hand at the hand unless it sees it elsewhere) for AWAY_SECONDS."""
        p, obj = self._percept, self._in_hand
        o = p.objects.get(obj) if p is not None and obj else None
        away = bool(o is not None and o.seen and away_from_hand(o.position, self.robot.tcp_pose().translation()))
        if not away:
            self._away_since = None
            return False
        self._away_since = p.t if self._away_since is None else self._away_since
        self._lost = p.t - self._away_since >= AWAY_SECONDS
        return self._lost

    def _partner_hand(self) -> tuple[float, float, float] | None:
        """Where the partner's open hand was last seen held out (table x, y, z), within OPEN_HAND_MEMORY s."""
        now = self._percept.t if self._percept is not None else 0.0
        if self._open_hand is None or now - self._open_hand[0] > OPEN_HAND_MEMORY:
            return None
        return self._open_hand[1]

    def _reaching_hand(self) -> tuple[float, float, float] | None:
        """Where the person's hand is seen in this frame reaching or closing on something (table x, y, z); placed
        short of where it is when the robot's own arm hides its end. What it reaches for is for the caller to
        judge by how near it is: vision names the object nearest the hand, which need not be the one in the
        robot's hand held out to it."""
        p = self._percept
        h = p.hand if p is not None else None
        if h is None or not h.seen or h.posture not in REACHING:
            return None
        return h.position

    def _partner_done(self, t: float) -> bool:
        """The partner's hand seen at rest (no object-directed posture, nothing in it) or not seen at all,
        for WAIT_REST s: the act the robot waited for is over."""
        p = self._percept
        h = p.hand if p is not None else None
        resting = h is None or not h.seen or (h.posture == "none" and h.object_in_hand is None)
        if not resting:
            self._rest_since = None
            return False
        self._rest_since = t if self._rest_since is None else self._rest_since
        return t - self._rest_since >= WAIT_REST

    def _seen_state(self, name: str) -> str | None:
        """The state of ``name`` as seen steadily: every frame that saw its state for STEADY_STATE s read it
        the same, the last of them within STATE_FRESH s; else None (a state read once may be a misreading)."""
        if self._percept is None or name not in self._states:
            return None
        state, first, last = self._states[name]
        return state if last - first >= STEADY_STATE and self._percept.t - last <= STATE_FRESH else None

    def _stopper_removed(self) -> bool:
        """Seen, not known: the bottle looks open."""
        p = self._percept
        b = p.objects.get("bottle") if p is not None else None
        return bool(b is not None and b.seen and b.state_seen and b.state == "open")

    # -- decisions -----------------------------------------------------------------------------
    def begin(self, action: str, t: float, utterance: str = "") -> None:
        """Start carrying out ``action`` (a new AEL decision)."""
        self.action = action
        self.status = Status.RUNNING
        self.reason = ""
        self.records.append(ActionRecord(action, t))
        spec = ACTION_PRIMITIVES.get(action)
        if spec is None:
            self.primitive = None
            self._speech_until = t + (WAIT_SECONDS if action == "Wait" else reading_time(utterance or action))
            self._wait_until = t + WAIT_MAX if action == "Wait" else self._speech_until
            self._rest_since = None
            return
        cls, aim = spec
        self._aim = aim
        self._held_out_seen = False
        self._held_out_name = None
        self._held_grip = None
        self._away_since, self._lost = None, False
        obj = aim
        if aim == "held_out" and self._percept is not None and self._percept.hand.seen and self._percept.hand.object_in_hand:
            obj = self._percept.hand.object_in_hand   # what the person holds out, as seen: what the hand sets out to grasp
        self.primitive = cls(self.robot, obj, human_holds=lambda: self._human_holds(aim or self.primitive.object),
                             locate=self._locate, stopper_removed=self._stopper_removed,
                             lifted=lambda: self._lifted(aim), partner_hand=self._partner_hand,
                             identify=lambda: self._held_out_name, seen_elsewhere=self._seen_elsewhere,
                             offered=self._offered, held_out=self._held_out, hand_busy=lambda: self._hand_busy(self.primitive.object),
                             seen_state=self._seen_state,
                             reaching_hand=self._reaching_hand, holder_grip=lambda: self._held_grip)
        # hidden right now (often behind the robot's own arm): start from where it was last seen;
        # the gaze goes there and the target field takes over once the cameras see it again
        self.primitive.start(self._locate(aim))

    def see(self, percept: Percept) -> None:
        if self._percept is not None and lost_frame(percept):
            # the agent above carries what it saw across such frames; a primitive built on one would
            # act on nothing (no hand holding out, no object): keep the last frame that saw something
            return
        self._percept = percept
        h = percept.hand
        if h.seen and h.posture == "open_palm_request" and h.held_out:
            self._open_hand = (percept.t, tuple(float(v) for v in h.position))
        if h.seen and h.object_in_hand:
            self._held_out_name = h.object_in_hand
            if h.posture in HELD_GRIPS:
                self._held_grip = HELD_GRIPS[h.posture]
        if h.seen:
            o = percept.objects.get(h.object_in_hand) if h.object_in_hand else None
            standing = o is not None and o.seen and o.position[2] < STANDING_Z
            self._hand_seen.append((percept.t, h, None if standing else h.object_in_hand))
            if h.posture in USING and not h.end_hidden:
                self._used_at = percept.t
        while self._hand_seen and self._hand_seen[0][0] <= percept.t - OFFER_WINDOW:
            self._hand_seen.popleft()
        held = percept.objects.get(h.object_in_hand) if h.seen and h.object_in_hand else None
        if held is not None and held.seen:
            self._held_out_seen = True
        for name, o in percept.objects.items():
            if o.seen and o.state_seen:
                prev = self._states.get(name)
                first = prev[1] if prev is not None and prev[0] == o.state else percept.t
                self._states[name] = (o.state, first, percept.t)
            if o.seen:
                self._last_seen[name] = (o.position[0], o.position[1])
                lift = self._lift_seen(percept, name)[0]
                if lift is not None and name != percept.robot.holding:
                    self._lifted_seen[name] = (percept.t, lift)
                else:
                    self._lifted_seen.pop(name, None)
                if o.position[2] < STANDING_Z and name != percept.robot.holding:
                    self._standing[name] = (o.position[0], o.position[1])
                else:
                    self._standing.pop(name, None)

    def _obstacles(self) -> dict[str, tuple[float, float] | None]:
        """The objects the arm keeps clear of: those standing on the table, but for the one it acts on until
        it has set that one down and backed off it (withdrawing, the arm must not sweep it over)."""
        p = self.primitive
        acted_on, set_down = (p.object, p.set_down) if p is not None else (None, None)
        return {name: xy for name, xy in self._standing.items()
                if (name != acted_on or name == set_down) and name != self.holding()}

    def tick(self, t: float, dt: float) -> None:
        """One control tick: advance the primitive (or the speech act) and note how it ended."""
        if self.status is not Status.RUNNING:
            self.robot.hold()
            return
        if self.primitive is None:
            if t >= self._speech_until and (self.action != "Wait" or self._partner_done(t) or t >= self._wait_until):
                self._end(t, Status.SUCCEEDED, "")
            return
        self.robot.ik.set_obstacles(self._obstacles())
        prog = self.primitive.tick(dt, self._target_xy(self._aim))
        if self._lost:
            self._in_hand = None      # the cameras saw it elsewhere: whatever the hand holds, not that
        elif self.primitive.carrying and self.primitive.object in OBJECTS:
            self._in_hand = self.primitive.object
        if self.primitive.released is not None:
            # where it set the object down, the robot knows without looking (its arm may hide it now)
            name, xy = self.primitive.released
            self._last_seen[name] = self._standing[name] = xy
            self.primitive.released = None
        if prog.status.ended:
            self._end(t, prog.status, prog.reason if prog.status is Status.FAILED else "")

    def _end(self, t: float, status: Status, reason: str) -> None:
        self.status = status
        self.reason = reason
        rec = self.records[-1]
        rec.end, rec.status, rec.reason = t, status, reason

    def ended(self) -> ActionRecord | None:
        """The record of the action that has just ended, once: the agent has taken in its end (in the
        proprioception of the percept it was given), and the executor is idle again."""
        if not self.status.ended:
            return None
        self.status = Status.IDLE
        self.action = None
        self.primitive = None
        return self.records[-1]
