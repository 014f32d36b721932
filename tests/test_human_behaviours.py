"""Behaviours in physics: grasps from two placements, the stopper pull (fails free, works held),
the passive profile's patience, determinism.  The robot side is a stand-in: a mocap body whose
weld holds the bottle (physics decides; the human only sees that the stand-in holds it)."""

import mujoco
import numpy as np
import pytest

from assistbot.human.controller import HumanController
from assistbot.human.perception import RobotView
from assistbot.world import Arrangement, World, build_world, layout


def _world_with_standin(arr: Arrangement, seed: int = 0):
    """The scene plus a mocap 'hand' that can weld itself to the bottle (a stand-in robot)."""
    spec = mujoco.MjSpec.from_file(str(layout.SCENE_XML))
    body = spec.worldbody.add_body(name="standin", mocap=True, pos=[0.3, 0.0, 1.2])
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.01, 0, 0], contype=0, conaffinity=0)
    spec.add_equality(name="standin_hold", type=mujoco.mjtEq.mjEQ_WELD, name1="standin", name2="bottle",
                      objtype=mujoco.mjtObj.mjOBJ_BODY, active=False)
    model = spec.compile()
    w = World(model, arr.validate(), seed)
    return w


def _hold_bottle(w):
    """Put the stand-in at the bottle and weld it (keeping the relative pose)."""
    m, d = w.model, w.data
    mid = m.body("standin").mocapid[0]
    d.mocap_pos[mid] = d.xpos[w.body_id["bottle"]] + np.array([0.05, 0, 0.08])
    mujoco.mj_forward(m, d)
    eq = m.equality("standin_hold").id
    m.eq_data[eq, :] = 0
    hb = d.xpos[m.body("standin").id]
    m.eq_data[eq, 3:6] = d.xpos[w.body_id["bottle"]] - hb  # standin frame = world-aligned
    m.eq_data[eq, 6:10] = d.xquat[w.body_id["bottle"]]
    m.eq_data[eq, 10] = 1.0
    d.eq_active[eq] = 1


def _standin_view(w):
    held = bool(w.data.eq_active[w.model.equality("standin_hold").id])
    p = w.data.xpos[w.model.body("standin").id]
    return RobotView("bottle" if held else None, tuple(p), True, False)


@pytest.mark.parametrize("where", [(-0.22, -0.12), (-0.28, -0.02)])
@pytest.mark.parametrize("grip", ["ag", "sg"])
def test_grasp_and_hold_out_bottle(where, grip):
    w = build_world(Arrangement.from_mapping({"bottle": {"zone": "HWS", "state": "closed", "position": list(where)},
                                              "glass": {"zone": "RWS", "state": "empty"}}), seed=0)
    hc = HumanController(w, profile="passive")
    hc.start("grasp", object="bottle", grip=grip, hold_out=True)
    hc.run(9.0)
    assert [e.kind for e in hc.events() if e.kind in ("start", "success", "failure")] == ["start", "success"]
    st = w.state()
    assert st.human_holds == "bottle"
    assert st.objects["bottle"].pos[2] > layout.TABLE_Z + 0.05          # lifted off the table
    assert np.linalg.norm(np.array(st.objects["bottle"].pos[:2]) - np.array(where)) > 0.08   # moved toward the robot


def test_stopper_pull_fails_with_a_free_bottle():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=0)
    hc = HumanController(w, profile="passive")
    hc.start("pull_stopper")
    hc.run(10.0)
    ends = [e for e in hc.events() if e.kind in ("success", "failure")]
    assert ends and ends[0].kind == "failure" and "lifts" in ends[0].detail["reason"]
    assert w.state().stopper_attached


def test_stopper_pull_succeeds_while_the_bottle_is_held():
    w = _world_with_standin(Arrangement.from_options("HWS:closed", "RWS:empty"))
    _hold_bottle(w)
    hc = HumanController(w, profile="passive", see=_standin_view)
    hc.start("pull_stopper")
    hc.run(10.0)
    ends = [e for e in hc.events() if e.kind in ("success", "failure")]
    assert ends and ends[0].kind == "success", ends
    assert not w.state().stopper_attached and w.state().bottle_open


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
