"""mink IK on the reduced model: reaches poses, keeps off the human, reports failures."""

from __future__ import annotations

import mink
import numpy as np

from assistbot.robot.gaze import gaze_angles
from assistbot.robot.ik import READY_POSTURE, ArmIK
from assistbot.robot.ik_model import build_ik_model


def _run(ik, target, n=300):
    q = READY_POSTURE.copy()
    for _ in range(n):
        res = ik.solve(q, target, 0.02)
        q = res.q
    return q, res


def test_ik_reaches_a_side_grasp_pose():
    ik = ArmIK()
    target = mink.SE3.from_rotation_and_translation(mink.SO3.identity(), np.array([0.22, -0.05, 0.82]))
    q, res = _run(ik, target)
    assert res.ok and res.position_error < 0.005
    lo, hi = ik.model.jnt_range.T
    assert np.all(q >= lo - 1e-6) and np.all(q <= hi + 1e-6)


def test_collision_limit_keeps_arm_off_the_human_head():
    ik = ArmIK()
    model = ik.model
    head = model.geom("human_head").id
    target = mink.SE3.from_rotation_and_translation(mink.SO3.identity(), model.geom_xpos[head] if False else np.array([-0.68, 0.0, 1.25]))
    q, res = _run(ik, target, n=400)
    ik.configuration.update(q)
    import mujoco
    d = ik.configuration.data
    from assistbot.robot.ik_model import ARM_GEOMS
    dmin = min(mujoco.mj_geomDistance(model, d, model.geom(g).id, head, 1.0, None) for g in ARM_GEOMS)
    assert dmin >= 0.05


def test_ik_model_has_only_the_arm():
    assert build_ik_model().nq == 7


def test_gaze_points_down_at_the_table():
    pan, tilt = gaze_angles(np.array([0.65, 0, 1.46]), np.array([0.2, 0.0, 0.75]))
    assert abs(pan) < 1e-9 and 0.9 < tilt < 1.2
    pan, _ = gaze_angles(np.array([0.65, 0, 1.46]), np.array([0.65, -0.5, 0.75]))
    assert pan > 1.0  # a point on the robot's right (-y) turns the head toward -y


def test_ik_model_agrees_with_the_world():
    """The reduced IK model is the world's scene: same shoulder, same joint ranges, same TCP at a posture."""
    import mujoco

    from assistbot.robot.ik_model import ARM_JOINTS
    from assistbot.world import Arrangement, build_world

    w = build_world(Arrangement.from_options("HWS:closed", "RWS:inverted"))
    ik = ArmIK()
    m = w.model
    assert np.allclose(ik.shoulder, w.data.xpos[m.body("robot_link1").id])
    for k, j in enumerate(ARM_JOINTS):
        assert np.allclose(ik.model.jnt_range[k], m.jnt_range[m.joint(j).id])
        w.data.qpos[m.jnt_qposadr[m.joint(j).id]] = READY_POSTURE[k]
    mujoco.mj_forward(m, w.data)
    assert np.allclose(ik.tcp_pose(READY_POSTURE).translation(), w.data.site("robot_tcp").xpos, atol=1e-6)


def test_fast_qp_gives_minks_answer():
    """ArmIK's direct daqp path (limits as bounds) solves the same QP as mink.solve_ik."""
    from assistbot.robot.ik import IKParams

    fast, ref = ArmIK(IKParams(fast_qp=True)), ArmIK(IKParams(fast_qp=False))
    rng = np.random.default_rng(1)
    q = READY_POSTURE.copy()
    for _ in range(60):
        p = np.array([0.0, 0.0, 0.95]) + rng.uniform(-0.15, 0.15, 3)  # near the middle line: collision rows too
        target = mink.SE3.from_rotation_and_translation(mink.SO3.from_z_radians(rng.uniform(-0.5, 0.5)), p)
        a, b = fast.solve(q, target, 0.02), ref.solve(q, target, 0.02)
        assert a.ok and b.ok
        assert np.allclose(a.q, b.q, atol=1e-6)
        q = a.q
