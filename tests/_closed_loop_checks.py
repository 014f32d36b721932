"""What the seed's experiments must show at the end of an episode, whatever the perception.

Shared by the oracle closed-loop tests and the vision end-to-end tests.
"""

from __future__ import annotations


def in_order(seq: list[str], wanted: list[str]) -> bool:
    it = iter(seq)
    return all(any(x == w for x in it) for w in wanted)


def check_fig3_4(r) -> None:
    """SG grasp -> error; robot holds, human removes the stopper; A6 (never A7); fill; hand over; drink."""
    decisions = [a for _, a in r.decisions]
    assert r.success, (r.end_reason, decisions, r.actions)
    assert in_order(decisions, ["Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                                "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]), decisions
    assert "Reach-turn-and-hand-over-glass" not in decisions  # A6 wins over A7: the open bottle is in the RWS
    spoken = {u["source"] for u in r.utterances}
    for action in ("Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass",
                   "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"):
        assert f"AEL:{action}" in spoken, action
    events = [e["event"] for e in r.world_events]
    # the physical story: stopper off while the robot holds the bottle, glass turned, then filled, then drunk
    assert in_order(events, ["stopper_removed", "glass_turned", "glass_filled", "drink"]), events
    removed = next(e for e in r.world_events if e["event"] == "stopper_removed")
    assert removed["robot_holds"] == "bottle"
    assert r.min_distance_human >= 0.05
    assert r.spilled_fraction < 0.10


def check_fig5(r) -> None:
    """A passive person: hold for the stopper, request the glass (not hand over the bottle), fill, hand over, drink."""
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
