"""A hand-over to a person whose hand holds something else stops before it carries the object into what they
hold: the robot sets the object down in its own workspace, and that object is then in the arm's way like
any other standing one (in the physics; perception is a stand-in)."""

from __future__ import annotations

import numpy as np

from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import body_xy, run
from assistbot.world import Arrangement, build_world


def _hand_over(hand_busy):
    w = build_world(Arrangement.from_options("RWS:open@0.22,-0.10", "RWS:empty@0.20,0.16"), seed=0)
    robot = RobotController(w.model, w.data)
    prim = P.HandOver(robot, "bottle", hand_busy=hand_busy, locate=lambda name: body_xy(w, name)())
    seen: dict[str, object] = {"min_x": np.inf}

    def watch(t):
        # the arm keeps clear of the object it set down once it has backed off it, as the executor has it
        robot.ik.set_obstacles({prim.set_down: body_xy(w, prim.set_down)()} if prim.set_down else {})
        seen["min_x"] = min(seen["min_x"], float(robot.tcp_pose().translation()[0]))
        if prim.progress.phase == "release" and "set down at release" not in seen:
            seen["set down at release"] = prim.set_down
        if prim.progress.phase == P.OFFER_PHASE and "offered" not in seen:
            seen["offered"] = w.time

    pr, _ = run(w, prim, body_xy(w, "bottle"), seconds=45.0, each_tick=watch)
    return w, prim, pr, seen


def test_a_hand_over_to_a_hand_that_is_not_free_ends_with_the_object_set_down_in_the_rws():
    w, prim, pr, seen = _hand_over(lambda: True)
    assert pr.status is P.Status.FAILED and "the person's hand is not free" in pr.reason, pr.reason
    assert "offered" not in seen and seen["min_x"] > 0.0      # never held out, never over the person's side
    st = w.state()
    assert st.robot_holds is None and st.objects["bottle"].zone == "RWS" and st.objects["bottle"].upright, st.summary()
    # once the hand has backed off it, the bottle set down is an obstacle for the rest of the withdrawal
    assert seen["set down at release"] is None and prim.set_down == "bottle"


def test_a_hand_over_to_a_free_hand_is_held_out():
    w, prim, pr, seen = _hand_over(lambda: False)
    assert "offered" in seen and seen["min_x"] < 0.1
