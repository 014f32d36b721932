"""Did a decision answer a cue of the person, ignore one, or come without one? The seed's claim, counted.

The seed argues that in the field architecture a present cue of the partner's intention biases the choice
toward the complementary action, while a missing one leads by itself to a decision that does not count on
the partner. To measure both the same way for every agent, each decision is set against what the agent
itself was shown of the person's hand (the percept, after any perturbation) in the CUE_WINDOW s before it:

* a **cue** is an OL item (`ol_items_of`) other than a reach, shown in at least CUE_SHARE of the percepts
  of the window: a grip on an object, an object held out, a request, a pointing, a pour, a drink, pulling
  the stopper. A reach says where the hand goes, not what for;
* the intentions a cue signals are those of `assistbot.task.INTENTIONS` whose action chains the item
  evidences (positive weights in the task's tables, read, not copied);
* a decision **answers** the cue when the task weighs the decided action positively for one of those
  intentions, or names the person's mismatch (Communicate-Error); else it **ignored** it;
* a decision with no cue in its window was taken **without a cue** (the seed's fallback).

Counts only: whether the answer was right is the task's outcome (time to drink, failed actions).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from assistbot.cognition.architecture import ol_items_of
from assistbot.cognition.percept import Percept
from assistbot.task import ASL_CHAINS, INTENTIONS, ROBOT_ACTION_BY_NAME, ROBOT_ACTIONS

#: s of percepts before a decision in which a cue must show, and the share of them it must show in
CUE_WINDOW = 1.0
CUE_SHARE = 0.5
#: the actions the task weighs up for a mismatch of the person's (naming it): an answer to whatever cue showed it
NAMING_THE_MISMATCH = frozenset(a.name for a in ROBOT_ACTIONS if any(w > 0 for w in a.errors.values()))

_CHAINS = {c.name: c for c in ASL_CHAINS}


def intentions_of(item: str) -> frozenset[str]:
    """The intentions an OL item is evidence of: through the action chains it weighs positively."""
    return frozenset(i.name for i in INTENTIONS
                     if any(w > 0 and _CHAINS[c].primitives.get(item, 0.0) > 0 for c, w in i.chains.items()))


def answers(action: str, intentions: frozenset[str] | set[str]) -> bool:
    """Does the task weigh ``action`` as a complement of one of ``intentions`` (or is it naming a mismatch)?"""
    if action in NAMING_THE_MISMATCH:
        return True
    weights = ROBOT_ACTION_BY_NAME[action].intentions
    return any(weights.get(i, 0.0) > 0 for i in intentions)


@dataclass
class CueLedger:
    """Feed every percept the agent saw (`see`) and every new decision (`decided`); `counts` at the end.
    A `assistbot.interfaces.Measure`: in an episode's summary under ``cues``."""

    name: str = "cues"
    window: float = CUE_WINDOW
    share: float = CUE_SHARE
    _seen: deque = field(default_factory=deque)            # (t, cue items shown then)
    decisions: list[dict] = field(default_factory=list)    # per decision: t, action, cues, kind

    def see(self, percept: Percept) -> None:
        items = frozenset(i for i in ol_items_of(percept) if not i.startswith("reach_"))
        self._seen.append((percept.t, items))
        while self._seen and self._seen[0][0] < percept.t - self.window - 1e-9:
            self._seen.popleft()

    def cues_at(self, t: float) -> list[str]:
        """The cues shown in at least ``share`` of the percepts of the window before ``t``."""
        frames = [items for ts, items in self._seen if t - self.window - 1e-9 <= ts <= t + 1e-9]
        if not frames:
            return []
        every = sorted(set().union(*frames))
        return [c for c in every if sum(c in f for f in frames) >= self.share * len(frames)]

    def decided(self, t: float, action: str) -> None:
        """Record the decision of ``action`` at ``t`` as "answered", "ignored" or "without cue"."""
        cues = self.cues_at(t)
        intentions = set().union(*(intentions_of(c) for c in cues)) if cues else set()
        kind = ("without cue" if not cues else "answered" if answers(action, intentions) else "ignored")
        self.decisions.append({"t": round(t, 3), "action": action, "cues": cues, "kind": kind})

    def summary(self) -> dict:
        return {**self.counts(), "decisions": list(self.decisions)}

    def counts(self) -> dict[str, int]:
        kinds = [d["kind"] for d in self.decisions]
        return {"answered": kinds.count("answered"), "ignored": kinds.count("ignored"),
                "without_cue": kinds.count("without cue")}
