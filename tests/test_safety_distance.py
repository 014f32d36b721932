"""The safety measure (`DrinkingTask.min_distance_human`): the closest the robot comes to the person's head and
torso, the parts the robot must keep 5 cm from. The working arm meets the robot's hand in every hand-over and
the resting left hand lies on the table at the hand-over zone's edge: those, the legs and the chair are left to
the touch monitor (any overlap with any part of the person)."""

from __future__ import annotations

import math

import mujoco

from assistbot.episode.drinking_task import DrinkingTask
from assistbot.world import Arrangement, build_world


def test_the_measure_is_to_the_head_and_torso_and_exact():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=1)
    task = DrinkingTask(w, 360.0)
    m, d = w.model, w.data
    robot, person = task._distance_pairs
    names = {m.geom(int(g)).name for g in person}
    assert {"human_head", "human_torso", "human_torso_neck", "human_torso_shoulders"} <= names
    assert all(n.startswith(("human_head", "human_torso")) for n in names), names
    human = [g for g in range(m.ngeom) if m.body(int(m.geom_bodyid[g])).name.startswith("human")]
    left_behind = {g for g in human if g not in set(person.tolist())}
    assert any(m.geom(g).name == "human_chair_seat" for g in left_behind)
    assert all(m.body(int(m.geom_bodyid[g])).name.startswith("robot") for g in robot)
    brute = min(mujoco.mj_geomDistance(m, d, int(a), int(b), 2.0, None) for a, b in zip(robot, person))
    assert math.isclose(task._distance_to_trunk(), brute, abs_tol=1e-9)
