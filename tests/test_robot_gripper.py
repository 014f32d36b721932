"""The hand's skin: a grasp is felt on an object, not on the hand itself."""

from __future__ import annotations

from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.gripper import EMPTY_CLOSED
from assistbot.robot.primitives import Status
from assistbot.robot.sim import body_xy, run
from assistbot.world import Arrangement, build_world


def test_a_hand_closed_on_nothing_feels_itself_but_holds_nothing():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=0)
    r = RobotController(w.model, w.data)
    r.gripper.close()
    for _ in range(75):
        r.hold()
        w.step(10)
    g = r.gripper
    assert min(g.finger_angles()) > EMPTY_CLOSED        # every finger curled onto the palm...
    assert g.pressure()["palm"] > 1.0                    # ... where the skin feels the fingertips
    assert g.fully_closed() and not g.grasps()


def test_a_hand_closed_on_the_glass_grasps_it():
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty@0.20,-0.12"), seed=0)
    r = RobotController(w.model, w.data)
    pr, _ = run(w, P.ReachAndGrasp(r, "glass"), body_xy(w, "glass"))
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert r.gripper.grasps() and not r.gripper.fully_closed()
    assert max(r.gripper.finger_angles()) < EMPTY_CLOSED
