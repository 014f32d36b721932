"""The state-machine baseline drives whole episodes: the person drinks in every shipped scenario, with the
labelled oracle and with vision, the seed's experiments with the seed's decisions in order -- the
comparison with the field architecture means something only if both solve the task. Slow."""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import pytest

from assistbot.episode import run_scenario
from assistbot.scenario import load_scenario, shipped_scenarios

pytestmark = pytest.mark.slow
SHIPPED = sorted(p.stem for p in shipped_scenarios())
#: the seed's experiments: the decisions the seed reports, in order
SEED_ORDER = {
    "paper-fig3-4": ["Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                     "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"],
    "paper-fig5": ["Grasp-hold-bottle-to-remove-cup", "Request-glass", "Reach-grasp-open-bottle-fill-glass",
                   "Reach-full-glass-to-hand-over"],
    "fig4-fill-and-hand-over": ["Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"],
}


@lru_cache(maxsize=None)
def episode(name: str, perception: str):
    scenario = dataclasses.replace(load_scenario(name), agent="fsm")
    return run_scenario(scenario, perception=perception, video=False)


def in_order(seq: list[str], wanted: list[str]) -> bool:
    it = iter(seq)
    return all(any(x == w for x in it) for w in wanted)


@pytest.mark.parametrize("perception", ["oracle", "vision"])
@pytest.mark.parametrize("name", SHIPPED)
def test_the_fsm_agent_makes_the_person_drink(name, perception):
    r = episode(name, perception)
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert in_order(decisions, SEED_ORDER.get(name, [])), decisions
    assert "Reach-turn-and-hand-over-glass" not in decisions or name != "paper-fig3-4"   # A6, not A7, as the seed
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10
