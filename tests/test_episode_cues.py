"""Each decision against the cues of the person's hand the agent was shown just before it: answered,
ignored, or taken without one (the seed's fallback). The tables come from the task's own weights."""

import pytest

from assistbot.cognition.percept import HandPercept, Percept
from assistbot.episode.cues import CUE_WINDOW, CueLedger, answers, intentions_of


def test_a_cue_signals_the_intentions_whose_chains_it_evidences():
    assert intentions_of("hold_out_glass") == {"Give-glass"}
    assert intentions_of("grasp_sg_glass") == {"Turn-glass", "Drink"}
    assert intentions_of("open_hand_request") == {"Get-glass", "Get-bottle"}
    assert intentions_of("point_bottle") == {"Get-bottle"}
    assert intentions_of("pour") == {"Pour"}


@pytest.mark.parametrize("action,intentions,expected", [
    ("Receive-object", {"Give-glass"}, True),             # the complement of giving
    ("Reach-full-glass-to-hand-over", {"Give-glass"}, False),
    ("Wait", {"Drink"}, True),                            # the person drinks: the robot waits
    ("Suggest-drink", {"Drink"}, False),                  # weighed against while she drinks
    ("Communicate-Error", {"Pour"}, True),                # naming the person's mismatch answers it
])
def test_an_action_answers_an_intention_the_task_weighs_it_positively_for(action, intentions, expected):
    assert answers(action, intentions) is expected


def _feed(ledger, t0, seconds, hand, dt=0.1):
    n = int(round(seconds / dt))
    for k in range(n):
        ledger.see(Percept(t=round(t0 + k * dt, 3), hand=hand(k) if callable(hand) else hand))
    return round(t0 + (n - 1) * dt, 3)


def _kind(ledger, t, action):
    ledger.decided(t, action)
    return ledger.decisions[-1]["kind"]


HELD_OUT = HandPercept(posture="grasp_ag", object_in_hand="glass", held_out=True)
STILL = HandPercept(posture="none")


def test_a_decision_after_a_cue_answers_or_ignores_it_and_one_without_a_cue_is_the_fallback():
    led = CueLedger()
    t = _feed(led, 0.0, 2.0, HELD_OUT)
    assert _kind(led, t, "Receive-object") == "answered"
    assert _kind(led, t, "Request-bottle") == "ignored"
    t = _feed(led, t + 0.1, 2.0, STILL)
    assert _kind(led, t, "Reach-full-glass-to-hand-over") == "without cue"
    assert led.counts() == {"answered": 1, "ignored": 1, "without_cue": 1}
    assert led.decisions[0]["cues"] == ["grasp_ag_glass", "hold_out_glass"]


def test_a_cue_must_show_in_half_the_window_and_a_reach_is_no_cue():
    led = CueLedger()
    # a misread posture in 2 of 10 frames is not a cue
    t = _feed(led, 0.0, 1.0, lambda k: HELD_OUT if k in (3, 7) else STILL)
    assert led.cues_at(t) == []
    # the hand reaching for the glass says where it goes, not what for
    t = _feed(led, t + 0.1, 1.0, HandPercept(posture="reach", directed_at="glass"))
    assert led.cues_at(t) == [] and _kind(led, t, "Request-glass") == "without cue"
    # a cue older than the window is gone
    t = _feed(led, t + 0.1, 1.0, HELD_OUT)
    t = _feed(led, t + 0.1, CUE_WINDOW + 0.2, STILL)
    assert led.cues_at(t) == []
