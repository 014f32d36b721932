"""The executor's reach targets come from the Percept: what the person holds out is a target,
what they hold for themselves is not followed toward them."""

from __future__ import annotations

import pytest

from assistbot.cognition.percept import HandPercept, ObjectPercept, Percept
from assistbot.episode.executor import RobotExecutor
from assistbot.world import PAPER_ARRANGEMENTS, build_world


@pytest.fixture(scope="module")
def executor():
    return RobotExecutor(build_world(PAPER_ARRANGEMENTS["fig3"], 0))


def _percept(hand: HandPercept) -> Percept:
    return Percept(t=1.0, objects={"glass": ObjectPercept("glass", "HWS", "full", (-0.12, -0.03, 0.18)),
                                   "bottle": ObjectPercept("bottle", "RWS", "open", (0.2, 0.1, 0.0))}, hand=hand)


def test_an_object_the_person_drinks_from_is_not_a_target(executor):
    executor.see(_percept(HandPercept("drink", (-0.15, -0.03, 0.3), object_in_hand="glass", held_out=False)))
    assert executor._target_xy("glass") is None
    assert executor._target_xy("bottle") == (0.2, 0.1)


def test_an_object_held_out_to_the_robot_is_a_target(executor):
    executor.see(_percept(HandPercept("grasp_ag", (-0.1, -0.03, 0.2), object_in_hand="glass", held_out=True)))
    assert executor._target_xy("glass") == (-0.12, -0.03)
    assert executor._target_xy("held_out") == (-0.12, -0.03)


def test_a_standing_object_is_a_target(executor):
    executor.see(_percept(HandPercept("none", seen=True)))
    assert executor._target_xy("glass") == (-0.12, -0.03)
