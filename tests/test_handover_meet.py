"""An object held out farther than the person's hand goes: their reach stops short of it, the robot sees the
hand stop there and brings the object nearer, and the person takes it. Not seeing the hand, the robot cannot,
and the person does not take it. In the physics; perception is a stand-in that reports the person's grasp
site while their hand reaches for the glass, as vision reports a hand reaching for an object."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.human.controller import HumanController
from assistbot.human.population import Body, Partner
from assistbot.human.script import parse_human
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import body_xy, run
from assistbot.world import Arrangement, build_world
from assistbot.world.layout import TABLE_Z

#: a person seated back from the table with a narrowed range of motion: the glass held out where the default
#: person takes it lies beyond their reach
SHORT_REACH = Body(upper_arm=0.97, forearm=0.97, shoulder_height=1.0, seat_back=0.08, seat_side=-0.04, rom=0.25)


def _offer(see_hand: bool):
    w = build_world(Arrangement.from_options("HWS:closed@-0.22,-0.12", "RWS:empty@0.24,-0.12"), seed=0, body=SHORT_REACH)
    robot = RobotController(w.model, w.data)
    human = HumanController(w, config=parse_human({"profile": "passive", "partner": Partner(body=SHORT_REACH).to_dict()}))
    human.start("take_from_robot", object="glass")

    def reaching():
        b = human.current
        if not see_hand or b is None or b.name != "take_from_robot":
            return None
        p = w.site_pos("human_r_grasp")
        near = np.linalg.norm(p[:2] - np.asarray(body_xy(w, "glass")())) < 0.2
        return (float(p[0]), float(p[1]), float(p[2] - TABLE_Z)) if near else None

    prim = P.HandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass",
                      locate=lambda name: body_xy(w, name)(), reaching_hand=reaching)
    seen: dict[str, np.ndarray] = {}

    def watch(t):
        human.tick(t)
        if prim.progress.phase == P.OFFER_PHASE and prim._failure is None:   # the glass held out (not set down)
            seen.setdefault("first", robot.tcp_pose().translation().copy())
            seen["last"] = robot.tcp_pose().translation().copy()

    pr, _ = run(w, prim, body_xy(w, "glass"), seconds=60.0, each_tick=watch)
    return w, human, pr, seen


def _takes(human):
    return [b for b in human.done if b.name == "take_from_robot"]


def test_the_robot_brings_the_object_nearer_a_hand_that_stops_short_of_it():
    w, human, pr, seen = _offer(see_hand=True)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    takes = _takes(human)
    assert takes and takes[-1].status == "succeeded", takes[-1].reason if takes else human.done
    # brought nearer the person, and up toward where the hand stopped (beyond the reach it has lower down)
    moved = seen["last"] - seen["first"]
    assert moved[0] < -0.01 and np.linalg.norm(moved) > 0.03, seen
    st = w.state()
    assert st.robot_holds is None and st.objects["glass"].upright, st.summary()
    assert st.human_holds == "glass" or st.objects["glass"].zone == "HWS", st.summary()


@pytest.mark.slow
def test_not_seeing_the_hand_stop_the_robot_does_not_bring_it_and_the_person_cannot_take_it():
    w, human, pr, seen = _offer(see_hand=False)
    assert pr.status is P.Status.FAILED, pr.reason
    takes = _takes(human)
    assert takes and takes[0].status == "failed", human.done
    assert np.linalg.norm(seen["last"] - seen["first"]) < 0.01, seen
