"""Physical facts of the scene, shown with scripted joint targets (no cognition).

The robot's grasps are friction only: the gripper's servos squeeze and the contacts hold.
"""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.catalogue import grasp_height
from assistbot.world import ROBOT_ARM_JOINTS, Arrangement, build_world
from assistbot.world.scripted import ik, ramp

I3 = np.eye(3)
FINGERS = ("robot_finger1", "robot_finger2", "robot_finger3")


def _robot_grasp(w, obj: str) -> dict[str, float]:
    """Drive the arm around `obj` (horizontal approach from the robot's side) and close the fingers."""
    c = w.data.xpos[w.body_id[obj]].copy() + [0, 0, grasp_height(obj)]
    zero = {j: 0.0 for j in ROBOT_ARM_JOINTS}
    back = ik(w, "robot_tcp", c + [0.22, 0, 0.05], I3, ROBOT_ARM_JOINTS, q_start=zero)
    pre = ik(w, "robot_tcp", c + [0.17, 0, 0], I3, ROBOT_ARM_JOINTS, q_start=back)
    at = ik(w, "robot_tcp", c, I3, ROBOT_ARM_JOINTS, q_start=pre)
    w.set_gripper(-0.3)
    ramp(w, back, 0.8)
    ramp(w, pre, 1.0, 0.2)
    ramp(w, at, 1.5, 0.3)
    ramp(w, {f: 1.6 for f in FINGERS}, 0.5, 0.5)
    assert w.robot_holding() == obj
    return at


def _in_tcp(w, obj: str) -> np.ndarray:
    t = w.data.site("robot_tcp")
    return t.xmat.reshape(3, 3).T @ (w.data.xpos[w.body_id[obj]] - t.xpos)


@pytest.mark.parametrize("obj, arrangement", [
    ("bottle", ("RWS:closed@0.12,0.05", "HWS:empty")),
    ("glass", ("HWS:closed", "RWS:empty@0.12,0.05")),
])
def test_robot_holds_by_friction_through_lift_and_pour_tilt(obj, arrangement):
    w = build_world(Arrangement.from_options(*arrangement))
    m = w.model
    welds = [i for i in range(m.neq) if m.eq_type[i] in (0, 1)]  # connect, weld: none touches the robot
    assert not any(m.body(int(m.eq_obj1id[i])).name.startswith("robot") or m.body(int(m.eq_obj2id[i])).name.startswith("robot")
                   for i in welds)
    start = w.data.xpos[w.body_id[obj]].copy()
    at = _robot_grasp(w, obj)
    r0 = _in_tcp(w, obj)
    c = start + [0, 0, grasp_height(obj)]
    up = ik(w, "robot_tcp", c + [0, 0, 0.20], I3, ROBOT_ARM_JOINTS, q_start=at)
    t0 = w.time
    ramp(w, up, 1.5, 0.3)
    assert w.data.xpos[w.body_id[obj]][2] - start[2] > 0.19          # lifted 20 cm
    tilt = dict(up, robot_j7=up["robot_j7"] + np.radians(100))
    ramp(w, tilt, 1.5)
    ramp(w, tilt, 0.0, hold=5.0 - (w.time - t0))
    assert w.time - t0 >= 4.99
    z_axis = w.data.xmat[w.body_id[obj]].reshape(3, 3)[:, 2]
    assert np.degrees(np.arccos(z_axis[2])) == pytest.approx(100, abs=5)  # really tilted
    assert np.linalg.norm(_in_tcp(w, obj) - r0) < 0.01                # slip < 1 cm
    assert w.robot_holding() == obj
    s = w.state()
    if obj == "bottle":  # the closed bottle tilted past horizontal loses no liquid
        assert s.liquid.in_bottle == s.liquid.total
    assert w.warnings() == {}


def test_pour_from_open_bottle_fills_the_glass():
    w = build_world(Arrangement.from_options("RWS:open@0.12,0.12", "RWS:empty@0.12,-0.06"))
    at = _robot_grasp(w, "bottle")
    c = w.data.xpos[w.body_id["bottle"]].copy() + [0, 0, grasp_height("bottle")]
    lift = ik(w, "robot_tcp", c + [0, 0, 0.13], I3, ROBOT_ARM_JOINTS, q_start=at)
    ramp(w, lift, 1.0, 0.2)
    over = ik(w, "robot_tcp", (0.12, 0.05, c[2] + 0.13), I3, ROBOT_ARM_JOINTS, q_start=lift)
    ramp(w, over, 1.0, 0.2)
    pour = dict(over, robot_j7=over["robot_j7"] + np.radians(140))
    ramp(w, pour, 1.5, hold=2.5)
    s = w.state()
    assert s.liquid.in_glass >= 0.9 * s.liquid.total, s.summary()
    assert s.glass_state == "full"


def test_full_glass_carried_level_spills_little_and_inverted_holds_none():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:full@0.12,0.05"))
    at = _robot_grasp(w, "glass")
    c = w.data.xpos[w.body_id["glass"]].copy() + [0, 0, grasp_height("glass")]
    up = ik(w, "robot_tcp", c + [0, 0, 0.15], I3, ROBOT_ARM_JOINTS, q_start=at)
    ramp(w, up, 1.2, 0.2)
    across = ik(w, "robot_tcp", c + [0.0, -0.15, 0.15], I3, ROBOT_ARM_JOINTS, q_start=up)
    ramp(w, across, 1.2, 0.2)
    back = ik(w, "robot_tcp", c + [0.05, 0.0, 0.08], I3, ROBOT_ARM_JOINTS, q_start=across)
    ramp(w, back, 1.2, 0.5)
    s = w.state()
    assert s.liquid.spilled < 0.1 * s.liquid.total, s.summary()
    assert s.glass_state == "full"
    # turn it upside down: nothing stays in it
    inv = dict(back, robot_j7=back["robot_j7"] + np.radians(165))
    ramp(w, inv, 1.5, hold=2.0)
    s = w.state()
    assert s.objects["glass"].inverted and s.glass_state == "inverted"
    assert s.liquid.in_glass == 0, s.summary()


def test_a_full_glass_shaken_as_by_a_tremor_keeps_its_liquid():
    """Lifted and shaken up and down by 1.8 cm at 7.8 Hz (a partner's tremor as the hand made it, 2.3 g):
    the particles bounce but stay in the glass.  With a contact as soft as MuJoCo's default (solref 0.02)
    they sank through the 8 mm base and the glass was empty in 0.1 s."""
    w = build_world(Arrangement.from_options("RWS:open", "RWS:full"))
    m, d = w.model, w.data
    w.step(250)
    j = m.joint("glass_free")
    qa, va = j.qposadr[0], j.dofadr[0]
    p0 = d.qpos[qa:qa + 3].copy()
    amp, w_, t0 = 0.018, 2 * np.pi * 7.8, d.time
    while d.time - t0 < 5.0:      # the glass moved as a hand would move it: lifted 10 cm in 1 s, then shaken
        t = d.time - t0
        rise, on = min(1.0, t), min(1.0, max(0.0, t - 1.0) / 0.5)
        d.qpos[qa:qa + 7] = [p0[0], p0[1], p0[2] + 0.10 * rise + on * amp * np.sin(w_ * t), 1, 0, 0, 0]
        d.qvel[va:va + 6] = [0, 0, (0.10 if t < 1.0 else 0.0) + on * amp * w_ * np.cos(w_ * t), 0, 0, 0]
        w.step(1)
    s = w.state()
    assert s.liquid.in_glass >= 0.95 * s.liquid.total and s.glass_state == "full", s.summary()
