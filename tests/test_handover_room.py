"""Each hand on the part of the glass the other leaves free, in the physics: the robot hands the person a full
glass it holds by its upper part (`offer_grasp_height`), she takes it below the robot's hand where her eyes
see room for her grip (`grip_beside_the_robots_hand`), and no robot geom goes more than 1 cm into hers on
the way (the touch measure of every episode summary). Perception is the ground truth here (`body_xy`)."""

from __future__ import annotations

import pytest

from assistbot.episode.touch import TouchMonitor
from assistbot.human.controller import HumanController
from assistbot.human.script import parse_human
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import body_xy, run
from assistbot.world import Arrangement, build_world


def _hand_over_full_glass():
    w = build_world(Arrangement.from_options("HWS:open@-0.22,-0.12", "RWS:full@0.24,-0.12"), seed=0)
    robot = RobotController(w.model, w.data)
    human = HumanController(w, config=parse_human({"profile": "passive"}))
    human.start("take_from_robot", object="glass")
    prim = P.HandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass",
                      locate=lambda name: body_xy(w, name)())
    touch = TouchMonitor(w.model, w.data)
    seen: dict = {}

    def watch(t):
        human.tick(t)
        touch.update(t, 0.0)
        base = w.data.xpos[w.body_id["glass"]][2]
        if prim.progress.phase == P.OFFER_PHASE and "offered" not in seen:
            seen["offered"] = float(robot.tcp_pose().translation()[2] - base)
        if w.human_holding() == "glass" and "taken_at" not in seen:
            # where her grip closed: her grasp site's height above the glass's base, and her palm's normal
            seen["taken_at"] = float(w.site_pos("human_r_grasp")[2] - base)
            seen["palm_normal"] = w.data.xmat[w.body_id["human_r_hand"]].reshape(3, 3)[:, 1].copy()

    pr, _ = run(w, prim, body_xy(w, "glass"), seconds=45.0, each_tick=watch)
    return w, human, pr, touch.worst, seen


@pytest.fixture(scope="module")
def handed():
    return _hand_over_full_glass()


def test_the_robot_holds_what_it_gives_by_its_upper_part(handed):
    w, human, pr, worst, seen = handed
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    # its TCP (the middle finger's height) high up the 10 cm glass, not at the 5 cm it takes a glass at to pour
    assert seen["offered"] == pytest.approx(P.offer_grasp_height("glass", RobotController(w.model, w.data).gripper), abs=0.015)
    assert seen["offered"] > P.GRASP_HEIGHT["glass"] + 0.025, seen


def test_she_takes_it_below_the_robots_hand_and_the_hands_stay_apart(handed):
    w, human, pr, worst, seen = handed
    takes = [b for b in human.done if b.name == "take_from_robot"]
    assert takes and takes[0].status == "succeeded", human.done
    st = w.state()
    # hers alone, nothing spilled (she may already be bringing it to her mouth)
    assert st.robot_holds is None and st.human_holds == "glass" and st.liquid.spilled == 0, st.summary()
    assert worst.depth <= TouchMonitor.DEEP, worst
    # her side grip (the palm's normal level, not down as from above), low on the glass, under the robot's hand
    assert abs(seen["palm_normal"][2]) < 0.5 and seen["taken_at"] < 0.03, seen
