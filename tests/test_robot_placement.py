"""Where the robot puts things down: clear of the corridor to the hand-over place and of what stands there."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.robot.controller import REACH
from assistbot.robot.ik import ArmIK
from assistbot.robot.placement import CORRIDOR_CLEAR, OBJECT_CLEAR, REACH_MARGIN, put_down_spot, segment_distance
from assistbot.robot.primitives import GRASP_HEIGHT, HOLD_OUT_XY
from assistbot.robot.primitives.places import TO_REST
from assistbot.world.layout import TABLE_Z

SHOULDER = ArmIK().shoulder


@pytest.mark.parametrize("standing", [[], [(0.20, -0.12)], [(0.20, 0.12)], [(0.26, -0.06)], [(0.16, 0.24), (0.20, -0.12)]])
@pytest.mark.parametrize("obj", ["bottle", "glass"])
def test_the_spot_keeps_clear_of_the_corridor_and_the_objects_and_is_within_reach(standing, obj):
    spot = put_down_spot(SHOULDER, REACH, HOLD_OUT_XY, standing, GRASP_HEIGHT[obj])
    assert spot[0] > 0.1                       # in the robot's half, back from the middle line
    corridor = float(segment_distance(spot[None], SHOULDER[:2], np.array(HOLD_OUT_XY))[0])
    assert corridor >= CORRIDOR_CLEAR - 1e-9
    for o in standing:
        assert np.hypot(*(spot - o)) >= OBJECT_CLEAR - 1e-9
    grasp = np.array([spot[0], spot[1], TABLE_Z + GRASP_HEIGHT[obj]])
    assert np.linalg.norm(grasp - SHOULDER) <= REACH - REACH_MARGIN


def test_the_middle_of_the_workspace_on_the_corridor_is_never_chosen():
    # (0.20, 0.0), where the robot used to put things down, lies on the way to every hand-over
    assert float(segment_distance(np.array([[0.20, 0.0]]), SHOULDER[:2], np.array(HOLD_OUT_XY))[0]) < CORRIDOR_CLEAR
    spot = put_down_spot(SHOULDER, REACH, HOLD_OUT_XY, [], GRASP_HEIGHT["bottle"])
    assert np.hypot(*(spot - (0.20, 0.0))) > 0.05


@pytest.mark.parametrize("standing", [[], [(0.20, 0.12)], [(-0.2, 0.1)]])
def test_the_spot_keeps_clear_of_the_way_down_to_rest(standing):
    # the hand goes down from the ready pose to rest after every action, its open fingers pointing at the
    # table: a bottle set down 11 cm from the ready pose had its neck swept (partner 1070)
    plain = put_down_spot(SHOULDER, REACH, HOLD_OUT_XY, standing, GRASP_HEIGHT["bottle"])
    assert float(segment_distance(plain[None], *TO_REST)[0]) < CORRIDOR_CLEAR
    spot = put_down_spot(SHOULDER, REACH, HOLD_OUT_XY, standing, GRASP_HEIGHT["bottle"], ways=(TO_REST,))
    assert float(segment_distance(spot[None], *TO_REST)[0]) >= CORRIDOR_CLEAR - 1e-9
    assert float(segment_distance(spot[None], SHOULDER[:2], np.array(HOLD_OUT_XY))[0]) >= CORRIDOR_CLEAR - 1e-9
