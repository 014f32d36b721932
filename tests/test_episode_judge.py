"""The failure kinds an episode ends with, and the touch measure: each from the world's own physics."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from assistbot.episode.judge import FALLEN_SECONDS, NOTICE_SECONDS, REPEAT_DECISIONS, REPEAT_FAILURES, STALL_SECONDS, Judge
from assistbot.episode.touch import TouchMonitor
from assistbot.world import Arrangement, build_world


def world(bottle="RWS:open", glass="RWS:empty"):
    return build_world(Arrangement.from_options(bottle, glass), seed=0)


def run(w, judge, seconds, each=None):
    reason = None
    for _ in range(int(round(seconds / 0.02))):
        if each is not None:
            each()
        w.step(10)
        reason = judge.verdict(w.time)
        if reason is not None:
            break
    return reason


def test_nothing_decided_and_nothing_moving_for_30_s_is_a_stall():
    w = world()
    j = Judge(w, time_limit=100.0)
    assert run(w, j, STALL_SECONDS - 1.0) is None
    j.decided(w.time, "Wait")            # a decision restarts the clock
    assert run(w, j, STALL_SECONDS - 1.0) is None
    assert run(w, j, 2.0) == "stalled"
    assert j.end_reason() == "stalled"


def test_a_moving_arm_is_not_a_stall():
    w = world()
    j = Judge(w, time_limit=100.0)
    act = w.actuator("robot_j1")
    wave = lambda: w.data.ctrl.__setitem__(act, 0.1 + 0.3 * math.sin(w.time))  # noqa: E731
    assert run(w, j, STALL_SECONDS + 5.0, each=wave) is None


def test_the_same_action_failing_three_times_or_decided_five_times_in_a_row_is_repeating():
    w = world()
    j = Judge(w, time_limit=100.0)
    for k in range(REPEAT_FAILURES - 1):
        j.action_ended(float(k), "Receive-object", "failed", "grasp: the hand closed on nothing")
        j.action_ended(float(k), "Request-glass", "succeeded")
    assert j.verdict(5.0) is None
    j.action_ended(6.0, "Receive-object", "failed", "grasp: the hand closed on nothing")
    assert j.verdict(6.0) == "repeating" and j.detail["action"] == "Receive-object"
    j2 = Judge(w, time_limit=100.0)
    for k in range(REPEAT_DECISIONS - 1):
        j2.decided(float(k), "Wait")
    j2.decided(9.0, "Request-glass")     # another decision breaks the run
    for k in range(REPEAT_DECISIONS - 1):
        j2.decided(10.0 + k, "Wait")
    assert j2.verdict(15.0) is None
    j2.decided(20.0, "Wait")
    assert j2.verdict(20.0) == "repeating"


def test_a_bottle_tipped_over_ends_the_episode_naming_it_and_the_glass_standing_beside_it_does_not():
    w = world("RWS:closed@0.15,0.15", "RWS:empty@0.2,-0.15")
    j = Judge(w, time_limit=100.0)
    b = w.body_id["bottle"]
    # a twist about the table's x axis for a moment: the bottle tips over and lies on the table
    tip = lambda: w.data.xfrc_applied.__setitem__((b, 3), 0.25 if w.time < 0.25 else 0.0)  # noqa: E731
    # the episode runs on for the robot to see the fall and say so ...
    assert run(w, j, 4.0, each=tip) is None
    assert abs(w.data.xmat[b][8]) < 0.5          # it does lie on its side
    assert j.fallen() == ["bottle"]
    j.said(w.time, "error:glass_fell")           # (what fell is not the glass)
    assert j.verdict(w.time) is None
    j.said(w.time, "error:bottle_fell")
    assert j.verdict(w.time) == "object fell"
    assert j.end_reason() == "object fell: bottle" and j.detail == {"object": "bottle", "robot_said": True}


def test_a_fall_the_robot_does_not_say_ends_the_episode_after_its_notice_time():
    w = world("RWS:closed@0.15,0.15", "RWS:empty@0.2,-0.15")
    j = Judge(w, time_limit=100.0)
    b = w.body_id["bottle"]
    tip = lambda: w.data.xfrc_applied.__setitem__((b, 3), 0.25 if w.time < 0.25 else 0.0)  # noqa: E731
    assert run(w, j, 1.0 + FALLEN_SECONDS + NOTICE_SECONDS, each=tip) == "object fell"
    assert j.detail == {"object": "bottle", "robot_said": False}


def test_an_inverted_glass_is_standing_not_fallen():
    w = world("RWS:closed", "RWS:inverted")
    j = Judge(w, time_limit=100.0)
    assert run(w, j, 2.0) is None
    assert j.fallen() == []


def test_nan_in_the_physics_is_diverged_and_the_time_limit_ends_the_rest():
    w = world()
    j = Judge(w, time_limit=1.0)
    assert run(w, j, 2.0) == "time limit"
    w2 = world()
    j2 = Judge(w2, time_limit=10.0)
    w2.data.qpos[0] = np.nan
    assert j2.verdict(0.0) == "diverged"


# ----------------------------------------------------------------------------------- touching the person
def _two_bodies(gap: float):
    """A robot capsule and a human box, `gap` m apart (negative: overlapping); neither collides."""
    spec = mujoco.MjSpec()
    r = spec.worldbody.add_body(name="robot_finger", pos=[0, 0, 1])
    r.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[0.01, 0.03, 0], contype=0, conaffinity=0)
    h = spec.worldbody.add_body(name="human_hand", pos=[0.01 + 0.02 + gap, 0, 1])
    h.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.02, 0.04, 0.05], contype=0, conaffinity=0)
    m = spec.compile()
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    return m, d


@pytest.mark.parametrize("gap", [0.005, -0.004, -0.015])
def test_touch_is_the_deepest_overlap_of_robot_and_human_geoms_whether_or_not_they_collide(gap):
    m, d = _two_bodies(gap)
    t = TouchMonitor(m, d)
    t.update(0.0, 0.02)
    w = t.worst
    assert w.depth == pytest.approx(max(0.0, -gap), abs=1e-6)
    assert (w.depth > 0) == (gap < 0)
    if gap < 0:
        assert w.robot_geom.startswith("robot_finger") and w.human_geom.startswith("human_hand")
        assert w.seconds == (0.02 if -gap > t.DEEP else 0.0)
    assert w.force == 0.0          # the pair does not collide: no contact force
