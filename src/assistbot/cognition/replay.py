"""Run an agent (the field architecture by default) on a percept timeline and collect what it decided and said."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from assistbot.cognition.architecture import Cognition
from assistbot.cognition.config import LAYERS
from assistbot.cognition.percept import Decision, Said
from assistbot.cognition.timeline import Timeline
from assistbot.interfaces import Agent


@dataclass
class Replay:
    """The outcome of one timeline: the agent (the architecture, with its recorder), every decision, the log."""

    timeline: Timeline
    agent: Agent
    decisions: list[Decision] = field(default_factory=list)
    recorder: Any = None

    @property
    def cognition(self) -> Cognition:
        """The field architecture that ran (its fields, for the figures)."""
        if not isinstance(self.agent, Cognition):
            raise TypeError(f"the timeline ran {type(self.agent).__name__}, not the field architecture")
        return self.agent

    @property
    def said(self) -> list[Said]:
        return [u for d in self.decisions for u in d.utterances]

    @property
    def chosen(self) -> list[str]:
        """The actions decided, in order."""
        return [a for _, kind, a in self.agent.decisions() if kind == "decide"]

    def decided_at(self, action: str) -> float | None:
        for t, kind, a in self.agent.decisions():
            if kind == "decide" and a == action:
                return t
        return None

    def peaks_at(self, t: float) -> dict[str, list[str]]:
        """The peaks of each layer at the last update at or before ``t`` (s)."""
        best = None
        for d in self.decisions:
            if d.t <= t + 1e-9:
                best = d
        return best.peaks if best else {L: [] for L in LAYERS}

    def log_lines(self) -> list[str]:
        """The decision / utterance log, one event per line, in time order."""
        events: list[tuple[float, int, str]] = []
        targets = iter([d.target for d in self.decisions if d.new and d.action])   # one per decision, in order
        for t, kind, a in self.agent.decisions():
            if kind == "decide":
                target = next(targets, None)
                events.append((t, 0, f"{t:7.2f}  DECIDE   {a}" + (f"  (target: {target})" if target else "")))
            else:
                events.append((t, 0, f"{t:7.2f}  RELEASE  {a}  [{kind.replace('release ', '').strip('()')}]"))
        for s in self.said:
            events.append((s.t, 1, f"{s.t:7.2f}  SAY {s.layer:<4} {s.item}: \"{s.text}\"  <{s.tag}>"))
        return [line for _, _, line in sorted(events, key=lambda e: (e[0], e[1]))]


def replay(timeline: Timeline, overrides: Mapping[str, Any] | None = None, record: bool = True, every: int = 4,
           backend: str = "auto", seed: int | None = 0, agent: str = "dnf", learn: Path | None = None) -> Replay:
    """Play ``timeline`` (ground-truth percepts) into a fresh agent: the field architecture (``dnf``, recorded
    for the figures when ``record``), or any other `assistbot.agents` name or ``module:factory``. ``learn``: a
    weights file the field architecture starts from (if it exists), learns on, and writes back
    (`assistbot.cognition.learning`)."""
    from assistbot.cognition import learning

    rec = None
    a: Agent
    if learn is not None:
        learning.check_learner(agent)
    if agent == "dnf":
        params = {**timeline.config, **(overrides or {})}
        cog = Cognition(overrides=learning.learning_overrides(params, prefix="") if learn is not None else params,
                        backend=backend, seed=seed)
        episodes = learning.load_into(cog, learn) if learn is not None else 0
        rec = cog.record(every=every) if record else None
        a = cog
    else:
        from assistbot.agents import agent_factory

        a = agent_factory(agent, "--agent")(seed or 0, dict(overrides or {}))
    out = Replay(timeline, a, recorder=rec)
    for p in timeline.percepts():
        out.decisions.append(a.update(p))
    if learn is not None:
        learning.write_weights(learn, cog.learned_weights(), episodes + 1)
    return out
