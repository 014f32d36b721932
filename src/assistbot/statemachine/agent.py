"""The state-machine agent: the baseline the field architecture is measured against.

The same contract as the field architecture (`assistbot.interfaces.Agent`): a `Percept` in every 100 ms, a
`Decision` out, the same executor and the same utterances (`assistbot.task.UTTERANCES`). Its states:

    IDLE      nothing decided. A cue of the person (held out, a wrong move, a request, pointing, pouring)
              is answered at once; without one, once the person's hand has rested for
              ``initiative_after`` s, the robot takes the next step of the task (`rules.next_step`).
    ACTING    an action runs until the robot's proprioception reports it ended; then IDLE, or AWAITING
              after an action that asks the person for something.
    AWAITING  the robot asked for something or suggested the drink: cues are answered as in IDLE, but the
              robot takes no step of its own until the situation changes or ``answer_timeout`` s pass.
    STOPPED   an object fell over: the robot says so once and does nothing more.

Repeated failure: an action that failed ``max_failures`` times in the same situation (the same remembered
facts) is not chosen again there; the robot says so (Keeps-failing, or Cannot-take-it-from-the-hand
followed by its alternative, Take-from-table).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, fields
from typing import Any

from assistbot.cognition.percept import Decision, Percept, Said
from assistbot.errors import UserError
from assistbot.statemachine import rules
from assistbot.statemachine.memory import Memory
from assistbot.task import FAILURE_OF, FALLS, ROBOT_ACTION_BY_NAME, UTTERANCES

#: the partner responses (`RobotAction.response`) that come after the robot's action has ended -- the person
#: hands over what was asked for, drinks when told -- rather than during it (taking what the robot holds
#: out, pulling the stopper from the bottle it holds)
ANSWERED_AFTER = ("give_object", "drink")


@dataclass
class StateMachineConfig:
    """The machine's timings and limits (sweepable as ``cognition.<name>`` with ``agent: fsm``)."""

    initiative_after: float = 3.0   # s the person's hand rests before the robot acts on its own
    answer_timeout: float = 15.0    # s the robot waits for an answer to its request or offer
    max_failures: int = 2           # failures of one action in one situation before it is given up there
    fallen_after: float = 1.0       # s an object must be seen lying before the robot gives up
    cue_confirm: float = 0.3        # s a cue of the person must show without a break: one misread frame is not a cue

    @classmethod
    def from_overrides(cls, overrides: dict[str, Any], where: str = "agent: fsm") -> "StateMachineConfig":
        names = {f.name: f.type for f in fields(cls)}
        config = cls()
        for key, value in overrides.items():
            if key not in names:
                raise UserError(where, f"cognition.{key}", f"the fsm agent's parameters are {', '.join(names)}")
            try:
                setattr(config, key, type(getattr(config, key))(value))
            except (TypeError, ValueError):
                raise UserError(where, f"cognition.{key}", f"must be a number, got {value!r}") from None
        return config


class Phase(str, enum.Enum):
    IDLE = "idle"
    ACTING = "acting"
    AWAITING = "awaiting"
    STOPPED = "stopped"


def _say(t: float, layer: str, item: str) -> Said:
    u = UTTERANCES[layer][item]
    return Said(t, layer, item, u.text, u.tag)


class StateMachineAgent:
    """A finite-state controller for the drinking task (see the module docstring)."""

    def __init__(self, config: StateMachineConfig | None = None) -> None:
        self.config = config or StateMachineConfig()
        self.memory = Memory(confirm=self.config.cue_confirm)
        self.phase = Phase.IDLE
        self.doing: str | None = None
        self.error: str | None = None
        self.awaiting_until = 0.0
        self.asked_in: frozenset = frozenset()      # the situation the running (or last) action was decided in
        self.failures: dict[tuple[str, frozenset], int] = {}
        self.said_mismatch: str | None = None     # the mismatch said for the cue still showing
        self.gave_up: set[tuple[str, frozenset]] = set()
        self.just_given: str | None = None       # the object the robot has just handed over
        self.waited: frozenset | None = None      # the situation the robot last decided to wait in
        self.history: list[tuple[float, str, str]] = []
        self.transitions: list[tuple[float, str, str]] = []   # (t, from phase, to phase)

    # -- the Agent interface ------------------------------------------------------------------------
    def update(self, percept: Percept) -> Decision:
        t = percept.t
        m = self.memory
        m.take_in(percept)
        released = self._released(percept)
        self._not_an_offer_what_was_just_given()
        said: list[Said] = []
        fell = m.fallen(t, self.config.fallen_after)
        if fell is not None and self.phase is not Phase.STOPPED and self.phase is not Phase.ACTING:
            self._go(t, Phase.STOPPED)
            said.append(_say(t, "AML", FALLS[fell]))
        if self.phase in (Phase.IDLE, Phase.AWAITING):
            choice = self._choose(t, said)
            if choice is not None:
                action, error = choice
                return self._decide(t, action, error, released, said)
        return Decision(t, action=self.doing, target=self._target(), released=released, error=self.error, utterances=said)

    def between(self, t: float) -> Decision:
        return Decision(t, action=self.doing, target=self._target(), error=self.error)

    def decisions(self) -> list[tuple[float, str, str]]:
        return list(self.history)

    def trace(self) -> dict[str, Any]:
        return {"fsm": self.phase.value}

    # -- the transitions ----------------------------------------------------------------------------
    def _go(self, t: float, phase: Phase) -> None:
        if phase is not self.phase:
            self.transitions.append((t, self.phase.value, phase.value))
            self.phase = phase

    def _situation(self) -> frozenset:
        return frozenset(self.memory.facts().items())

    def _released(self, p: Percept) -> str | None:
        """ACTING -> IDLE or AWAITING once the proprioception reports the action ended."""
        if self.phase is not Phase.ACTING or not (p.robot.status.ended and p.robot.action == self.doing):
            return None
        done, self.doing, self.error = self.doing, None, None
        assert done is not None
        self.history.append((p.t, f"release ({p.robot.status.value})", done))
        if p.robot.status.value == "failed":
            key = (done, self._situation())
            self.failures[key] = self.failures.get(key, 0) + 1
        action = ROBOT_ACTION_BY_NAME[done]
        succeeded = p.robot.status.value == "succeeded"
        asks = action.response in ANSWERED_AFTER and succeeded
        if action.response == "take_object" and succeeded:
            self.just_given = action.target
        if asks:
            self.awaiting_until = p.t + self.config.answer_timeout
        self._go(p.t, Phase.AWAITING if asks else Phase.IDLE)
        return done

    def _not_an_offer_what_was_just_given(self) -> None:
        """The person who has just taken an object from the robot still holds it out as her hand comes
        back: not an offer, until she has once been seen not holding it out."""
        if self.just_given is None:
            return
        held = f"hold_out_{self.just_given}"
        if held in self.memory.showing_since:       # held out in this percept, confirmed or not
            if held in self.memory.cues:
                self.memory.cues.remove(held)
        else:
            self.just_given = None

    def _choose(self, t: float, said: list[Said]) -> tuple[str, str | None] | None:
        m = self.memory
        if not m.known():
            return None
        cue = rules.cue_response(m)
        if cue is not None and cue[0] == "Communicate-Error":
            if cue[1] == self.said_mismatch:
                return None               # said already, while the same wrong move goes on
            self.said_mismatch = cue[1]
            return cue
        if rules.mismatch(m) is None:
            self.said_mismatch = None
        if cue is not None and cue[0] == "Wait":
            if self.waited == self._situation():
                return None               # waited once for this; the person is still at it
            self.waited = self._situation()
        if cue is not None:
            return self._unless_given_up(t, cue[0], said)
        if self.phase is Phase.AWAITING:
            if t < self.awaiting_until - 1e-9 and self._situation() == self.asked_in:
                return None               # no answer yet, and still time for one
            self._go(t, Phase.IDLE)
        if m.person_acting() or m.idle_for(t) < self.config.initiative_after - 1e-9 or m.holding is not None:
            return None
        step = rules.next_step(m)
        if step is None or not rules.feasible(step, m):
            return None
        return self._unless_given_up(t, step, said)

    def _unless_given_up(self, t: float, action: str, said: list[Said]) -> tuple[str, str | None] | None:
        """The action, or its alternative once it has failed ``max_failures`` times in this situation."""
        key = (action, self._situation())
        if self.failures.get(key, 0) < self.config.max_failures:
            return action, None
        if FAILURE_OF.get(action) == "Cannot-take-it-from-the-hand":
            if key not in self.gave_up:
                self.gave_up.add(key)
                said.append(_say(t, "AML", "Cannot-take-it-from-the-hand"))
            return "Take-from-table", None
        if key not in self.gave_up:
            self.gave_up.add(key)
            said.append(_say(t, "AML", "Keeps-failing"))
        return None

    def _decide(self, t: float, action: str, error: str | None, released: str | None, said: list[Said]) -> Decision:
        if error is not None:
            said.append(_say(t, "AML", error))
        said.append(_say(t, "AEL", action))
        self.doing, self.error, self.asked_in = action, error, self._situation()
        self.history.append((t, "decide", action))
        self._go(t, Phase.ACTING)
        return Decision(t, action=action, target=self._target(), new=True, released=released, error=error, utterances=said)

    def _target(self) -> str | None:
        return ROBOT_ACTION_BY_NAME[self.doing].target if self.doing else None


def fsm_agent(seed: int, overrides: dict[str, Any]) -> StateMachineAgent:
    """The factory `assistbot.agents` names ``fsm`` (the machine draws no random numbers: ``seed`` is unused)."""
    return StateMachineAgent(StateMachineConfig.from_overrides(overrides))
