"""Degraded cues of the partner, applied to the percept after perception, the same for every agent.

The seed argues that in the field architecture a missing or late cue of the partner's intention leads by
itself to a decision that does not count on the partner, while a present cue biases the choice. These
perturbations make cues late, short, wrong or changing, on what perception reports of the person's hand,
so that every agent (`assistbot.agents`) sees the same degraded `Percept`:

    perturb.cue_delay       s (0-2): the hand is reported this much late (its posture, grip, what it holds out)
    perturb.cue_duration    s (0.2-3; 0 = off): a grip, request or pointing is reported for this long, then
                            the hand reads as still (posture none, nothing held out)
    perturb.posture_flip    probability (0-0.3) per percept that the posture reads as another class
                            (a grip as the other grip), flickering as a poor classifier does
    perturb.change_of_mind  s (0 = off): a grip reads as the other grip for its first T s, then as itself
                            (the partner starts with one grip and switches to the other)

`vision.dropout` (whole frames lost) is vision's own. Seeded from the episode's seed: a run repeats.
"""

from __future__ import annotations

import copy
from collections import deque
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from assistbot.cognition.percept import HandPercept, Percept, RobotPercept
from assistbot.errors import UserError
from assistbot.interfaces import Perception
from assistbot.task import HAND_POSTURES

GRIPS = ("grasp_ag", "grasp_sg")
#: postures that are a cue of the partner addressed to the robot or revealing the goal
CUES = (*GRIPS, "open_palm_request", "pointing")
OTHER_GRIP = {"grasp_ag": "grasp_sg", "grasp_sg": "grasp_ag"}


@dataclass(frozen=True)
class Perturbation:
    cue_delay: float = 0.0
    cue_duration: float = 0.0
    posture_flip: float = 0.0
    change_of_mind: float = 0.0

    #: parameter -> (lowest, highest) allowed
    RANGES = {"cue_delay": (0.0, 5.0), "cue_duration": (0.0, 10.0), "posture_flip": (0.0, 1.0), "change_of_mind": (0.0, 10.0)}

    @property
    def active(self) -> bool:
        return any(getattr(self, f.name) > 0 for f in fields(self))


#: the override paths (``perturb.<name>``)
PERTURB_PARAMS: tuple[str, ...] = tuple(f"perturb.{f.name}" for f in fields(Perturbation))


def check_perturb_value(path: str, value: Any, where: str) -> float:
    """A perturbation's value, checked against its range."""
    name = path[len("perturb."):]
    lo, hi = Perturbation.RANGES[name]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not lo <= value <= hi:
        raise UserError(where, path, f"a number from {lo:g} to {hi:g}, got {value!r}")
    return float(value)


class PerturbedPerception:
    """A `Perception` whose percepts of the person's hand are degraded by a `Perturbation`."""

    def __init__(self, inner: Perception, perturbation: Perturbation, seed: int) -> None:
        self.inner = inner
        self.p = perturbation
        self.name = inner.name
        self.label = inner.label
        self._rng = np.random.default_rng([seed, 0x9e37])
        self._past: deque[tuple[float, HandPercept]] = deque()
        self._cue: tuple[str, float] | None = None      # the cue posture showing, since when
        self.render_seconds = 0.0

    def perceive(self, t: float, body: RobotPercept) -> Percept:
        percept = self.inner.perceive(t, body)
        self.render_seconds = self.inner.render_seconds
        percept.hand = self.degrade(t, percept.hand)
        return percept

    def degrade(self, t: float, hand: HandPercept) -> HandPercept:
        """The hand as reported at ``t`` under the perturbation."""
        hand = self._delayed(t, hand)
        hand = copy.copy(hand)
        since = self._showing_since(t, hand)
        if self.p.change_of_mind > 0 and hand.posture in GRIPS and t - since < self.p.change_of_mind - 1e-9:
            hand.posture = OTHER_GRIP[hand.posture]
        if self.p.cue_duration > 0 and hand.posture in CUES and t - since >= self.p.cue_duration - 1e-9:
            hand.posture, hand.held_out, hand.pointed_at, hand.directed_at = "none", False, None, None
        if self.p.posture_flip > 0 and hand.seen and self._rng.random() < self.p.posture_flip:
            hand.posture = self._wrong(hand.posture)
        return hand

    def _delayed(self, t: float, hand: HandPercept) -> HandPercept:
        """The hand as perceived ``cue_delay`` s ago (at rest before anything that old exists)."""
        if self.p.cue_delay <= 0:
            return hand
        due = t - self.p.cue_delay + 1e-9
        self._past.append((t, hand))
        while len(self._past) > 1 and self._past[1][0] <= due:
            self._past.popleft()
        if self._past[0][0] <= due:
            return self._past[0][1]
        return HandPercept(posture="none", seen=hand.seen, position=hand.position)

    def _showing_since(self, t: float, hand: HandPercept) -> float:
        """Since when the current cue posture (the true one, before flips) has shown without a break."""
        key = hand.posture if hand.posture in CUES else ""
        if self._cue is None or self._cue[0] != key:
            self._cue = (key, t)
        return self._cue[1]

    def _wrong(self, posture: str) -> str:
        if posture in OTHER_GRIP:
            return OTHER_GRIP[posture]
        others = [p for p in HAND_POSTURES if p != posture]
        return others[int(self._rng.integers(len(others)))]

    def overlay(self) -> np.ndarray | None:
        return self.inner.overlay()

    def close(self) -> None:
        self.inner.close()
