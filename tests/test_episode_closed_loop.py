"""The closed loop end to end with the labelled ORACLE perception (ground truth, not vision).

This isolates physics + cognition + robot + human from vision: the seed's Fig. 3-4
storyline must play out in order and end with the person drinking. (The same with
vision is tests/test_episode_e2e.py.) Slow: run by .ci/run and `make test-all`.
"""

from __future__ import annotations

from functools import lru_cache

import pytest

from assistbot.episode import run_scenario

pytestmark = pytest.mark.slow


@lru_cache(maxsize=None)
def episode(name: str):
    return run_scenario(name, perception="oracle", video=False)


def in_order(seq: list[str], wanted: list[str]) -> bool:
    it = iter(seq)
    return all(any(x == w for x in it) for w in wanted)


def test_paper_fig3_4_with_oracle_perception_ends_with_the_drink_in_the_seeds_order():
    r = episode("paper-fig3-4")
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert r.perception == "oracle"
    assert in_order(decisions, ["Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                                "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]), decisions
    assert "Reach-turn-and-hand-over-glass" not in decisions  # A6 wins over A7: the open bottle is in the RWS
    spoken = {u["source"] for u in r.utterances}
    for action in ("Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass"):
        assert f"AEL:{action}" in spoken
    events = [e["event"] for e in r.world_events]
    # the physical story: stopper off while the robot holds the bottle, glass turned, then filled, then drunk
    assert in_order(events, ["stopper_removed", "glass_turned", "glass_filled", "drink"]), events
    removed = next(e for e in r.world_events if e["event"] == "stopper_removed")
    assert removed["robot_holds"] == "bottle"
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10


def test_paper_fig5_passive_user_with_oracle_perception():
    r = episode("paper-fig5")
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert in_order(decisions, ["Grasp-hold-bottle-to-remove-cup", "Request-glass",
                                "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]), decisions
    assert "Hand-over-bottle" not in decisions[: decisions.index("Request-glass")]
    # the passive person starts nothing before the robot first speaks to them
    first_said = min(u["t"] for u in r.utterances if u["source"].startswith("AEL:"))
    starts = [e for e in r.human_events if e["kind"] == "start"]
    assert starts and all(e["t"] > first_said for e in starts)
    events = [e["event"] for e in r.world_events]
    assert in_order(events, ["stopper_removed", "glass_filled", "drink"]), events
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10
