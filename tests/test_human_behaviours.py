"""Behaviours in physics: grasps from two placements, the stopper pull (fails free, works held),
the passive profile's patience, determinism, the wrong grip set down and taken again to give.
(The stopper pull while the robot holds the bottle, with the `human.standin` robot, is in
test_human_acts.py.)"""

import numpy as np
import pytest

from assistbot.human.behaviours import GRASP_HEIGHT
from assistbot.human.controller import HumanController
from assistbot.world import Arrangement, build_world, layout


@pytest.mark.parametrize("where", [(-0.22, -0.12), (-0.28, -0.02)])
@pytest.mark.parametrize("grip", ["ag", "sg"])
def test_grasp_and_hold_out_bottle(where, grip):
    w = build_world(Arrangement.from_mapping({"bottle": {"zone": "HWS", "state": "closed", "position": list(where)},
                                              "glass": {"zone": "RWS", "state": "empty"}}), seed=0)
    hc = HumanController(w, profile="passive")
    hc.start("grasp", object="bottle", grip=grip, hold_out=True)
    hc.run(9.0)
    assert [e.kind for e in hc.events() if e.kind in ("start", "succeeded", "failed")] == ["start", "succeeded"]
    st = w.state()
    assert st.human_holds == "bottle"
    assert st.objects["bottle"].pos[2] > layout.TABLE_Z + 0.05          # lifted off the table
    assert np.linalg.norm(np.array(st.objects["bottle"].pos[:2]) - np.array(where)) > 0.08   # moved toward the robot


def test_stopper_pull_fails_with_a_free_bottle():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=0)
    hc = HumanController(w, profile="passive")
    hc.start("pull_stopper")
    hc.run(10.0)
    ends = [e for e in hc.events() if e.kind in ("succeeded", "failed")]
    assert ends and ends[0].kind == "failed" and "lifts" in ends[0].detail["reason"]
    assert w.state().stopper_attached


def test_passive_does_nothing_for_30_s_without_a_request():
    w = build_world(Arrangement.from_options("HWS:closed", "HWS:inverted"), seed=0)
    hc = HumanController(w, profile="passive")
    q0 = hc.arm.q.copy()
    hc.run(30.0)
    assert hc.events("start") == []
    assert np.allclose(hc.arm.q, q0)
    st = w.state()
    assert st.stopper_attached and st.human_holds is None and st.objects["glass"].inverted


def test_passive_answers_a_request_for_the_bottle():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=0)
    hc = HumanController(w, profile="passive")
    hc.run(1.0)
    hc.hear("request:bottle", w.time)
    hc.run(8.0)
    starts = hc.events("start")
    assert starts and starts[0].what == "hand_to_robot" and starts[0].t >= 1.0 + hc.profile.reaction_delay - 1e-6
    assert w.state().human_holds == "bottle"


def _trajectory(seed):
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:inverted"), seed=seed)
    hc = HumanController(w, profile="active", seed=seed)
    out = []
    for _ in range(4):
        hc.run(0.5)
        out.append(w.data.qpos.copy())
    return np.array(out), [(e.t, e.kind, e.what) for e in hc.log]


def test_same_seed_same_trajectory():
    a, la = _trajectory(3)
    b, lb = _trajectory(3)
    assert la == lb and np.array_equal(a, b)


def test_asked_for_the_bottle_she_holds_by_its_middle_she_gives_it_from_above():
    """Held out by a side grip round its middle (the wrong grip, taken to hold it out), the bottle leaves no room
    for the robot's hand: her fingers wrap the side it closes on (2.5 cm into its palm in the task-space matrix).
    Asked to hand it over from above, she sets it down and takes it again that way before she holds it out."""
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=0)
    hc = HumanController(w, profile="active")
    hc.start("grasp", object="bottle", grip="sg", hold_out=True)
    hc.run(9.0)
    assert w.state().human_holds == "bottle" and hc.arm.posture == "sg"
    hc.start("hand_to_robot", object="bottle", grip="ag")
    lowest = np.inf
    for _ in range(40):
        hc.run(0.5)
        lowest = min(lowest, float(w.data.xpos[w.body_id["bottle"]][2]))
    assert lowest < layout.TABLE_Z + 0.005            # set down on the table in between
    assert w.state().human_holds == "bottle" and hc.arm.posture == "ag"
    base = w.data.xpos[w.body_id["bottle"]][2]
    assert w.site_pos("human_r_grasp")[2] - base == pytest.approx(GRASP_HEIGHT[("bottle", "ag")], abs=0.02)
