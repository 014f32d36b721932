"""The MJCF is a scene and self-contained parts: every part file compiles on its own, the scene
includes them and adds only the scene's own things, and the home posture lives in the scene's keyframe."""

from __future__ import annotations

import mujoco
import pytest

from assistbot.resources import MJCF

SCENE = MJCF / "scene.xml"
PARTS = sorted(p for p in MJCF.glob("*.xml") if p != SCENE)


def _names(model: mujoco.MjModel, obj: mujoco.mjtObj, count: int) -> set[str]:
    return {mujoco.mj_id2name(model, obj, i) for i in range(count)} - {None, ""}


def test_the_folder_has_the_parts_the_scene_is_made_of():
    assert {p.stem for p in PARTS} >= {"robot", "human", "table", "objects", "liquid"}


@pytest.mark.parametrize("part", PARTS, ids=lambda p: p.name)
def test_each_part_compiles_alone(part):
    model = mujoco.MjModel.from_xml_path(str(part))
    assert model.nbody > 1


def test_the_scene_is_its_parts_plus_floor_lights_and_cameras():
    scene = mujoco.MjModel.from_xml_path(str(SCENE))
    parts = [mujoco.MjModel.from_xml_path(str(p)) for p in PARTS]
    bodies = set().union(*(_names(m, mujoco.mjtObj.mjOBJ_BODY, m.nbody) for m in parts))
    assert _names(scene, mujoco.mjtObj.mjOBJ_BODY, scene.nbody) == bodies
    materials = set().union(*(_names(m, mujoco.mjtObj.mjOBJ_MATERIAL, m.nmat) for m in parts))
    assert _names(scene, mujoco.mjtObj.mjOBJ_MATERIAL, scene.nmat) == materials | {"floor"}


def test_the_home_keyframe_is_a_posture_within_the_limits_that_its_servos_hold():
    model = mujoco.MjModel.from_xml_path(str(SCENE))
    home = model.key("home")
    assert home.ctrl.shape == (model.nu,)
    for a in range(model.nu):
        joint = model.actuator(a).trnid[0]
        q = home.qpos[model.jnt_qposadr[joint]]
        lo, hi = model.jnt_range[joint]
        assert lo <= q <= hi, model.joint(joint).name
        assert home.ctrl[a] == q, model.actuator(a).name
