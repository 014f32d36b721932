"""Holding an object out until the person takes it (`WaitForTake`), phase by phase with a stand-in robot whose
wrist reads what the test sets: a grip that closes while the robot brings the object nearer a hand that stopped
short is felt as the take it is."""

from __future__ import annotations

import mink
import numpy as np

from assistbot.interfaces import Status
from assistbot.robot.phases.wait_for_take import WaitForTake

DT = 0.02
WEIGHT = np.array([0.0, 0.0, -14.0])     # N: the hand and the full glass, held still
TAKEN = np.array([0.0, 0.0, 5.0])        # N: the part of that weight a closed grip takes up


class _Gripper:
    def __init__(self) -> None:
        self.force = WEIGHT.copy()

    def wrist_force_world(self) -> np.ndarray:
        return self.force.copy()


class _Robot:
    def __init__(self) -> None:
        self.gripper = _Gripper()
        self.pose = mink.SE3.identity()

    def hold(self) -> None:
        pass

    def commanded_tcp_pose(self) -> mink.SE3:
        return self.pose

    def move_toward(self, pose: mink.SE3, dt: float) -> None:
        self.pose = pose


class _Prim:
    """A person whose hand stopped short of the glass at HAND and keeps still there."""

    HAND = (-0.08, -0.05, 0.15)

    def __init__(self) -> None:
        self.robot = _Robot()

    def reaching_hand(self):
        return self.HAND


def _hold_out(grip_closes_in_the_bring: bool) -> tuple[Status, float, int]:
    wait = WaitForTake("wait for the human to take it", 20.0, "the human did not take it",
                       meet=lambda prim, hand: mink.SE3.from_translation(np.array([-0.03, 0.0, 0.0])))
    prim = _Prim()
    wait.start(prim)
    t, status = 0.0, Status.RUNNING
    while status is Status.RUNNING:
        if grip_closes_in_the_bring and wait._bringing is not None:
            prim.robot.gripper.force = WEIGHT + TAKEN      # her hand, right at the glass, closes on it as it comes
        status, _ = wait.tick(prim, DT, t)
        t += DT
    return status, t, wait._meets


def test_a_grip_that_closes_while_the_object_is_brought_nearer_is_felt():
    status, t, meets = _hold_out(grip_closes_in_the_bring=True)
    assert meets == 1
    assert status is Status.SUCCEEDED and t < WaitForTake.MEET_STILL + WaitForTake.MEET_SECONDS + 1.0, (status, t)


def test_brought_nearer_and_not_taken_it_is_not_let_go():
    status, t, meets = _hold_out(grip_closes_in_the_bring=False)
    assert meets == 1 and status is Status.FAILED, (status, t, meets)
