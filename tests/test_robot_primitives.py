"""Robot primitives in the physics (no cognition): the effect happens, safely, from two placements."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.robot.controller import HANDOVER_DEPTH, RobotController
from assistbot.robot.primitives import ReachAndGrasp, Request, Retract, Status, TurnGlass
from assistbot.robot.sim import CONTROL_DT, Bench, Placement


def run(bench: Bench, prim, target=lambda b: None, seconds: float = 25.0):
    worst = {"human": 1e9, "min_x": 1e9, "limits": True}
    prim.start(target(bench))
    for _ in range(int(seconds / CONTROL_DT)):
        pr = prim.tick(CONTROL_DT, target(bench))
        bench.step()
        worst["human"] = min(worst["human"], bench.min_human_distance())
        worst["min_x"] = min(worst["min_x"], bench.robot_min_x())
        worst["limits"] &= bench.arm_within_limits()
        if pr.status is not Status.RUNNING:
            break
    return pr, worst


def assert_safe(worst):
    assert worst["human"] >= 0.05
    assert worst["min_x"] >= -HANDOVER_DEPTH
    assert worst["limits"]


@pytest.mark.parametrize("xy", [(0.15, 0.10), (0.22, -0.15)])
def test_turn_glass_ends_upright_in_rws(xy):
    bench = Bench(Placement(glass=xy, bottle=(0.25, 0.32), glass_inverted=True))
    robot = RobotController(bench.model, bench.data)
    pr, worst = run(bench, TurnGlass(robot), lambda b: tuple(b.body_pos("glass")[:2]))
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert bench.body_up("glass")[2] > 0.98
    assert bench.body_pos("glass")[0] > 0.04
    assert bench.body_pos("glass")[2] < 0.76
    assert_safe(worst)


def test_unreachable_target_fails_with_reason_in_bounded_time():
    bench = Bench(Placement(glass=(0.20, -0.12)))
    robot = RobotController(bench.model, bench.data)
    pr, worst = run(bench, ReachAndGrasp(robot, "glass"), lambda b: (-0.35, -0.50), seconds=15.0)
    assert pr.status is Status.FAILED
    assert "reach" in pr.reason
    assert pr.t < 10.0
    assert_safe(worst)


def test_request_holds_open_hand_near_middle_line():
    bench = Bench(Placement(glass=(0.20, -0.12)))
    robot = RobotController(bench.model, bench.data)
    pr, worst = run(bench, Request(robot, "glass"), lambda b: (-0.22, 0.12), seconds=10.0)
    assert pr.status is Status.SUCCEEDED, pr.reason
    palm = bench.data.site_xpos[bench.model.site("robot_palm_face").id]
    assert abs(palm[0]) < 0.15
    assert robot.gripper.finger_angles().max() < 0.2  # open
    assert_safe(worst)


def test_retract_from_home():
    bench = Bench()
    robot = RobotController(bench.model, bench.data)
    pr, worst = run(bench, Retract(robot), seconds=8.0)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert_safe(worst)
