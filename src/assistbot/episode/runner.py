"""One episode in simulated time: physics ~2 ms, control 50 Hz, perception 10 Hz.

    physics --render--> Perception --Percept--> Agent --Decision--> Actor --> actuators
                                                  |utterances--> speech log, the Partner hears the tags
    the Partner ticks on what it hears and sees; the world steps; the Task watches and ends the episode.

The loop knows its parts only by their interfaces (`assistbot.interfaces`); `assistbot.episode.builder`
makes them from a scenario. The agent sees only the Percept (vision's, or the labelled oracle's) with the
robot's proprioception. The log (one JSON object per perception tick and per event) and the summary are
written by `assistbot.episode.outputs`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

from assistbot.cognition.percept import Decision, Percept
from assistbot.interfaces import CONTROL_DT, Actor, Agent, Measure, Partner, Perception, Status, Task
from assistbot.speech import SpeechLog

PERCEPTION_EVERY = 5  # control ticks: 10 Hz


@dataclass
class EpisodeResult:
    scenario: str
    seed: int
    perception: str
    success: bool
    end_reason: str
    time: float
    time_to_drink: float | None
    decisions: list[tuple[float, str]]
    releases: list[tuple[float, str, str]]
    utterances: list[dict]
    human_events: list[dict]
    world_events: list[dict]
    actions: list[dict]
    spilled_fraction: float
    min_distance_human: float
    errors_communicated: int
    wall: dict[str, float]
    overrides: dict[str, Any] = field(default_factory=dict)
    touched_person: dict = field(default_factory=dict)
    end_detail: dict = field(default_factory=dict)
    measures: dict = field(default_factory=dict)   # each `Measure`'s summary, by its name
    person: dict = field(default_factory=dict)     # the partner's attributes (human.population; {}: the default person)

    @property
    def n_failed_actions(self) -> int:
        """The robot actions that ended failed (a decision the world did not bear out)."""
        return sum(1 for a in self.actions if a["status"] == "failed")

    def summary(self) -> dict:
        return {
            "scenario": self.scenario, "seed": self.seed, "perception": self.perception,
            "success": self.success, "end_reason": self.end_reason, "end_detail": self.end_detail,
            "time": round(self.time, 3),
            "time_to_drink": None if self.time_to_drink is None else round(self.time_to_drink, 3),
            "decisions": [a for _, a in self.decisions],
            "decision_times": [round(t, 3) for t, _ in self.decisions],
            "utterances": self.utterances, "actions": self.actions, "world_events": self.world_events,
            "human_events": self.human_events,
            "spilled_fraction": round(self.spilled_fraction, 4),
            "min_distance_human": round(self.min_distance_human, 4),
            "touched_person": self.touched_person,
            "errors_communicated": self.errors_communicated,
            **self.measures,
            "wall_seconds": {k: round(v, 3) for k, v in self.wall.items()},
            "overrides": self.overrides,
            "person": self.person,
        }


class _Stopwatch:
    """Adds the wall time of a ``with`` block to one entry of the episode's wall-time account."""

    def __init__(self, wall: dict[str, float]) -> None:
        self.wall = wall
        self.key = ""

    def __call__(self, key: str) -> "_Stopwatch":
        self.key = key
        return self

    def __enter__(self) -> None:
        self.t0 = time.perf_counter()

    def __exit__(self, *exc) -> None:
        self.wall[self.key] += time.perf_counter() - self.t0


class Episode:
    """The loop over one episode's parts. ``scenario`` names the run (its name, for outputs); the parts are
    given, made by `assistbot.episode.builder.build_episode`."""

    def __init__(self, scenario, seed: int, world, perception: Perception, agent: Agent, actor: Actor,
                 partner: Partner, task: Task, overrides: dict[str, Any] | None = None,
                 frame_every: float | None = None, truth: Perception | None = None,
                 measures: tuple[Measure, ...] = (), person: dict[str, Any] | None = None) -> None:
        self.scenario, self.seed, self.overrides = scenario, seed, dict(overrides or {})
        self.person = dict(person or {})   # the partner population's attributes of this person ({}: the default one)
        self.measures = measures   # watch the agent for the summary (the cue ledger, say); never act
        self.world, self.perception, self.agent, self.actor, self.partner, self.task = (
            world, perception, agent, actor, partner, task)
        self.truth = truth       # ground truth for the log only (--record-truth): never reaches the agent
        self.speech = SpeechLog()
        self.log: list[dict] = []
        self.frame_every = frame_every
        self.on_frame: Callable[["Episode"], None] | None = None
        # perception is what turns the world into a Percept (vision's processing, or the oracle);
        # rendering, the head cameras' images it starts from
        self.wall = {"physics": 0.0, "rendering": 0.0, "perception": 0.0, "cognition": 0.0, "robot": 0.0, "human": 0.0,
                     "video": 0.0}
        self._clock = _Stopwatch(self.wall)
        self._n_sub = max(1, int(round(CONTROL_DT / world.model.opt.timestep)))
        self._next_frame = 0.0
        self._partner_seen = 0   # the partner's log entries taken in
        self._task_seen = 0      # the task's world events logged
        self.last_percept: Percept | None = None
        self.last_decision: Decision | None = None
        self._tick = 0

    # -- the loop -----------------------------------------------------------------------------------
    def run(self, progress: Callable[[float], None] | None = None) -> EpisodeResult:
        while True:
            t = self.world.time
            over = self.tick()
            if progress is not None:
                progress(self.world.time)
            if over:
                # a physics that blew up resets its clock to 0: the episode then ended at this tick
                return self._result(self.world.time if self.world.time >= t else t)

    def tick(self) -> bool:
        """One control tick (perceive and decide every PERCEPTION_EVERY-th, act, the person, physics); True
        once the episode is over. `run` loops over it; `assistbot.env` steps it from outside."""
        w, t = self.world, self.world.time
        if self._tick % PERCEPTION_EVERY == 0:
            decision = self._perceive_and_decide(t)
        else:
            with self._clock("cognition"):
                decision = self.agent.between(t)
        self._carry_out(t, decision)
        with self._clock("robot"):
            self.actor.tick(t, CONTROL_DT)
        with self._clock("human"):
            self.partner.tick(t)
        self._take_partner_events()
        self._video_frame(t)
        with self._clock("physics"):
            w.step(self._n_sub)
        self._tick += 1
        over = self.task.stepped(w.time, CONTROL_DT)
        self._log_task_events()
        return over

    def result(self, t_end: float | None = None) -> EpisodeResult:
        """The summary so far (at the end: what `run` returns)."""
        return self._result(self.world.time if t_end is None else t_end)

    def _perceive_and_decide(self, t: float) -> Decision:
        c0 = time.perf_counter()
        percept = self.perception.perceive(t, self.actor.proprioception())
        c1 = time.perf_counter()
        self.actor.see(percept)
        for m in self.measures:
            m.see(percept)
        decision = self.agent.update(percept)
        ended = self.actor.ended()   # the agent has seen the end in this percept's proprioception
        if ended is not None:
            self.task.action_ended(t, ended)
        rendered = self.perception.render_seconds
        self.wall["rendering"] += rendered
        self.wall["perception"] += c1 - c0 - rendered
        self.wall["cognition"] += time.perf_counter() - c1
        self.last_percept = percept
        self.task.observe(t)
        self._log_task_events()
        self._log_tick(t, percept, decision)
        return decision

    def _carry_out(self, t: float, decision: Decision) -> None:
        """What the agent says is spoken (the partner hears it); a new decision starts an action."""
        self.last_decision = decision
        for u in decision.utterances:
            self.speech.say(u.t, u.text, u.tag, f"{u.layer}:{u.item}")
            self.partner.hear(u.tag, u.t)
            self.task.said(u.t, u.tag)
            self.log.append({"t": round(u.t, 3), "kind": "say", "layer": u.layer, "item": u.item, "text": u.text, "tag": u.tag})
        if decision.released:
            self.log.append({"t": round(t, 3), "kind": "release", "action": decision.released})
        if decision.new and decision.action:
            said = [u.text for u in decision.utterances if u.layer == "AEL"]
            self.actor.begin(decision.action, t, said[0] if said else "")
            self.task.decided(t, decision.action)
            for m in self.measures:
                m.decided(t, decision.action)
            self.log.append({"t": round(t, 3), "kind": "decide", "action": decision.action, "target": decision.target})

    def _video_frame(self, t: float) -> None:
        if self.frame_every is not None and t >= self._next_frame and self.on_frame is not None:
            with self._clock("video"):
                self.on_frame(self)
            self._next_frame += self.frame_every

    # -- the log ------------------------------------------------------------------------------------
    def _take_partner_events(self) -> None:
        for ev in self.partner.log[self._partner_seen:]:
            self.log.append({"t": round(ev.t, 3), "kind": "human", "what": ev.kind, "behaviour": ev.what,
                             "detail": {k: v for k, v in ev.detail.items() if isinstance(v, (str, int, float, bool, type(None)))}})
            self.task.partner_did(ev)
        self._partner_seen = len(self.partner.log)

    def _log_task_events(self) -> None:
        for ev in self.task.events[self._task_seen:]:
            self.log.append({"t": ev["t"], "kind": "world", **ev})
        self._task_seen = len(self.task.events)

    def _log_tick(self, t: float, percept: Percept, decision: Decision) -> None:
        objs = {k: {"zone": o.zone, "state": o.state, "seen": o.seen, "state_seen": o.state_seen, "conf": round(o.confidence, 2),
                    "pos": [round(float(v), 3) for v in o.position]} for k, o in percept.objects.items()}
        h = percept.hand
        body = self.actor.proprioception()
        truth = {}
        if self.truth is not None:
            tp = self.truth.perceive(t, body)
            truth = {"truth": {"objects": {k: {"zone": o.zone, "state": o.state} for k, o in tp.objects.items()},
                               "hand": {"posture": tp.hand.posture, "object": tp.hand.object_in_hand, "held_out": tp.hand.held_out}}}
        self.log.append({
            "t": round(t, 3), "kind": "tick",
            "percept": {"objects": objs, "hand": {"posture": h.posture, "seen": h.seen, "object": h.object_in_hand,
                                                  "held_out": h.held_out},
                        "robot": {"holding": body.holding, "action": body.action, "status": body.status}},
            **self.agent.trace(),
            "decision": decision.action, "robot_status": body.status,
            "human": self.partner.appearance().behaviour,
            **truth,
        })

    def _result(self, t_end: float) -> EpisodeResult:
        history = self.agent.decisions()
        decisions = [(t, a) for t, kind, a in history if kind == "decide"]
        releases = [(t, kind, a) for t, kind, a in history if kind != "decide"]
        end_reason = self.task.end_reason or "time limit"
        ends = ("start", Status.SUCCEEDED.value, Status.FAILED.value)
        return EpisodeResult(
            scenario=self.scenario.name, seed=self.seed, perception=self.perception.name,
            success=end_reason == "drink", end_reason=end_reason, time=t_end,
            decisions=decisions, releases=releases,
            utterances=[u.to_dict() for u in self.speech],
            human_events=[{"t": round(e.t, 3), "kind": e.kind, "what": e.what} for e in self.partner.log if e.kind in ends],
            world_events=list(self.task.events),
            actions=[{"action": r.action, "start": round(r.start, 3), "end": None if r.end is None else round(r.end, 3),
                      "status": r.status.value, "reason": r.reason} for r in self.actor.records],
            errors_communicated=sum(1 for _, a in decisions if a == "Communicate-Error"),
            measures={m.name: m.summary() for m in self.measures},
            wall=dict(self.wall),
            overrides=self.overrides,
            person=self.person,
            **self.task.outcome(),
        )
