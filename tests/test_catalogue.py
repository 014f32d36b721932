"""The object catalogue: its geometry is the scene's, and every part of the project knows exactly its objects."""

from __future__ import annotations

import json
import math

import mujoco
import pytest

from assistbot import catalogue, task
from assistbot.errors import UserError
from assistbot.resources import TEMPLATES
from assistbot.sweep.spec import OBJECT_PATHS, check_path
from assistbot.vision.library import KINDS
from assistbot.vision.segment import PARTS
from assistbot.world import Arrangement, Placement, all_arrangements, build_world, layout
from assistbot.world.render import SEGMENT_LABELS


@pytest.fixture(scope="module")
def scene() -> mujoco.MjModel:
    return build_world(all_arrangements()[0]).model


@pytest.mark.parametrize("name", catalogue.NAMES)
def test_geometry_is_the_compiled_scenes(scene, name):
    o = catalogue.BY_NAME[name]
    assert catalogue.radius(name) == scene.geom(o.radius_geom).size[0]
    assert catalogue.grasp_height(name) == scene.site(o.grasp_site).pos[2]
    assert scene.site(o.grasp_site).bodyid == scene.body(o.body).id
    if o.top_site is not None:
        assert catalogue.height(name) == scene.site(o.top_site).pos[2]
        assert 0.0 < catalogue.grasp_height(name) < catalogue.height(name)
    else:
        with pytest.raises(ValueError):
            catalogue.height(name)


def test_the_top_of_a_closed_bottle_is_its_stoppers_cap_in_the_physics():
    # one home for "how tall does it stand": the robot's obstacles and clearances, the person's carrying
    w = build_world(Arrangement.from_options("RWS:closed", "HWS:empty"))
    m, d = w.model, w.data
    mujoco.mj_forward(m, d)
    cap = m.geom("stopper_cap").id
    cap_top = d.geom_xpos[cap][2] + m.geom_size[cap][1]
    assert catalogue.top("bottle") == pytest.approx(cap_top - d.xpos[w.body_id["bottle"]][2], abs=1e-6)
    assert catalogue.top("bottle", fitted=False) == catalogue.height("bottle") < catalogue.top("bottle")
    assert catalogue.top("glass") == catalogue.height("glass")


@pytest.mark.parametrize("name", catalogue.NAMES)
def test_every_object_is_in_the_scene_and_in_vision(scene, name):
    o = catalogue.BY_NAME[name]
    body = scene.body(o.body).id
    assert scene.jnt_type[scene.body_jntadr[body]] == mujoco.mjtJoint.mjJNT_FREE
    assert scene.equality(f"human_hold_{name}").id >= 0           # the person's hand can hold it
    assert o.colour in PARTS and o.colour in SEGMENT_LABELS.values()
    assert all(p in catalogue.BY_NAME and not catalogue.BY_NAME[p].task for p in o.parts)


def test_task_objects_have_states_and_a_classifier_in_the_template_library():
    index = json.loads((TEMPLATES / "index.json").read_text())["kinds"]
    assert catalogue.TASK_OBJECTS and all(catalogue.STATES[o] for o in catalogue.TASK_OBJECTS)
    for name in catalogue.TASK_OBJECTS:
        assert KINDS[name] == catalogue.STATES[name]
        assert tuple(index[name]["classes"]) == catalogue.STATES[name]
        for zone in layout.ZONES:
            assert zone in catalogue.BY_NAME[name].places


def test_one_posture_list_for_the_task_and_vision():
    index = json.loads((TEMPLATES / "index.json").read_text())["kinds"]
    assert KINDS["hand"] == task.HAND_POSTURES
    assert tuple(index["hand"]["classes"]) == task.HAND_POSTURES


def test_the_task_reasons_about_the_catalogues_objects():
    assert task.OBJECTS == catalogue.TASK_OBJECTS and task.OBJECT_STATES == catalogue.STATES
    assert {i.rsplit("_", 2)[0] for i in task.OML_ITEMS} == set(catalogue.TASK_OBJECTS)


def _mapping(**states: str) -> dict:
    return {o: {"zone": "HWS" if o == "bottle" else "RWS", "state": states.get(o, catalogue.STATES[o][0])}
            for o in catalogue.TASK_OBJECTS}


@pytest.mark.parametrize("name,state", [(o, s) for o in catalogue.TASK_OBJECTS for s in catalogue.STATES[o]])
def test_the_arrangement_parser_accepts_every_catalogue_state(name, state):
    arr = Arrangement.from_mapping(_mapping(**{name: state}))
    assert arr.placement(name).state == state
    assert [n for n, _ in zip(catalogue.TASK_OBJECTS, arr.placements)] == list(catalogue.TASK_OBJECTS)


@pytest.mark.parametrize("name", catalogue.TASK_OBJECTS)
def test_the_arrangement_parser_rejects_other_states_and_missing_objects(name):
    with pytest.raises(UserError) as exc:
        Arrangement.from_mapping(_mapping(**{name: "melted"}))
    assert exc.value.key == f"objects.{name}.state"
    missing = _mapping()
    del missing[name]
    with pytest.raises(UserError) as exc:
        Arrangement.from_mapping(missing)
    assert exc.value.key == f"objects.{name}"


@pytest.mark.parametrize("name", [o for o in catalogue.NAMES if o not in catalogue.TASK_OBJECTS] + ["cup"])
def test_the_arrangement_parser_rejects_objects_it_does_not_place(name):
    with pytest.raises(UserError) as exc:
        Arrangement.from_mapping({**_mapping(), name: {"zone": "HWS", "state": "closed"}})
    assert exc.value.key == f"objects.{name}"


def test_every_arrangement_is_each_objects_zone_and_state():
    arrs = all_arrangements()
    assert len(arrs) == math.prod(len(layout.ZONES) * len(catalogue.STATES[o]) for o in catalogue.TASK_OBJECTS)
    assert len(set(arrs)) == len(arrs)
    assert Arrangement(*arrs[0].placements) == arrs[0]
    assert Arrangement(**{o: arrs[0].placement(o) for o in catalogue.TASK_OBJECTS}) == arrs[0]
    with pytest.raises(TypeError):
        Arrangement(arrs[0].placements[0])
    with pytest.raises(TypeError):
        Arrangement(*arrs[0].placements, stopper=Placement("HWS", "closed"))


def test_the_sweeps_object_paths_are_the_catalogues():
    objects = {p.split(".")[1] for p in OBJECT_PATHS}
    assert objects == set(catalogue.TASK_OBJECTS)
    for name in catalogue.TASK_OBJECTS:
        for key in ("zone", "state", "position"):
            check_path(f"objects.{name}.{key}", "sweep")
    for name in [o for o in catalogue.NAMES if o not in catalogue.TASK_OBJECTS]:
        with pytest.raises(UserError):
            check_path(f"objects.{name}.zone", "sweep")
