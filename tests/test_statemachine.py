"""The state-machine baseline (agent: fsm): its transitions on percept timelines, as the field architecture's
decisions are tested (Fig. 3-5 through the same timelines), and its handling of cues, waiting and failure."""

from __future__ import annotations

from pathlib import Path

import pytest

from assistbot.agents import AGENTS, agent_factory
from assistbot.cli import main
from assistbot.cognition import load_timeline, timeline_from_dict
from assistbot.cognition.replay import replay
from assistbot.errors import UserError
from assistbot.statemachine import Phase, StateMachineAgent, StateMachineConfig

TIMELINES = Path(__file__).resolve().parents[1] / "scenarios" / "timelines"
SCENE = {"t": 0.0, "bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "RWS", "state": "inverted"},
         "hand": {"posture": "none"}}


def _tl(events, duration=6.0):
    return timeline_from_dict({"name": "t", "duration": duration, "events": events})


def _fsm(name_or_timeline):
    tl = load_timeline(TIMELINES / f"{name_or_timeline}.yaml") if isinstance(name_or_timeline, str) else name_or_timeline
    return replay(tl, agent="fsm", record=False)


def test_the_fsm_is_an_agent_the_scenarios_can_name():
    assert "fsm" in AGENTS
    agent = agent_factory("fsm", "test")(0, {})
    assert isinstance(agent, StateMachineAgent)
    for method in ("update", "between", "decisions", "trace"):     # the Agent protocol's methods
        assert callable(getattr(agent, method))


def test_fig3_wrong_grip_error_then_hold_for_the_stopper_then_turn_the_glass():
    rep = _fsm("fig3")
    assert rep.chosen == ["Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass"]
    said = [(s.layer, s.item) for s in rep.said]
    assert said[:2] == [("AML", "Cannot-remove-stopper"), ("AEL", "Communicate-Error")]


def test_fig4_fills_then_hands_over():
    assert _fsm("fig4").chosen == ["Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over"]


def test_fig5_passive_user_holds_for_stopper_asks_for_the_glass_fills_hands_over():
    rep = _fsm("fig5")
    assert rep.chosen == ["Grasp-hold-bottle-to-remove-cup", "Request-glass", "Reach-grasp-open-bottle-fill-glass",
                          "Reach-full-glass-to-hand-over"]
    # the request is answered (the glass arrives in the RWS) before the request's release: no waiting then
    assert rep.decided_at("Reach-grasp-open-bottle-fill-glass") - 10.2 < 0.15


@pytest.mark.parametrize("name, error", [("error_pour_closed_bottle", "Pour-from-closed-bottle"),
                                         ("error_drink_empty_glass", "Drink-from-empty-glass")])
def test_a_wrong_move_is_named(name, error):
    rep = _fsm(name)
    assert rep.chosen[:1] == ["Communicate-Error"]
    assert ("AML", error) in [(s.layer, s.item) for s in rep.said]


def test_an_object_held_out_is_received():
    assert _fsm("give_glass").chosen == ["Receive-object"]


def test_one_misread_frame_is_not_a_cue_three_are():
    flick = [SCENE, {"t": 1.0, "hand": {"posture": "pointing", "pointed_at": "glass"}}, {"t": 1.1, "hand": {"posture": "reach"}}]
    assert _fsm(_tl(flick, duration=2.0)).chosen == []
    held = [SCENE, {"t": 1.0, "hand": {"posture": "pointing", "pointed_at": "glass"}}, {"t": 1.4, "hand": {"posture": "reach"}}]
    assert _fsm(_tl(held, duration=2.0)).chosen == ["Reach-turn-and-hand-over-glass"]


def test_the_robot_waits_for_the_person_before_taking_the_initiative():
    # the person is busy with the bottle until 4 s: no step of the robot's own before she rests 3 s
    busy = [SCENE, {"t": 0.0, "hand": {"posture": "reach", "directed_at": "bottle"}}, {"t": 4.0, "hand": {"posture": "none"}}]
    rep = _fsm(_tl(busy, duration=9.0))
    assert rep.chosen == ["Request-bottle"]
    assert 6.85 <= rep.decided_at("Request-bottle") <= 7.05   # the last busy percept at 3.9 s, + 3 s


def test_after_a_request_no_own_step_until_an_answer_or_the_timeout():
    cfg = StateMachineConfig(answer_timeout=5.0)
    agent = StateMachineAgent(cfg)
    events = [{"t": 0.0, "bottle": {"zone": "RWS", "state": "open"}, "glass": {"zone": "HWS", "state": "empty"},
               "hand": {"posture": "none"}},
              {"t": 4.0, "robot": {"status": "succeeded", "action": "Request-glass"}}]
    for p in _tl(events, duration=12.0).percepts():
        agent.update(p)
        if p.t == pytest.approx(5.0):
            assert agent.phase is Phase.AWAITING
    decided = [(round(t, 1), a) for t, kind, a in agent.decisions() if kind == "decide"]
    # the first percept comes at 0.1 s: the hand has rested 3 s at 3.1 s; released at 4 s, asked again at 9 s
    assert decided == [(3.1, "Request-glass"), (9.0, "Request-glass")]


def _failing(action, times, scene, duration=30.0):
    """A timeline in which ``action`` is decided and fails ``times`` times (the executor's report)."""
    events = [scene]
    t = 4.0
    for _ in range(times):
        events.append({"t": t, "robot": {"status": "failed", "action": action}})
        t += 4.0
    return _tl(events, duration=duration)


def test_receive_failing_twice_becomes_a_take_from_the_table_with_its_utterance():
    scene = {**SCENE, "bottle": {"zone": "HWS", "state": "open"},
             "hand": {"posture": "grasp_ag", "object_in_hand": "glass", "held_out": True}}
    rep = _fsm(_failing("Receive-object", 2, scene, duration=12.0))
    assert rep.chosen == ["Receive-object", "Receive-object", "Take-from-table"]
    assert ("AML", "Cannot-take-it-from-the-hand") in [(s.layer, s.item) for s in rep.said]


def test_an_action_failing_twice_in_one_situation_is_not_decided_a_third_time():
    scene = {"t": 0.0, "bottle": {"zone": "RWS", "state": "open"}, "glass": {"zone": "RWS", "state": "empty"},
             "hand": {"posture": "none"}}
    rep = _fsm(_failing("Reach-grasp-open-bottle-fill-glass", 2, scene, duration=30.0))
    assert rep.chosen == ["Reach-grasp-open-bottle-fill-glass"] * 2
    assert [(s.layer, s.item) for s in rep.said].count(("AML", "Keeps-failing")) == 1


def test_a_fallen_object_stops_the_robot_with_its_utterance():
    scene = {"t": 0.0, "bottle": {"zone": "RWS", "state": "open"}, "glass": {"zone": "HWS", "state": "empty"},
             "hand": {"posture": "none"}}
    agent = StateMachineAgent()
    for p in _tl([scene, {"t": 1.0, "bottle": {"lying": True}}], duration=10.0).percepts():
        d = agent.update(p)
        if d.utterances and d.utterances[0].item == "Bottle-fell-over":
            assert agent.phase is Phase.STOPPED
    assert agent.phase is Phase.STOPPED
    assert agent.decisions() == []


def test_fsm_parameters_are_its_own_and_a_wrong_one_is_named():
    assert StateMachineConfig.from_overrides({"answer_timeout": 8}).answer_timeout == 8.0
    with pytest.raises(UserError) as e:
        StateMachineConfig.from_overrides({"k": 0.9})
    assert "answer_timeout" in e.value.message and "cognition.k" in str(e.value)


def test_think_runs_the_fsm_on_a_timeline(tmp_path, capsys):
    assert main(["think", str(TIMELINES / "fig4.yaml"), "--agent", "fsm", "--out", str(tmp_path)]) == 0
    assert "DECIDE   Reach-grasp-open-bottle-fill-glass" in capsys.readouterr().out
    assert "agent: fsm" in (tmp_path / "log.txt").read_text()
    assert not list(tmp_path.glob("*.png"))     # no fields, no field figures


def test_an_object_held_out_that_vision_cannot_name_is_the_one_not_seen_on_the_table():
    scene = {"t": 0.0, "bottle": {"zone": "HWS", "state": "open"}, "glass": {"zone": "RWS", "state": "empty"},
             "hand": {"posture": "reach", "directed_at": "bottle"}}
    hidden = {"t": 1.0, "bottle": {"seen": False}, "hand": {"posture": "grasp_ag", "held_out": True}}
    assert _fsm(_tl([scene, hidden], duration=3.0)).chosen == ["Receive-object"]


def test_the_object_just_handed_over_still_held_out_is_not_an_offer_until_the_hand_came_back():
    scene = {"t": 0.0, "bottle": {"zone": "RWS", "state": "open"}, "glass": {"zone": "RWS", "state": "full"},
             "hand": {"posture": "none"}}
    handed = {"t": 4.0, "glass": {"zone": "HWS"}, "robot": {"status": "succeeded", "action": "Reach-full-glass-to-hand-over"},
              "hand": {"posture": "grasp_sg", "object_in_hand": "glass", "held_out": True}}
    back = {"t": 6.0, "hand": {"held_out": False}}
    offered = {"t": 7.0, "hand": {"held_out": True}}
    assert _fsm(_tl([scene, handed, back], duration=6.9)).chosen == ["Reach-full-glass-to-hand-over"]
    assert _fsm(_tl([scene, handed, back, offered], duration=8.0)).chosen == ["Reach-full-glass-to-hand-over", "Receive-object"]
