"""Hand-overs wherever the person holds out: the corners of the region (±8 cm in x and y, ±6 cm in z around
the nominal point) and its centre, person to robot and robot to person, bottle and glass, in the physics.

Each run ends with one holder (the taker), the giver's hand empty, and the other object standing where it
stood. Perception is a stand-in from ground truth (as in test_robot_primitives): the target's place, the
held object's height, whether the person holds it, and where the person's open hand was seen."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from assistbot.human.behaviours import hold_out_point
from assistbot.human.controller import HumanController
from assistbot.human.profiles import HOLD_OUT_REGION, PROFILES
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import CONTROL_DT, body_lift, body_xy, run
from assistbot.world import Arrangement, build_world
from assistbot.world.layout import TABLE_Z

CORNERS = [tuple(s * r for s, r in zip(signs, HOLD_OUT_REGION)) for signs in itertools.product((-1, 1), repeat=3)]
OFFSETS = [(0.0, 0.0, 0.0)] + CORNERS
#: the object handed over, and where both stand (the other one away from the way to the hand-over)
SETUPS = {"bottle": ("HWS:closed", "RWS:empty@0.26,-0.16"), "glass": ("RWS:closed@0.18,0.24", "HWS:empty")}
FAST = [("glass", CORNERS[0]), ("bottle", CORNERS[-1])]


def _person(w, offset):
    dx, dy, dz = offset
    return HumanController(w, PROFILES["passive"].with_(hold_out_dx=dx, hold_out_dy=dy, hold_out_dz=dz))


def _other(obj):
    return "glass" if obj == "bottle" else "bottle"


def _pose(w, name):
    b = w.body_id[name]
    return w.data.xpos[b].copy(), float(w.data.xmat[b][8])


def _settle(w, human, seconds):
    for _ in range(int(seconds / CONTROL_DT)):
        human.tick(w.time)
        w.step(10)


def _nothing_else_moved(w, obj, before):
    pos, up = _pose(w, _other(obj))
    assert np.linalg.norm(pos - before) < 0.01 and up > 0.99, (pos, before, up)


def person_to_robot(obj, offset):
    w = build_world(Arrangement.from_options(*SETUPS[obj]), seed=0)
    robot = RobotController(w.model, w.data)
    human = _person(w, offset)
    other0 = _pose(w, _other(obj))[0]
    robot.ik.set_obstacles({_other(obj): tuple(other0[:2])})   # where the robot sees it standing
    human.start("hand_to_robot", object=obj, grip="ag")
    while not (w.human_holding() == obj and human.arm.arrived(w.time, 0.03)) and w.time < 12.0:
        _settle(w, human, CONTROL_DT)
    assert w.human_holding() == obj
    prim = P.Receive(robot, obj, human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, obj),
                     locate=lambda name: body_xy(w, name)())
    pr, s = run(w, prim, body_xy(w, obj), seconds=60.0, each_tick=human.tick)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    _settle(w, human, 1.0)
    st = w.state()
    assert st.human_holds is None and st.robot_holds is None, st.summary()
    assert st.objects[obj].zone == "RWS" and st.objects[obj].upright, st.summary()
    assert human.done[-1].name == "hand_to_robot" and human.done[-1].status == "succeeded", human.done[-1].reason
    assert s.human >= 0.05
    _nothing_else_moved(w, obj, other0)


def robot_to_person(obj, offset):
    setup = {"bottle": ("RWS:open", "HWS:empty@-0.22,0.12"), "glass": ("HWS:closed@-0.22,-0.12", "RWS:empty@0.24,-0.12")}[obj]
    w = build_world(Arrangement.from_options(*setup), seed=0)
    robot = RobotController(w.model, w.data)
    human = _person(w, offset)
    other0 = _pose(w, _other(obj))[0]
    # the person shows where they want it: the open hand held out at their own hold-out point
    human.start("request", hold=1.0)
    seen = {}
    while human.current is not None and w.time < 15.0:
        if human.arm.posture == "request":          # the last place the open hand was seen held out
            p = w.site_pos("human_r_grasp")
            seen["hand"] = (float(p[0]), float(p[1]), float(p[2] - TABLE_Z))
        _settle(w, human, CONTROL_DT)
    # it went toward the person's own point (where the arm allows: never across the middle line)
    assert np.linalg.norm((np.array(seen["hand"]) + [0, 0, TABLE_Z] - hold_out_point(human))[1:]) < 0.04
    human.start("take_from_robot", object=obj)
    prim = P.HandOver(robot, obj, human_holds=lambda: w.human_holding() == obj, locate=lambda name: body_xy(w, name)(),
                      partner_hand=lambda: seen["hand"])
    pr, s = run(w, prim, body_xy(w, obj), seconds=60.0, each_tick=human.tick)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    _settle(w, human, 3.0)
    st = w.state()
    # the taker holds it; an empty glass, which she cannot drink from, she then sets down on her side
    taken = [b for b in human.done if b.name == "take_from_robot"]
    assert taken and taken[-1].status == "succeeded", taken[-1].reason if taken else human.done
    assert st.robot_holds is None, st.summary()
    assert st.human_holds == obj or (obj == "glass" and st.human_holds is None and st.objects[obj].zone == "HWS"), st.summary()
    assert st.objects[obj].upright
    assert s.human >= 0.05
    _nothing_else_moved(w, obj, other0)


@pytest.mark.parametrize("obj, offset", FAST)
def test_a_person_to_robot_hand_over_at_a_corner_of_the_region(obj, offset):
    person_to_robot(obj, offset)


@pytest.mark.parametrize("obj, offset", FAST)
def test_a_robot_to_person_hand_over_at_a_corner_of_the_region(obj, offset):
    robot_to_person(obj, offset)


@pytest.mark.slow
@pytest.mark.parametrize("offset", OFFSETS)
@pytest.mark.parametrize("obj", ["bottle", "glass"])
def test_person_to_robot_over_the_region(obj, offset):
    person_to_robot(obj, offset)


@pytest.mark.slow
@pytest.mark.parametrize("offset", OFFSETS)
@pytest.mark.parametrize("obj", ["bottle", "glass"])
def test_robot_to_person_over_the_region(obj, offset):
    robot_to_person(obj, offset)
