"""Repeated failure of the robot's own action, in a whole episode: a test double of the executor fails a
named action N times (it reports the failure without moving); the fields turn the second failure into
an AML mismatch, the robot says what went wrong, and AEL selects the alternative, which the real
executor then carries out in the physics. ORACLE perception: this isolates cognition and the executor."""

from __future__ import annotations

import dataclasses

import pytest

from assistbot.episode.builder import build_episode
from assistbot.episode.executor import RobotExecutor
from assistbot.interfaces import Status
from assistbot.scenario import parse_scenario

SCENARIO = {"name": "receive-fails", "seed": 0, "time_limit": 150,
            "objects": {"bottle": {"zone": "HWS", "state": "open"}, "glass": {"zone": "RWS", "state": "empty"}},
            "human": {"profile": "passive"}}


class FailingExecutor(RobotExecutor):
    """The real executor, but ``action`` fails its first ``times`` times after ``after`` s, without moving."""

    def __init__(self, world, action: str, times: int, after: float = 1.5) -> None:
        super().__init__(world)
        self.fail_action, self.times, self.after = action, times, after
        self.failed = 0
        self._fail_at: float | None = None

    def begin(self, action, t, utterance=""):
        if action == self.fail_action and self.failed < self.times:
            self.failed += 1
            super().begin("Wait", t, utterance)           # keeps still, as an action that cannot go on
            self.action, self.records[-1].action = action, action
            self._fail_at = t + self.after
            return
        self._fail_at = None
        super().begin(action, t, utterance)

    def tick(self, t, dt):
        if self._fail_at is not None and self.status is Status.RUNNING:
            if t >= self._fail_at:
                self._end(t, Status.FAILED, f"{self.fail_action}: injected failure")
                self._fail_at = None
            return
        super().tick(t, dt)


def episode(times: int, limit: float = 150.0):
    sc = dataclasses.replace(parse_scenario(SCENARIO), time_limit=limit)
    ep = build_episode(sc, perception="oracle")
    ep.actor = FailingExecutor(ep.world, "Receive-object", times)
    return ep, ep.run()


def test_two_failures_to_take_from_the_hand_are_said_and_bring_the_table_hand_over():
    ep, r = episode(2)
    decisions = [a for _, a in r.decisions]
    i = [k for k, a in enumerate(decisions) if a == "Receive-object"]
    assert len(i) == 2, decisions
    alt = decisions.index("Take-from-table")
    assert alt == i[1] + 1, decisions                       # right after the second failure
    said = [u for u in r.utterances if u["source"] == "AML:Cannot-take-it-from-the-hand"]
    t_fail2 = [a["end"] for a in r.actions if a["action"] == "Receive-object"][1]
    assert len(said) == 1 and said[0]["t"] >= t_fail2
    assert r.decisions[alt][0] > said[0]["t"] - 0.5
    # the person set it down under the robot's hand and the robot took it from the table
    took = [a for a in r.actions if a["action"] == "Take-from-table"]
    assert took and took[0]["status"] == "succeeded", r.actions
    assert any(e["what"] == "put_down_for_robot" and e["kind"] == "succeeded" for e in r.human_events)
    assert r.success, (r.end_reason, decisions)


def test_one_failure_is_tried_again_and_nothing_is_said():
    ep, r = episode(1, limit=60.0)
    decisions = [a for _, a in r.decisions]
    assert decisions.count("Receive-object") >= 2 and "Take-from-table" not in decisions, decisions
    assert not [u for u in r.utterances if u["source"].startswith("AML:")]


@pytest.mark.parametrize("mechanism", ["couplings.AFL->AML.k", "stimulus.failure_pulse"])
def test_without_the_mismatch_there_is_no_alternative(mechanism):
    sc = dataclasses.replace(parse_scenario(SCENARIO), time_limit=90.0)
    ep = build_episode(sc, perception="oracle", overrides={f"cognition.{mechanism}": 0.0})
    ep.actor = FailingExecutor(ep.world, "Receive-object", 2)
    r = ep.run()
    assert "Take-from-table" not in [a for _, a in r.decisions]


HOLD_OUT_BOTTLE = {"name": "hold-fails", "seed": 0, "time_limit": 200,
                   "objects": {"bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "RWS", "state": "empty"}},
                   "human": {"profile": "passive"}}


def test_two_failures_to_take_the_bottle_held_out_for_the_stopper_bring_the_table_hand_over():
    # the bottle she holds out to be held for the stopper, taken from her hand twice in vain (beyond the
    # arm's reach, say): the same mismatch as any take from the hand, and the same way round it
    ep = build_episode(parse_scenario(HOLD_OUT_BOTTLE), perception="oracle")
    ep.actor = FailingExecutor(ep.world, "Grasp-hold-bottle-to-remove-cup", 2)
    r = ep.run()
    decisions = [a for _, a in r.decisions]
    i = [k for k, a in enumerate(decisions) if a == "Grasp-hold-bottle-to-remove-cup"]
    assert len(i) >= 2 and "Take-from-table" in decisions, decisions
    alt = decisions.index("Take-from-table")
    assert i[1] < alt and decisions[i[1] + 1:alt].count("Grasp-hold-bottle-to-remove-cup") == 0, decisions
    said = [u for u in r.utterances if u["source"] == "AML:Cannot-take-it-from-the-hand"]
    assert said, [u["source"] for u in r.utterances]
    took = [a for a in r.actions if a["action"] == "Take-from-table"]
    assert took and took[0]["status"] == "succeeded", r.actions
    # then held for the stopper from the robot's side (the stopper comes off in its hand, not knocked off on
    # the way to the table under it), and the task goes on
    assert decisions[alt + 1:].count("Grasp-hold-bottle-to-remove-cup") >= 1, decisions
    opened = [e for e in r.world_events if e["event"] == "stopper_removed"]
    assert opened and opened[0]["robot_holds"] == "bottle", opened
    assert r.success, (r.end_reason, decisions)
