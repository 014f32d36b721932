"""Each hand on the part of the glass the other leaves free, in the physics, and no robot geom more than 1 cm
into the person's on the way (the touch measure of every episode summary). Perception is the ground truth
here (`body_xy`, `body_lift`).

- The robot hands the person a full glass it holds by its upper part (`offer_grasp_height`); she takes it
  below the robot's hand where her eyes see room for her grip (`grip_beside_the_robots_hand`).
- It turns the inverted glass, sets it down upright and gives it the same way (`TurnAndHandOver`).
- She hands the robot the glass she holds from above; once it holds it, her hand rises off the glass
  before it opens (`behaviours._let_go`). The robot waits to feel her let go (`WaitForLetGo`), and lowers
  the glass out from under her fingers before it takes it back (`TakeFromUnder`)."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.episode.touch import TouchMonitor
from assistbot.human.controller import HumanController
from assistbot.human.script import parse_human
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import CONTROL_DT, body_lift, body_xy, run
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


def _taken_upright_with_the_hands_apart(w, human, pr, touch):
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    takes = [b for b in human.done if b.name == "take_from_robot"]
    assert takes and takes[0].status == "succeeded", human.done
    # hers, upright: she may already have set the empty glass down on her side
    st = w.state()
    assert st.robot_holds is None and (st.human_holds == "glass" or st.objects["glass"].zone == "HWS"), st.summary()
    assert w.data.xmat[w.body_id["glass"]][8] > 0.9
    assert touch.worst.depth <= TouchMonitor.DEEP, touch.worst


def test_the_turned_glass_is_set_down_and_given_by_its_upper_part_with_the_hands_apart():
    """Held out by its middle, as the turn leaves it in the hand, the glass left her fingers no room beside the
    robot's palm (2.4 cm into it here, 2.7 cm in the task-space matrix): it is set down upright and taken again by
    its upper part."""
    w = build_world(Arrangement.from_options("HWS:open@-0.22,-0.12", "RWS:inverted@0.22,-0.10"), seed=0)
    robot = RobotController(w.model, w.data)
    human = HumanController(w, config=parse_human({"profile": "passive"}))
    prim = P.TurnAndHandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass",
                             locate=lambda name: body_xy(w, name)())
    touch = TouchMonitor(w.model, w.data)
    held = []

    def watch(t):
        if human.current is None and not human.done and prim.progress.phase == P.OFFER_PHASE:
            held.append(float(robot.tcp_pose().translation()[2] - w.data.xpos[w.body_id["glass"]][2]))
            human.start("take_from_robot", object="glass")
        human.tick(t)
        touch.update(t, 0.0)

    pr, _ = run(w, prim, body_xy(w, "glass"), seconds=60.0, each_tick=watch)
    _taken_upright_with_the_hands_apart(w, human, pr, touch)
    assert held and held[0] > P.GRASP_HEIGHT["glass"] + 0.025, held


def _glass_held_out_from_above():
    """A passive person running her own `hand_to_robot`: the glass grasped from above and held out, settled there.
    The world, the robot, the person, and her grasp site (where the robot's target field looks)."""
    w = build_world(Arrangement.from_options("RWS:closed@0.2,0.2", "HWS:empty@-0.20,0.05"), seed=0)
    robot = RobotController(w.model, w.data)
    human = HumanController(w, config=parse_human({"profile": "passive"}))
    human.start("hand_to_robot", object="glass", grip="ag")
    while not (w.human_holding() == "glass" and human.arm.arrived(w.time, 0.03)) and w.time < 10.0:
        human.tick(w.time)
        w.step(round(CONTROL_DT / w.model.opt.timestep))
    return w, robot, human, w.model.site("human_r_grasp").id


def test_she_lets_go_of_the_glass_she_held_from_above_without_sweeping_into_the_robots_hand():
    """Her grip from above hangs her fingers down the glass's side toward the robot; opened there, they swept
    2.5 cm into its palm here (2.2 cm in the task-space matrix). She lets go by rising off the glass first, and
    it ends in the robot's hand."""
    w, robot, human, hand = _glass_held_out_from_above()
    prim = P.Receive(robot, "glass", human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, "glass"),
                     locate=lambda name: body_xy(w, name)())
    touch = TouchMonitor(w.model, w.data)

    def watch(t):
        human.tick(t)
        touch.update(t, 0.0)

    pr, _ = run(w, prim, lambda: tuple(w.data.site_xpos[hand][:2]), seconds=60.0, each_tick=watch)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    gives = [b for b in human.done if b.name == "hand_to_robot"]
    assert gives and gives[0].status == "succeeded", human.done
    st = w.state()
    assert st.human_holds is None and st.objects["glass"].zone == "RWS", st.summary()
    assert touch.worst.depth <= TouchMonitor.DEEP, touch.worst


def _she_lets_go_but_leaves_her_hand(release_after: float, cameras_say_holding: bool):
    """She holds the glass out from above; ``release_after`` s after the robot's grip closes her grip gives, and
    her arm and fingers stay where they were. The robot's view of her holding it: the truth, or (not
    ``cameras_say_holding``) never, as the cameras read her hand round the glass the robot holds as open."""
    w, robot, human, hand = _glass_held_out_from_above()
    holds = (lambda: w.human_holding() is not None) if cameras_say_holding else (lambda: False)
    prim = P.Receive(robot, "glass", human_holds=holds, lifted=body_lift(w, "glass"), locate=lambda name: body_xy(w, name)())
    touch = TouchMonitor(w.model, w.data)
    grasped: list = []
    moved = [0.0]     # how far (m) the robot's hand went while she still held the glass

    def watch(t):
        if not grasped and robot.gripper.grasps():
            grasped.append((t, robot.tcp_pose().translation().copy()))
        if grasped and w.human_holding() is not None:
            moved[0] = max(moved[0], float(np.linalg.norm(robot.tcp_pose().translation() - grasped[0][1])))
            if t >= grasped[0][0] + release_after:
                w.human_release("glass")
        if not grasped:
            human.tick(t)
        touch.update(t, 0.0)

    pr, _ = run(w, prim, lambda: tuple(w.data.site_xpos[hand][:2]), seconds=60.0, each_tick=watch)
    return w, pr, touch.worst, moved[0]


def test_the_robot_takes_the_glass_down_from_under_fingers_left_hanging_on_it():
    """Let go of, the glass is lowered out from under her fingers, which hang down its side between it and the
    robot's palm, before it is taken back (taken back level, the robot's fingers round its far side swept
    through hers: 1.6 cm)."""
    w, pr, worst, _ = _she_lets_go_but_leaves_her_hand(1.0, cameras_say_holding=True)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    st = w.state()
    assert st.human_holds is None and st.objects["glass"].zone == "RWS", st.summary()
    assert worst.depth <= TouchMonitor.DEEP, worst


def test_the_robot_waits_to_feel_the_glass_let_go_where_the_cameras_cannot_tell():
    """The cameras read her hand as open from the moment the robot's closes round the glass: the robot's
    hand holds still until the glass's weight comes onto it, 2 s later, and then takes it."""
    w, pr, worst, moved = _she_lets_go_but_leaves_her_hand(2.0, cameras_say_holding=False)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    assert moved < 0.01, moved
    assert w.state().objects["glass"].zone == "RWS", w.state().summary()
    assert worst.depth <= TouchMonitor.DEEP, worst


@pytest.mark.parametrize("deeper", [0.0, 0.015])
def test_a_glass_held_from_above_is_taken_low_with_the_palm_short_of_her_fingers(deeper):
    """Seen held from above, the glass is taken by its lower part (the palm's lower edge at its base) with the palm
    ROOM_FOR_HER_FINGERS short of its wall: her fingers hang down its upper part toward the robot. The axis seen
    ``deeper`` (m, away from the robot, as vision places it in some frames) or not: with the nominal grasp the
    palm came to the wall, 1.3 cm into her fingers in the task-space matrix; short of the wall but at the
    nominal height, the upper finger closing round the glass went 1.7 cm into them."""
    w, robot, human, hand = _glass_held_out_from_above()
    prim = P.Receive(robot, "glass", human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, "glass"),
                     locate=lambda name: body_xy(w, name)(), holder_grip=lambda: "ag")
    touch = TouchMonitor(w.model, w.data)
    face = w.model.site("robot_palm_face").id
    glass = w.body_id["glass"]
    grasp: list = []     # the palm face's gap to the wall, and the TCP's height above the glass's base

    def watch(t):
        if not grasp and robot.gripper.grasps():
            grasp.append((float(np.linalg.norm(w.data.site_xpos[face][:2] - w.data.xpos[glass][:2])) - P.RADIUS["glass"],
                          float(robot.tcp_pose().translation()[2] - w.data.xpos[glass][2])))
        human.tick(t)
        touch.update(t, 0.0)

    pr, _ = run(w, prim, lambda: (w.data.site_xpos[hand][0] - deeper, w.data.site_xpos[hand][1]), seconds=60.0,
                each_tick=watch)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    assert w.state().human_holds is None and w.state().objects["glass"].zone == "RWS", w.state().summary()
    assert grasp, "the hand never closed on the glass"
    gap, height = grasp[0]
    assert gap > 0.008, grasp                         # the palm's face off the wall (0.5 cm and 0.1 cm at it)
    assert height < P.held_grasp_height("glass", robot.gripper) - 0.005, grasp    # below the band's middle
    assert touch.worst.depth <= TouchMonitor.DEEP, touch.worst
