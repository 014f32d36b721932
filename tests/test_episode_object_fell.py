"""An object that falls over ends the task: the robot sees it lying (vision, from its own cameras), says it
cannot go on, and the episode ends naming the object. An object knocked but left standing does not."""

from __future__ import annotations

import pytest

from assistbot.episode.builder import build_episode
from assistbot.scenario import parse_scenario
from assistbot.vision import detect

#: a passive partner: nothing happens on her side. The bottle is what falls: a glass on its side rolls off
#: the table, out of the cameras' view (the judge still ends the episode then, `test_episode_judge`)
SCENARIO = {"name": "bottle-falls", "seed": 0, "time_limit": 20,
            "objects": {"bottle": {"zone": "RWS", "state": "closed", "position": [0.15, 0.15]},
                        "glass": {"zone": "RWS", "state": "empty", "position": [0.2, -0.15]}},
            "human": {"profile": "passive"}}
TIP_UNTIL = 1.25   # s: a twist about the table's x axis from 1 s to this: the bottle tips onto its side


def run(torque: float):
    ep = build_episode(parse_scenario(SCENARIO), perception="vision")
    b = ep.world.body_id["bottle"]

    def push(t: float) -> None:
        ep.world.data.xfrc_applied[b, 3] = torque if 1.0 <= t < TIP_UNTIL else 0.0
    result = ep.run(progress=push)
    said = [e for e in ep.log if e.get("kind") == "say" and e["tag"] == "error:bottle_fell"]
    return ep, result, said


@pytest.mark.slow
def test_a_bottle_that_falls_over_is_seen_lying_and_the_robot_says_it_cannot_go_on():
    ep, result, said = run(0.25)
    assert result.end_reason == "object fell: bottle"
    assert result.end_detail == {"object": "bottle", "robot_said": True}
    assert said and said[0]["text"] == "The bottle has fallen over: I cannot go on."
    # seen, not guessed: the utterance comes after the fall, and the episode ends once it is said
    assert TIP_UNTIL < said[0]["t"] <= result.time


@pytest.mark.slow
def test_without_seeing_it_lie_the_robot_says_nothing_and_the_judge_ends_it_later(monkeypatch):
    monkeypatch.setattr(detect, "LYING_TILT", 9.0)     # vision never reports an object lying
    ep, result, said = run(0.25)
    assert result.end_reason == "object fell: bottle" and result.end_detail["robot_said"] is False
    assert not said


@pytest.mark.slow
def test_a_bottle_knocked_but_left_standing_is_no_fall():
    ep, result, said = run(0.05)      # a nudge: the bottle rocks and stands again
    assert abs(ep.world.data.xmat[ep.world.body_id["bottle"]][8]) > 0.95
    assert not result.end_reason.startswith("object fell")
    assert not said
