"""The scene loads, every arrangement settles, WorldState classifies it, bad arrangements are one clear error."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.errors import UserError
from assistbot.world import PAPER_ARRANGEMENTS, Arrangement, all_arrangements, build_world, layout
from assistbot.world.world import CAMERAS, HUMAN_ARM_JOINTS, ROBOT_ARM_JOINTS


def test_scene_names_that_other_parts_use():
    w = build_world(PAPER_ARRANGEMENTS["fig3"])
    m = w.model
    for j in ROBOT_ARM_JOINTS + HUMAN_ARM_JOINTS:
        assert m.actuator(j).id >= 0 and m.joint(j).id >= 0
    for name in CAMERAS:
        assert m.camera(name).id >= 0
    for site in ("human_r_grasp", "human_mouth", "robot_tcp", "bottle_mouth", "glass_rim"):
        assert m.site(site).id >= 0
    left, right = w.data.cam("head_cam_left").xpos, w.data.cam("head_cam_right").xpos
    assert np.linalg.norm(left - right) == pytest.approx(0.12, abs=1e-6)
    assert 30 <= len(w.particle_bodies) <= 80
    assert m.opt.timestep == pytest.approx(0.002)
    assert m.key("home").id >= 0
    # the table top in the model is where layout says
    top = m.geom("table_top")
    assert top.pos[2] + top.size[2] == pytest.approx(layout.TABLE_Z)


@pytest.mark.parametrize("arr", all_arrangements(), ids=lambda a: a.label())
def test_arrangement_settles_and_is_classified(arr):
    w = build_world(arr, seed=1)
    x0 = w.data.xpos.copy()
    w.step(1000)  # 2 s
    assert not np.isnan(w.data.qpos).any()
    assert w.warnings() == {}
    drift = np.linalg.norm(w.data.xpos - x0, axis=1)
    worst = int(drift.argmax())
    assert drift.max() < 1e-3, f"{w.model.body(worst).name} drifted {drift.max() * 1000:.2f} mm"
    s = w.state()
    assert s.objects["bottle"].zone == arr.bottle.zone
    assert s.objects["glass"].zone == arr.glass.zone
    assert s.bottle_state == arr.bottle.state
    assert s.glass_state == arr.glass.state
    n = s.liquid.total
    if arr.glass.state == "full":
        assert (s.liquid.in_glass, s.liquid.in_bottle) == (n, 0)
    else:
        assert (s.liquid.in_glass, s.liquid.in_bottle) == (0, n)
    assert s.liquid.spilled == 0 and s.robot_holds is None and s.human_holds is None


def test_explicit_position_is_used():
    arr = Arrangement.from_mapping({"bottle": {"zone": "RWS", "state": "open", "position": [0.3, -0.3]},
                                    "glass": {"zone": "HWS", "state": "empty"}}, "s.yaml")
    w = build_world(arr)
    assert w.state().objects["bottle"].pos[:2] == pytest.approx((0.3, -0.3), abs=1e-6)


@pytest.mark.parametrize("mapping, key", [
    ({"bottle": {"zone": "XWS", "state": "closed"}, "glass": {"zone": "HWS", "state": "empty"}}, "objects.bottle.zone"),
    ({"bottle": {"zone": "HWS", "state": "corked"}, "glass": {"zone": "HWS", "state": "empty"}}, "objects.bottle.state"),
    ({"bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "HWS", "state": "upside"}}, "objects.glass.state"),
    ({"bottle": {"zone": "HWS", "state": "closed", "position": [-0.2, 0.9]}, "glass": {"zone": "RWS", "state": "empty"}},
     "objects.bottle.position"),
    ({"bottle": {"zone": "HWS", "state": "closed", "position": [0.2, 0.0]}, "glass": {"zone": "RWS", "state": "empty"}},
     "objects.bottle.position"),
    ({"bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "RWS", "state": "empty", "position": [-0.1, 0]}},
     "objects.glass.position"),
    ({"bottle": {"zone": "HWS", "state": "closed"}, "glass": {"zone": "HWS", "state": "empty", "position": [-0.22, -0.1]}},
     "objects.glass.position"),
    ({"bottle": {"zone": "HWS", "state": "closed"}}, "objects.glass"),
    ({"bottle": {"zone": "HWS", "state": "closed", "colour": "red"}, "glass": {"zone": "HWS", "state": "empty"}}, "objects.bottle.colour"),
])
def test_bad_arrangement_names_the_key(mapping, key):
    with pytest.raises(UserError) as exc:
        Arrangement.from_mapping(mapping, "scen.yaml")
    assert exc.value.key == key
    assert exc.value.line().startswith(f"error: scen.yaml: {key}: ")


def test_options_parse_and_name_the_option():
    arr = Arrangement.from_options("hws:Closed", "RWS:inverted")
    assert arr == PAPER_ARRANGEMENTS["fig3"]
    with pytest.raises(UserError) as exc:
        Arrangement.from_options("HWS:closed", "RWS:sideways")
    assert exc.value.key == "--glass"


def test_world_starts_at_the_scenes_home_keyframe():
    w = build_world(PAPER_ARRANGEMENTS["fig4"])
    m, home = w.model, w.model.key("home")
    for a in range(m.nu):
        joint = m.actuator(a).trnid[0]
        assert w.qpos(m.joint(joint).name) == home.qpos[m.jnt_qposadr[joint]]
        assert w.data.ctrl[a] == home.ctrl[a]
