"""The stopper comes off only while the robot holds the bottle; the human's grip needs hand at object + closed hand."""

from __future__ import annotations

import numpy as np

from assistbot.world import HUMAN_ARM_JOINTS, ROBOT_ARM_JOINTS, STOPPER_RELEASE_FORCE, Arrangement, build_world
from assistbot.world.scripted import ik, ramp

I3 = np.eye(3)
HUMAN_START = dict({j: 0.0 for j in HUMAN_ARM_JOINTS}, human_r_shoulder_flex=1.0, human_r_elbow=0.8)


def _robot_holds_bottle_at_the_line(w):
    c = w.data.xpos[w.body_id["bottle"]].copy() + [0, 0, 0.08]
    back = ik(w, "robot_tcp", c + [0.22, 0, 0.05], I3, ROBOT_ARM_JOINTS, q_start={j: 0.0 for j in ROBOT_ARM_JOINTS})
    pre = ik(w, "robot_tcp", c + [0.17, 0, 0], I3, ROBOT_ARM_JOINTS, q_start=back)
    at = ik(w, "robot_tcp", c, I3, ROBOT_ARM_JOINTS, q_start=pre)
    w.set_gripper(-0.3)
    ramp(w, back, 0.8)
    ramp(w, pre, 1.0, 0.2)
    ramp(w, at, 1.5, 0.3)
    ramp(w, {f: 1.6 for f in ("robot_finger1", "robot_finger2", "robot_finger3")}, 0.5, 0.5)
    out = ik(w, "robot_tcp", c + [-0.10, 0, 0.02], I3, ROBOT_ARM_JOINTS, q_start=at)  # hold it out at the middle line
    ramp(w, out, 1.5, 0.3)
    assert w.robot_holding() == "bottle"


def _human_takes_stopper_and_pulls(w):
    """Reach the stopper with an open hand, close it (above grip), grip, pull 15 cm up. Returns the peak pull force."""
    st = w.site_pos("stopper_grasp")
    w.set_hand_posture("open")
    above = ik(w, "human_r_grasp", st + [0, 0, 0.06], None, HUMAN_ARM_JOINTS, q_start=HUMAN_START)
    on = ik(w, "human_r_grasp", st, None, HUMAN_ARM_JOINTS, q_start=above)
    ramp(w, above, 1.5, 0.2)
    ramp(w, on, 0.8, 0.2)
    assert not w.human_grasp("stopper")          # open hand: no grip
    w.set_hand_posture("ag")
    w.step(250)
    assert w.human_grasp("stopper")              # closed hand at the stopper: grip
    pull = ik(w, "human_r_grasp", st + [0, 0, 0.15], None, HUMAN_ARM_JOINTS, q_start=on)
    peak = [0.0]
    ramp(w, pull, 1.0, 0.5, each_step=lambda: peak.__setitem__(0, max(peak[0], w.stopper_pull_force())))
    return peak[0]


def test_pull_lifts_a_free_standing_bottle_with_its_stopper():
    w = build_world(Arrangement.from_options("HWS:closed@-0.12,-0.12", "RWS:empty"))
    z0 = w.data.xpos[w.body_id["bottle"]][2]
    peak = _human_takes_stopper_and_pulls(w)
    s = w.state()
    assert s.bottle_state == "closed" and s.human_holds == "stopper"
    assert w.data.xpos[w.body_id["bottle"]][2] - z0 > 0.10     # the bottle came up with the stopper
    assert peak < STOPPER_RELEASE_FORCE


def test_same_pull_removes_the_stopper_while_the_robot_holds_the_bottle():
    w = build_world(Arrangement.from_options("RWS:closed@0.10,-0.10", "HWS:empty"))
    _robot_holds_bottle_at_the_line(w)
    z0 = w.data.xpos[w.body_id["bottle"]][2]
    peak = _human_takes_stopper_and_pulls(w)
    s = w.state()
    assert peak >= STOPPER_RELEASE_FORCE
    assert s.bottle_state == "open" and s.bottle_open and s.human_holds == "stopper" and s.robot_holds == "bottle"
    assert abs(w.data.xpos[w.body_id["bottle"]][2] - z0) < 0.01
    assert w.data.xpos[w.body_id["stopper"]][2] - w.site_pos("bottle_mouth")[2] > 0.08


def test_human_grip_needs_the_hand_at_the_object_and_closed():
    w = build_world(Arrangement.from_options("HWS:closed@-0.15,0.05", "HWS:empty@-0.25,0.32"))
    w.set_hand_posture("sg")
    w.step(250)
    assert w.hand_closed()
    for obj in ("bottle", "glass", "stopper"):   # closed hand, far away: nothing
        assert w.grasp_distance(obj) > 0.05
        assert not w.human_grasp(obj)
    # reach the bottle's side with an open hand, then close: grip; opening the hand lets go
    g = w.site_pos("stopper_grasp") - [0, 0, 0.12]
    w.set_hand_posture("open")
    q = ik(w, "human_r_grasp", g + [-0.045, 0, 0], None, HUMAN_ARM_JOINTS, q_start=HUMAN_START)
    ramp(w, q, 1.5, 0.3)
    assert w.grasp_distance("bottle") < 0.03
    w.set_hand_posture("sg")
    w.step(250)
    assert w.human_grasp("bottle") and w.state().human_holds == "bottle"
    w.set_hand_posture("open")
    w.step(100)
    assert w.human_holding() is None
