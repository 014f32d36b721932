"""The human arm: minimum-jerk reaches with IK land on their targets; the middle-line limit holds."""

import numpy as np
import pytest

from assistbot.human.arm import HANDOVER_X_MAX, MAX_JOINT_SPEED, ORIENT, HumanArm, grip_orientation, min_jerk
from assistbot.world import PAPER_ARRANGEMENTS, build_world


def _run(world, arm, t, seconds):
    for _ in range(int(round(seconds / arm.dt))):
        arm.tick(t)
        world.step(10)
        t += arm.dt
    return t


def test_min_jerk_profile():
    assert min_jerk(0.0) == 0.0 and min_jerk(1.0) == 1.0
    assert abs(min_jerk(0.5) - 0.5) < 1e-12
    s = np.linspace(0, 1, 101)
    v = np.diff([min_jerk(x) for x in s])
    assert np.all(v >= 0) and v[0] < 1e-3 and v[-1] < 1e-3  # starts and ends at rest


@pytest.mark.parametrize("target,grip", [((-0.22, -0.12, 0.92), "ag"), ((-0.25, 0.12, 0.82), "sg"), ((-0.10, -0.05, 0.95), "sg")])
def test_reach_lands_on_target_with_bounded_speed(target, grip):
    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
    arm = HumanArm(world, speed=0.2)
    R = grip_orientation(grip, target)
    dur = arm.move_to(target, R, t=0.0)
    qs = []
    t = 0.0
    for _ in range(int((dur + 0.6) / arm.dt)):
        arm.tick(t)
        qs.append(arm.q.copy())
        world.step(10)
        t += arm.dt
    Rgoal = R
    p, R = arm.hand_pose()
    assert np.linalg.norm(p - np.array(target)) < 0.02
    ang = np.arccos(np.clip((np.trace(R @ Rgoal.T) - 1) / 2, -1, 1))
    assert ang < 0.35
    assert np.max(np.abs(np.diff(qs, axis=0))) <= MAX_JOINT_SPEED * arm.dt + 1e-9


def test_middle_line_limit_clamps_and_logs():
    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
    arm = HumanArm(world, speed=0.3)
    arm.move_to((0.35, 0.0, 0.95), ORIENT["sg"], t=0.0)
    assert len(arm.clamped) == 1 and arm.clamped[0][1][0] == 0.35 and arm.clamped[0][2][0] <= HANDOVER_X_MAX
    hand_geoms = [g for g in range(world.model.ngeom) if world.model.body(world.model.geom_bodyid[g]).name.startswith("human_r_")]
    t, xmax = 0.0, -1.0
    for _ in range(150):
        arm.tick(t)
        world.step(10)
        t += arm.dt
        xmax = max(xmax, float(np.max(world.data.geom_xpos[hand_geoms, 0])), float(arm.hand_pose()[0][0]))
    assert xmax <= HANDOVER_X_MAX


def test_compiled_ik_step_agrees_with_the_numpy_reference():
    from assistbot.human.arm import _exp_rot
    from assistbot.human.dls import bounded, dls_step, dls_step_numpy

    rng = np.random.default_rng(0)
    lo, hi = -2 * np.ones(7), 2 * np.ones(7)
    for trial in range(100):
        R = _exp_rot(rng.normal(size=3))
        R_t = _exp_rot(rng.normal(size=3) * (3.0 if trial % 3 == 0 else 0.3)) @ R   # large and small errors
        args = (rng.normal(size=3), R_t, rng.normal(size=3), R, rng.normal(size=(3, 7)), rng.normal(size=(3, 7)),
                rng.normal(size=7), rng.normal(size=7), lo, hi)
        q = dls_step(*args)
        assert np.allclose(q, dls_step_numpy(*args), atol=1e-9)
        q_cmd = rng.uniform(-1.9, 1.9, size=7)          # a command within the joint limits
        out, big = bounded(q, q_cmd, lo, hi, 0.024)
        assert np.all(np.abs(out - q_cmd) <= 0.024 + 1e-12) and big == pytest.approx(np.abs(out - q_cmd).max())


def test_rehearsing_motions_predicts_the_reach_and_changes_nothing():
    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
    arm = HumanArm(world, speed=0.3)
    q0, ctrl0, goal0 = arm.q.copy(), world.data.ctrl.copy(), arm.p_goal.copy()
    near = ((-0.25, -0.10, 0.95), grip_orientation("ag", (-0.25, -0.10, 0.95)), None, 0.03)
    far = ((0.40, 0.40, 1.30), grip_orientation("ag", (0.40, 0.40, 1.30)), None, 0.03)
    assert arm.rehearse([near, near]) == 2
    assert arm.rehearse([near, far, near]) == 1
    assert np.array_equal(arm.q, q0) and np.array_equal(world.data.ctrl, ctrl0) and np.array_equal(arm.p_goal, goal0)
    assert arm.segment is None and not arm.clamped
    # what was rehearsed is what the arm then does
    t = 0.0
    arm.move_to(*near[:2], t=t)
    t = _run(world, arm, t, 3.0)
    assert np.linalg.norm(arm.fk(arm.q)[0] - np.array(near[0])) < 0.03
