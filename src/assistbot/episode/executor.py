"""The robot side of an episode: AEL decisions become motion primitives or speech acts.

An action that moves the arm runs its primitive (`assistbot.robot.actions`)
with targets from perception; a speech act (Communicate-Error, Suggest-drink,
Wait) lasts as long as it takes to say. Either way the executor reports
``running`` / ``finished`` / ``failed`` as proprioception, which is how
cognition learns that its decision was carried out.
"""

from __future__ import annotations

from dataclasses import dataclass

from assistbot.cognition.percept import Percept
from assistbot.robot.actions import ACTION_PRIMITIVES
from assistbot.robot.controller import RobotController
from assistbot.robot.primitives import Status
from assistbot.speech import reading_time

# How long the robot keeps still for an action that is only speech.
WAIT_SECONDS = 2.0


@dataclass
class ActionRecord:
    action: str
    start: float
    end: float | None = None
    status: str = "running"
    reason: str = ""


class RobotExecutor:
    def __init__(self, world) -> None:
        self.world = world
        self.robot = RobotController(world.model, world.data)
        self.primitive = None
        self.action: str | None = None
        self.status = "idle"
        self.reason = ""
        self._speech_until = 0.0
        self.records: list[ActionRecord] = []
        self._percept: Percept | None = None
        self._last_seen: dict[str, tuple[float, float]] = {}
        self._held_out_seen = False  # the object the person holds out has been seen during this action

    # -- what the robot knows of its own body ------------------------------------------------
    def holding(self) -> str | None:
        body = self.robot.gripper.holding()
        return body if body in ("bottle", "glass") else None

    def proprioception(self) -> dict:
        return {"holding": self.holding(), "action": self.action, "status": self.status}

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
        if p is None or not p.hand.seen:
            return False
        if obj == "held_out":
            return p.hand.object_in_hand is not None
        return p.hand.object_in_hand == obj

    def _stopper_removed(self) -> bool:
        """Seen, not known: the bottle looks open."""
        p = self._percept
        b = p.objects.get("bottle") if p is not None else None
        return bool(b is not None and b.seen and b.state_seen and b.state == "open")

    # -- decisions -----------------------------------------------------------------------------
    def begin(self, action: str, t: float, utterance: str = "") -> None:
        """Start carrying out ``action`` (a new AEL decision)."""
        self.action = action
        self.status = "running"
        self.reason = ""
        self.records.append(ActionRecord(action, t))
        spec = ACTION_PRIMITIVES.get(action)
        if spec is None:
            self.primitive = None
            self._speech_until = t + (WAIT_SECONDS if action == "Wait" else reading_time(utterance or action))
            return
        cls, obj = spec
        self._held_out_seen = False
        self.primitive = cls(self.robot, obj, human_holds=lambda o=obj: self._human_holds(o),
                             locate=self._locate, stopper_removed=self._stopper_removed)
        # hidden right now (often behind the robot's own arm): start from where it was last seen;
        # the gaze goes there and the target field takes over once the cameras see it again
        self.primitive.start(self._locate(obj))

    def see(self, percept: Percept) -> None:
        self._percept = percept
        h = percept.hand
        held = percept.objects.get(h.object_in_hand) if h.seen and h.object_in_hand else None
        if held is not None and held.seen:
            self._held_out_seen = True
        for name, o in percept.objects.items():
            if o.seen:
                self._last_seen[name] = (o.position[0], o.position[1])

    def tick(self, t: float, dt: float) -> None:
        """One control tick: advance the primitive (or the speech act) and note how it ended."""
        if self.status != "running":
            self.robot.hold()
            return
        if self.primitive is None:
            if t >= self._speech_until:
                self._end(t, "finished", "")
            return
        prog = self.primitive.tick(dt, self._target_xy(self.primitive.object))
        if prog.status is Status.SUCCEEDED:
            self._end(t, "finished", "")
        elif prog.status is Status.FAILED:
            self._end(t, "failed", prog.reason)

    def _end(self, t: float, status: str, reason: str) -> None:
        self.status = status
        self.reason = reason
        rec = self.records[-1]
        rec.end, rec.status, rec.reason = t, status, reason

    def acknowledge(self) -> None:
        """Cognition has taken in the end of the action: back to idle."""
        if self.status in ("finished", "failed"):
            self.status = "idle"
            self.action = None
            self.primitive = None
