"""Perturbations of the partner's cues (perturb.*): each does what it says on a recorded percept stream."""

from __future__ import annotations

import copy
import math

import pytest

from assistbot.cognition import timeline_from_dict
from assistbot.cognition.percept import RobotPercept
from assistbot.episode.builder import split_overrides
from assistbot.episode.perturb import Perturbation, PerturbedPerception
from assistbot.errors import UserError

# the person reaches (0.5 s), grips from the side (2.5 s), holds it out (3 s), then rests
STREAM = timeline_from_dict({"name": "cue", "duration": 12.0, "events": [
    {"t": 0.0, "bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "RWS", "state": "inverted"},
     "hand": {"posture": "none"}},
    {"t": 1.0, "hand": {"posture": "reach", "directed_at": "bottle"}},
    {"t": 1.5, "hand": {"posture": "grasp_sg", "object_in_hand": "bottle"}},
    {"t": 4.0, "hand": {"held_out": True}},
    {"t": 7.0, "hand": {"posture": "none", "object_in_hand": None, "held_out": False, "directed_at": None}},
]})


class Replayed:
    """A `Perception` that plays the recorded stream back."""

    name, label, render_seconds = "oracle", "ORACLE", 0.0

    def __init__(self) -> None:
        self._stream = {round(p.t, 3): p for p in STREAM.percepts()}

    def perceive(self, t, body):
        return copy.deepcopy(self._stream[round(t, 3)])    # a fresh percept, as perception gives

    def overlay(self):
        return None

    def close(self):
        pass


def _run(**kw):
    seeing = PerturbedPerception(Replayed(), Perturbation(**kw), seed=3)
    times = sorted(round(p.t, 3) for p in STREAM.percepts())
    return [(t, seeing.perceive(t, RobotPercept()).hand) for t in times]


def _first(hands, posture):
    return next(t for t, h in hands if h.posture == posture)


def test_nothing_changes_without_a_perturbation():
    assert not Perturbation().active
    assert [h.posture for _, h in _run()] == [p.hand.posture for p in STREAM.percepts()]


@pytest.mark.parametrize("delay", [0.5, 1.3, 2.0])
def test_a_delayed_cue_appears_that_much_late(delay):
    clean, late = _run(), _run(cue_delay=delay)
    assert _first(late, "grasp_sg") - _first(clean, "grasp_sg") == pytest.approx(delay, abs=0.051)
    held = next(t for t, h in late if h.held_out)
    assert held - 4.0 == pytest.approx(delay, abs=0.051)


@pytest.mark.parametrize("duration", [0.2, 1.0, 3.0])
def test_a_short_cue_shows_only_for_its_duration_then_the_hand_reads_still(duration):
    hands = _run(cue_duration=duration)
    shown = [t for t, h in hands if h.posture == "grasp_sg"]
    assert shown[0] == pytest.approx(1.5, abs=0.051)
    assert len(shown) * 0.1 == pytest.approx(duration, abs=0.051)
    assert not any(h.held_out for t, h in hands if t >= 1.5 + duration)   # still: nothing held out either


@pytest.mark.parametrize("p", [0.05, 0.3])
def test_posture_flips_at_their_rate_within_the_binomial_interval(p):
    seeing = PerturbedPerception(Replayed(), Perturbation(posture_flip=p), seed=11)
    truth = {round(q.t, 3): q.hand.posture for q in STREAM.percepts()}
    n = flips = 0
    for _ in range(40):      # 40 passes over the stream: ~4800 percepts
        for t in sorted(truth):
            flips += seeing.perceive(t, RobotPercept()).hand.posture != truth[t]
            n += 1
    sd = math.sqrt(p * (1 - p) / n)
    assert abs(flips / n - p) < 4 * sd
    # a flipped grip reads as the other grip (a poor classifier's confusion), not as any posture
    one = _run(posture_flip=1.0)
    assert {h.posture for t, h in one if 1.5 <= t < 7.0} == {"grasp_ag"}


def test_a_change_of_mind_shows_the_other_grip_first():
    hands = _run(change_of_mind=1.0)
    grips = [(t, h.posture) for t, h in hands if h.posture.startswith("grasp")]
    assert grips[0] == (pytest.approx(1.5), "grasp_ag")
    assert _first(hands, "grasp_sg") == pytest.approx(2.5, abs=0.051)


def test_the_same_seed_gives_the_same_flicker():
    a = [h.posture for _, h in _run(posture_flip=0.2)]
    b = [h.posture for _, h in _run(posture_flip=0.2)]
    assert a == b


def test_perturbations_are_scenario_overrides_with_checked_ranges():
    assert split_overrides({"perturb.cue_delay": 1.5}, "s.yaml").perturb == {"cue_delay": 1.5}
    with pytest.raises(UserError, match="perturb.posture_flip.*from 0 to 1"):
        split_overrides({"perturb.posture_flip": 2}, "s.yaml")
    with pytest.raises(UserError, match="did you mean perturb.cue_delay"):
        split_overrides({"perturb.cue_dely": 1}, "s.yaml")
