"""The parts of an episode, by interface: what the loop (`assistbot.episode.runner.Episode`) needs of each.

    world --Perception--> Percept --Agent--> Decision --Actor--> motion
                                      |utterances--> Partner (hears) --> the person's arm
    the Task watches from outside: world events, the success test, the failure kinds, the end;
    Measures watch the agent: the percepts it is given, the decisions it takes.

In the spirit of dm_control's physics / task / environment split: the loop imports none of the concrete
parts; a builder (`assistbot.episode.builder`) makes them from a scenario. The DNF architecture is one
`Agent` (`assistbot.cognition.Cognition`); vision and the labelled oracle are two `Perception`s; the robot
executor is the `Actor`; the scripted person is the `Partner`; `DrinkingTask` is the `Task`.

One `Status` for everything that can run and end: a robot primitive, a robot action, a behaviour of the
person. The robot's proprioception is `RobotPercept` (what the gripper holds, the action, its status).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

if TYPE_CHECKING:
    import numpy as np

    from assistbot.cognition.percept import Decision, Percept, RobotPercept

#: the control period (s): the loop ticks the actor and the partner, and advances the physics, by this much
CONTROL_DT = 0.02


class Status(str, enum.Enum):
    """How a thing that runs stands: not started, running, or ended one way or the other. A str, so that
    logs and summaries carry the plain word."""

    IDLE = "idle"
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"

    @property
    def ended(self) -> bool:
        return self in (Status.SUCCEEDED, Status.FAILED)

    def __str__(self) -> str:
        return self.value


@dataclass
class ActionRecord:
    """One action the actor carried out: when it began and ended, and how."""

    action: str
    start: float
    end: float | None = None
    status: Status = Status.RUNNING
    reason: str = ""


@dataclass(frozen=True)
class PartnerView:
    """What a perfect observer sees the partner do (for the labelled oracle): the behaviour under way, its
    arguments (the object it is about, say), and the arm's posture. Not the partner's plans or memory."""

    behaviour: str | None = None
    args: dict[str, Any] = field(default_factory=dict)
    posture: str = "open"


@dataclass(frozen=True)
class PartnerEvent:
    """One thing the partner did, as the log keeps it: ``kind`` is "start", a `Status` value for an end
    ("succeeded", "failed"), or a note ("heard", "saw", "clamped", "note"); ``what`` names the behaviour."""

    t: float
    kind: str
    what: str
    detail: dict[str, Any] = field(default_factory=dict)


class Perception(Protocol):
    """The world as the robot sees it: a `Percept` at each perception tick."""

    name: str                 # what summaries record: "vision", "oracle"
    label: str                # what captions say (an oracle's says it is ground truth, not vision)
    render_seconds: float     # of the last `perceive`: the wall time spent drawing camera images

    def perceive(self, t: float, body: RobotPercept) -> Percept: ...

    def overlay(self) -> np.ndarray | None:
        """An image of what was perceived last (for the video), or None."""
        ...

    def close(self) -> None: ...


class Agent(Protocol):
    """The robot's mind: Percept in, Decision out."""

    def update(self, percept: Percept) -> Decision:
        """Take in a percept (at ``percept.t``) and decide."""
        ...

    def between(self, t: float) -> Decision:
        """Run on, without a new percept, up to ``t`` (the control ticks between perception ticks)."""
        ...

    def decisions(self) -> list[tuple[float, str, str]]:
        """(t, "decide" or "release (<status>)", action), in order: what the summary reports."""
        ...

    def trace(self) -> dict[str, Any]:
        """What the agent wants logged at each perception tick (the DNF: the peaks of its layers)."""
        ...


@runtime_checkable
class FieldAgent(Agent, Protocol):
    """An agent made of dynamic neural fields: its network can be drawn and recorded (video, figures)."""

    net: Any

    def record(self, layers: Any = None, every: int = 4, couplings: Any = ()) -> Any: ...


class Actor(Protocol):
    """The robot's body: decisions become motion (or speech acts); reports how each action ended."""

    action: str | None
    records: list[ActionRecord]

    def see(self, percept: Percept) -> None: ...

    def begin(self, action: str, t: float, utterance: str = "") -> None: ...

    def tick(self, t: float, dt: float) -> None: ...

    def proprioception(self) -> RobotPercept: ...

    def ended(self) -> ActionRecord | None:
        """The record of the action that has just ended, once (the actor is idle again after), else None."""
        ...


class Partner(Protocol):
    """The person: hears the robot, sees the world, acts with one arm."""

    log: list[PartnerEvent]

    def hear(self, tag: str, t: float) -> None: ...

    def tick(self, t: float) -> None: ...

    def appearance(self) -> PartnerView:
        """What an observer sees the person do (the labelled oracle reads only this)."""
        ...


class Task(Protocol):
    """The experimenter's side: watches the episode, says when it ends and why."""

    events: list[dict]            # world events, in order ({"t", "event", ...})

    @property
    def end_reason(self) -> str | None:
        """Once ended: "drink", "stalled", ... (`assistbot.episode.judge.END_REASONS`); else None."""
        ...

    def decided(self, t: float, action: str) -> None: ...

    def action_ended(self, t: float, record: ActionRecord) -> None: ...

    def said(self, t: float, tag: str) -> None: ...

    def partner_did(self, event: PartnerEvent) -> None: ...

    def observe(self, t: float) -> None:
        """At a perception tick: the world events since the last one."""
        ...

    def stepped(self, t: float, dt: float) -> bool:
        """After each control tick's physics: True once the episode is over."""
        ...

    def outcome(self) -> dict[str, Any]:
        """The task's measures for the summary: ``time_to_drink`` (s or None), ``spilled_fraction``,
        ``min_distance_human`` (m), ``touched_person`` and ``end_detail`` (dicts)."""
        ...


class Measure(Protocol):
    """Watches the agent without acting on the episode: every percept it is given and every decision it takes;
    its ``summary()`` goes into the episode's summary under ``name`` (`assistbot.episode.cues.CueLedger`)."""

    name: str

    def see(self, percept: "Percept") -> None: ...

    def decided(self, t: float, action: str) -> None: ...

    def summary(self) -> dict[str, Any]: ...
