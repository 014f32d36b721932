"""Run the architecture on a percept timeline and collect what it decided and said."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from assistbot.cognition.architecture import Cognition
from assistbot.cognition.config import LAYERS
from assistbot.cognition.percept import Decision, Said
from assistbot.cognition.timeline import Timeline


@dataclass
class Replay:
    """The outcome of one timeline: the architecture (with its recorder), every decision, the log."""

    timeline: Timeline
    cognition: Cognition
    decisions: list[Decision] = field(default_factory=list)
    recorder: Any = None

    @property
    def said(self) -> list[Said]:
        return self.cognition.log

    @property
    def chosen(self) -> list[str]:
        """The actions decided, in order."""
        return [a for _, kind, a in self.cognition.history if kind == "decide"]

    def decided_at(self, action: str) -> float | None:
        for t, kind, a in self.cognition.history:
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
        for t, kind, a in self.cognition.history:
            if kind == "decide":
                target = self.cognition.target_of(a) if a else None
                events.append((t, 0, f"{t:7.2f}  DECIDE   {a}" + (f"  (target: {target})" if target else "")))
            else:
                events.append((t, 0, f"{t:7.2f}  RELEASE  {a}  [{kind.replace('release ', '').strip('()')}]"))
        for s in self.said:
            events.append((s.t, 1, f"{s.t:7.2f}  SAY {s.layer:<4} {s.item}: \"{s.text}\"  <{s.tag}>"))
        return [line for _, _, line in sorted(events, key=lambda e: (e[0], e[1]))]


def replay(timeline: Timeline, overrides: Mapping[str, Any] | None = None, record: bool = True, every: int = 4,
           backend: str = "auto", seed: int | None = 0) -> Replay:
    """Play ``timeline`` through the ORACLE perception into a fresh `Cognition`."""
    cog = Cognition(overrides={**timeline.config, **(overrides or {})}, backend=backend, seed=seed)
    rec = cog.record(every=every) if record else None
    out = Replay(timeline, cog, recorder=rec)
    for p in timeline.percepts():
        out.decisions.append(cog.update(p))
    return out
