"""Robot primitives in the world's physics (no cognition): the effect happens, safely, from two placements.

Every run checks the issue's safety figures: the arm stays >= 5 cm from the human's head and
torso, within its joint ranges, and never deeper into the HWS than the hand-over zone.
Targets come from ground truth here (a stand-in for perception).
"""

from __future__ import annotations

import mink
import mujoco
import numpy as np
import pytest

from assistbot.human.controller import HumanController
from assistbot.robot import primitives as P
from assistbot.robot.actions import ACTION_PRIMITIVES, MOTIONS
from assistbot.robot.controller import HANDOVER_DEPTH, RobotController
from assistbot.robot.primitives import Status
from assistbot.robot.primitives.reaching import REST_POSE_POS, TOP_CLEARANCE
from assistbot.robot.sim import CONTROL_DT, body_lift, body_xy, run
from assistbot.task.drinking import ROBOT_ACTIONS
from assistbot.world import Arrangement, build_world
from assistbot.world.layout import TABLE_Z


def make(bottle: str, glass: str):
    w = build_world(Arrangement.from_options(bottle, glass), seed=0)
    return w, RobotController(w.model, w.data)


def assert_safe(s):
    assert s.human >= 0.05, s
    assert s.min_x >= -HANDOVER_DEPTH, s
    assert s.limits, s


def upright(w, obj):
    return w.data.xmat[w.body_id[obj]][8] > 0.98


def settle(w, seconds=1.0, human=None):
    for _ in range(int(seconds / CONTROL_DT)):
        if human is not None:
            human.tick(w.time)
        w.step(10)


def _holding_out(w, obj):
    """A passive person running their own `hand_to_robot`: grasps ``obj`` and holds it out (settled there)."""
    human = HumanController(w, "passive")
    human.start("hand_to_robot", object=obj, grip="ag")
    while not (w.human_holding() == obj and human.arm.arrived(w.time, 0.03)) and w.time < 10.0:
        settle(w, CONTROL_DT, human)
    return human


# --------------------------------------------------------------------------- turn, place, pour
@pytest.mark.parametrize("xy", ["0.15,0.10", "0.22,-0.15"])
def test_turn_glass_ends_upright_in_rws(xy):
    w, robot = make("HWS:closed", f"RWS:inverted@{xy}")
    pr, s = run(w, P.TurnGlass(robot), body_xy(w, "glass"))
    assert pr.status is Status.SUCCEEDED, pr.reason
    settle(w, 0.5)
    assert upright(w, "glass")
    assert w.state().objects["glass"].zone == "RWS"
    assert w.data.xpos[w.body_id["glass"]][2] < 0.76  # standing on the table
    assert_safe(s)


@pytest.mark.parametrize("obj, start, spot", [("glass", "0.20,-0.12", (0.25, 0.05)), ("bottle", "0.15,0.20", (0.22, -0.05))])
def test_place_in_rws_puts_the_object_down_upright_at_the_spot(obj, start, spot):
    w, robot = make(*( (f"RWS:closed@{start}", "HWS:empty") if obj == "bottle" else ("HWS:closed", f"RWS:empty@{start}")))
    pr, s = run(w, P.PlaceInRWS(robot, obj, spot=spot), body_xy(w, obj))
    assert pr.status is Status.SUCCEEDED, pr.reason
    settle(w, 0.5)
    p = w.data.xpos[w.body_id[obj]]
    assert np.hypot(p[0] - spot[0], p[1] - spot[1]) < 0.03
    assert w.state().objects[obj].zone == "RWS"
    assert upright(w, obj) and p[2] < 0.76
    assert_safe(s)


# the third: the bottle where the robot puts it down after holding it for the stopper, near the ready pose
@pytest.mark.parametrize("bottle, glass", [("0.20,0.12", "0.20,-0.12"), ("0.12,-0.20", "0.24,0.05"), ("0.26,-0.05", "0.13,0.167")])
def test_pour_fills_the_upright_glass(bottle, glass):
    w, robot = make(f"RWS:open@{bottle}", f"RWS:empty@{glass}")
    prim = P.Pour(robot, "bottle", locate=lambda name: body_xy(w, name)())
    pr, s = run(w, prim, body_xy(w, "bottle"))
    assert pr.status is Status.SUCCEEDED, pr.reason
    settle(w, 0.5)
    liq = w.state().liquid
    assert liq.in_glass >= 0.9 * liq.total, w.state().summary()
    assert liq.spilled < 0.1 * liq.total, w.state().summary()
    assert upright(w, "glass") and upright(w, "bottle")
    assert w.state().objects["bottle"].zone == "RWS"
    assert_safe(s)


def test_the_open_hand_turning_toward_a_bottle_near_the_ready_pose_passes_over_its_neck():
    # where the robot puts the bottle down after holding it for the stopper: the fingers, turning toward
    # it from the ready pose, sweep round at the height of its neck unless the hand comes in high enough
    w, robot = make("RWS:open@0.26,-0.05", "RWS:empty@0.13,0.167")
    m, d = w.model, w.data
    prim = P.Pour(robot, "bottle", locate=lambda name: body_xy(w, name)())
    hand = [g for g in range(m.ngeom) if m.body(m.geom_bodyid[g]).name.startswith("robot_f") or m.geom(g).name == "robot_palm"]
    bottle = [g for g in range(m.ngeom) if m.geom_bodyid[g] == w.body_id["bottle"]]
    nearest = []

    def tick(t):
        if prim.progress.phase in ("ready", "above pre-grasp"):
            nearest.append(min(mujoco.mj_geomDistance(m, d, a, b, 0.2, None) for a in hand for b in bottle))

    run(w, prim, body_xy(w, "bottle"), each_tick=tick, seconds=5.0)
    assert nearest and min(nearest) >= TOP_CLEARANCE - 0.002, min(nearest)
    assert upright(w, "bottle")


def test_pour_without_a_seen_glass_fails_with_a_reason():
    w, robot = make("RWS:open", "RWS:empty")
    prim = P.Pour(robot, "bottle")  # no locate(): the glass is not seen
    pr, _ = run(w, prim, body_xy(w, "bottle"), seconds=1.0)
    assert pr.status is Status.FAILED and "glass" in pr.reason


def test_pour_into_a_glass_seen_upside_down_is_refused_and_nothing_is_poured():
    """The decision to fill rested on a misreading (the glass read upright once while the person held it):
    the cameras now see it upside down, so the bottle is not tilted over it."""
    w, robot = make("RWS:open@0.20,0.12", "RWS:inverted@0.20,-0.12")
    prim = P.Pour(robot, "bottle", locate=lambda name: body_xy(w, name)(),
                  seen_state=lambda name: w.state().state_of(name))
    pr, s = run(w, prim, body_xy(w, "bottle"))
    assert pr.status is Status.FAILED and "upside down" in pr.reason
    settle(w, 0.5)
    liq = w.state().liquid
    assert liq.in_bottle == liq.total, w.state().summary()
    assert upright(w, "bottle") and w.state().objects["bottle"].zone == "RWS"
    assert_safe(s)


@pytest.mark.parametrize("prim_cls", [P.TurnGlass, P.TurnAndHandOver])
def test_a_glass_seen_upright_is_not_turned(prim_cls):
    w, robot = make("HWS:closed", "RWS:empty@0.20,-0.12")
    before = w.data.xpos[w.body_id["glass"]].copy()
    prim = prim_cls(robot, seen_state=lambda name: w.state().state_of(name))
    pr, s = run(w, prim, body_xy(w, "glass"), seconds=20.0)
    assert pr.status is Status.FAILED and "already upright" in pr.reason
    settle(w, 0.5)
    assert upright(w, "glass") and np.linalg.norm(w.data.xpos[w.body_id["glass"]] - before) < 0.005
    assert_safe(s)


# --------------------------------------------------------------------------- stopper
@pytest.mark.parametrize("bottle", ["0.20,0.12", "0.14,-0.18"])
def test_bottle_held_for_the_stopper_lets_a_15N_pull_take_it_off(bottle):
    """A stand-in hand pulls the stopper up with 15 N while the robot holds the bottle; the world's fit decides."""
    w, robot = make(f"RWS:closed@{bottle}", "HWS:empty")
    removed = lambda: not w.data.eq_active[w.eq_stopper]  # noqa: E731 - what the cameras would show
    prim = P.HoldBottleForStopper(robot, stopper_removed=removed)
    stopper = w.model.body("stopper").id
    pulled = []

    def pull(t):
        holding_out = prim.progress.phase == "hold steady for the stopper"
        on = holding_out and w.data.eq_active[w.eq_stopper]
        w.data.xfrc_applied[stopper, 2] = 15.0 if on else 0.0
        if on:
            pulled.append(t)

    pr, s = run(w, prim, body_xy(w, "bottle"), each_tick=pull)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert pulled and pulled[-1] - pulled[0] < 0.5  # the fit gave at once under the pull
    st = w.state()
    assert st.bottle_open
    settle(w, 0.5)
    assert upright(w, "bottle") and w.state().objects["bottle"].zone == "RWS"
    assert w.state().liquid.in_bottle == w.state().liquid.total
    assert_safe(s)


def test_the_scripted_human_pulls_the_stopper_off_the_bottle_the_robot_holds():
    w, robot = make("RWS:closed@0.18,0.10", "HWS:empty")
    human = HumanController(w, "passive")
    prim = P.HoldBottleForStopper(robot, stopper_removed=lambda: not w.data.eq_active[w.eq_stopper])

    def tick(t):
        if human.current is None and not human.done and prim.progress.phase == "hold steady for the stopper":
            human.start("pull_stopper")
        human.tick(t)

    pr, s = run(w, prim, body_xy(w, "bottle"), seconds=45.0, each_tick=tick)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert human.done and human.done[0].status == "succeeded", human.done and human.done[0].reason
    st = w.state()
    assert st.bottle_open and st.objects["bottle"].zone == "RWS" and upright(w, "bottle")
    assert_safe(s)


def _taken_from_her_and_held_for_the_stopper(w, robot, human):
    """The robot takes the bottle from the person's hand (HoldBottleForStopper, built now), a stand-in hand
    pulls the stopper while it holds it, and it ends opened, upright, in the RWS."""
    prim = P.HoldBottleForStopper(robot, human_holds=lambda: w.human_holding() == "bottle",
                                  stopper_removed=lambda: not w.data.eq_active[w.eq_stopper], lifted=body_lift(w, "bottle"),
                                  locate=lambda name: body_xy(w, name)())
    stopper = w.model.body("stopper").id

    def tick(t):
        on = prim.progress.phase == "hold steady for the stopper" and w.data.eq_active[w.eq_stopper]
        w.data.xfrc_applied[stopper, 2] = 15.0 if on else 0.0  # a stand-in hand pulls the stopper
        human.tick(t)

    pr, s = run(w, prim, body_xy(w, "bottle"), each_tick=tick)
    assert pr.status is Status.SUCCEEDED, pr.reason
    settle(w, 0.5, human)
    st = w.state()
    assert st.bottle_open and st.objects["bottle"].zone == "RWS" and upright(w, "bottle"), st.summary()
    assert_safe(s)


def test_bottle_held_out_by_the_human_is_taken_and_held_for_the_stopper():
    w, robot = make("HWS:closed@-0.22,-0.12", "RWS:empty")
    _taken_from_her_and_held_for_the_stopper(w, robot, _holding_out(w, "bottle"))


def test_bottle_beyond_reach_that_the_human_is_about_to_hold_out_is_waited_for():
    # decided while her hand is on its way to the bottle standing beyond the arm's reach: the robot
    # holds its hand out for it instead of reaching for it on the table (out of reach: a failure)
    w, robot = make("HWS:closed@-0.22,-0.12", "RWS:empty")
    human = HumanController(w, "passive")
    human.start("hand_to_robot", object="bottle", grip="ag")
    assert w.human_holding() is None
    _taken_from_her_and_held_for_the_stopper(w, robot, human)


def test_stopper_hold_times_out_with_a_reason():
    w, robot = make("RWS:closed", "HWS:empty")
    prim = P.HoldBottleForStopper(robot, timeout=2.0)
    pr, s = run(w, prim, body_xy(w, "bottle"), seconds=25)
    assert pr.status is Status.FAILED and "stopper" in pr.reason
    assert_safe(s)


@pytest.mark.slow
def test_a_stopper_nobody_pulls_is_not_waited_for_until_the_episode_counts_as_stalled():
    """Nobody pulls the stopper (or the cameras do not see it come off: the hand hides the bottle's top): the hold
    gives up, and the bottle is set down on the table again, before the arm has been still for as long as the
    judge calls a stalled episode (a partner's episode ended so, the hand held out with the opened bottle)."""
    from assistbot.episode.judge import MOVING_SPEED, STALL_SECONDS

    w, robot = make("RWS:closed", "HWS:empty")
    prim = P.HoldBottleForStopper(robot)
    arm = [w.model.jnt_dofadr[w.model.joint(f"robot_j{i}").id] for i in range(1, 8)]
    still = {"since": 0.0, "longest": 0.0}

    def watch(t):
        if np.abs(w.data.qvel[arm]).max() > MOVING_SPEED:
            still["since"] = t
        still["longest"] = max(still["longest"], t - still["since"])
    pr, _ = run(w, prim, body_xy(w, "bottle"), seconds=60, each_tick=watch)
    assert pr.status is Status.FAILED and "stopper" in pr.reason
    assert still["longest"] < STALL_SECONDS, still
    b = w.state().objects["bottle"]
    assert b.held_by is None and b.upright and b.zone == "RWS" and b.pos[2] < TABLE_Z + 0.01, w.state().summary()


# --------------------------------------------------------------------------- hand-over to the human
def _give(w, robot, prim, target, obj, seconds=45.0):
    """Run a giving primitive; the scripted human starts `take_from_robot` once the object is held out still."""
    human = HumanController(w, "passive")

    def tick(t):
        if human.current is None and not human.done and prim.progress.phase.startswith("wait for the human"):
            human.start("take_from_robot", object=obj)
        human.tick(t)

    pr, s = run(w, prim, target, seconds=seconds, each_tick=tick)
    settle(w, 1.0, human)
    return pr, s, human


@pytest.mark.parametrize("glass", ["0.20,-0.12", "0.14,0.08", "0.265,-0.089"])
def test_full_glass_handed_over_ends_in_the_human_hand(glass):
    """Also a glass standing close to the robot, which the arm reaches without folding into its own column."""
    w, robot = make("HWS:closed", f"RWS:full@{glass}")
    prim = P.HandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass")
    pr, s, human = _give(w, robot, prim, body_xy(w, "glass"), "glass")
    assert pr.status is Status.SUCCEEDED, pr.reason
    st = w.state()
    assert st.human_holds == "glass" and st.robot_holds is None, st.summary()
    assert st.liquid.spilled < 0.1 * st.liquid.total, st.summary()
    assert st.objects["glass"].zone == "HWS"
    assert_safe(s)


@pytest.mark.slow
def test_bottle_handed_over_ends_in_the_human_hand():
    w, robot = make("RWS:open@0.18,0.10", "HWS:empty")
    prim = P.HandOver(robot, "bottle", human_holds=lambda: w.human_holding() == "bottle")
    pr, s, _ = _give(w, robot, prim, body_xy(w, "bottle"), "bottle")
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert w.state().human_holds == "bottle"
    assert_safe(s)


@pytest.mark.slow
@pytest.mark.parametrize("glass", ["0.15,-0.05", "0.22,0.10"])
def test_turn_and_hand_over_gives_the_human_an_upright_glass(glass):
    w, robot = make("HWS:closed", f"RWS:inverted@{glass}")
    prim = P.TurnAndHandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass")
    pr, s, human = _give(w, robot, prim, body_xy(w, "glass"), "glass")
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert [(b.name, b.status) for b in human.done][:1] == [("take_from_robot", "succeeded")]
    # taken upright; the person then sets the empty glass down on her side or still holds it
    st = w.state()
    assert w.data.xmat[w.body_id["glass"]][8] > 0.9 and st.robot_holds is None
    assert st.human_holds == "glass" or st.objects["glass"].zone == "HWS", st.summary()
    assert_safe(s)


def test_the_hand_that_turned_the_glass_and_gave_it_comes_back_to_rest_unwound():
    """The hand holds the turned glass out upside down, toward the person's open hand near the middle line.
    Once it is taken, the empty hand rolls back the way it turned before it goes to rest: straight for the
    upright rest pose, the wrist winds on into its joint limits and stops short of the pose (then every
    next action fails at its first move)."""
    w, robot = make("RWS:closed@0.25,0.2", "RWS:inverted")
    hand = (-0.045, -0.071, 0.215)      # the open hand as an active person holds it out for the glass
    prim = P.TurnAndHandOver(robot, "glass", human_holds=lambda: w.human_holding() == "glass", partner_hand=lambda: hand)
    pr, s, human = _give(w, robot, prim, body_xy(w, "glass"), "glass")
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert [(b.name, b.status) for b in human.done][:1] == [("take_from_robot", Status.SUCCEEDED)]
    assert np.linalg.norm(robot.tcp_pose().translation() - REST_POSE_POS) < 0.04   # the rest move's tolerance
    lo, hi = robot.ik.model.jnt_range[:, 0], robot.ik.model.jnt_range[:, 1]
    assert np.all(np.minimum(robot.q() - lo, hi - robot.q()) > 0.05), robot.q()
    assert_safe(s)


def test_hand_over_felt_lets_go_only_once_the_human_holds_it():
    """The cameras cannot tell (``human_holds`` is always False): the wrist feels the person take it."""
    w, robot = make("HWS:closed", "RWS:full@0.20,-0.12")
    prim = P.HandOver(robot, "glass", human_holds=lambda: False)
    at_let_go = []

    def watch(t):
        if prim.progress.phase == "let go" and not at_let_go:
            at_let_go.append(w.human_holding())

    human = HumanController(w, "passive")

    def tick(t):
        watch(t)
        if human.current is None and not human.done and prim.progress.phase == P.OFFER_PHASE:
            human.start("take_from_robot", object="glass")
        human.tick(t)

    pr, s = run(w, prim, body_xy(w, "glass"), seconds=45.0, each_tick=tick)
    settle(w, 1.0, human)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert at_let_go == ["glass"]
    st = w.state()
    assert st.human_holds == "glass" and st.liquid.spilled < 0.1 * st.liquid.total, st.summary()


def test_hand_over_without_a_taker_fails_with_a_reason():
    # a full glass held out still for 6 s: the liquid settling in it is not taken for a pull
    w, robot = make("HWS:closed", "RWS:full@0.18,-0.10")
    prim = P.HandOver(robot, "glass", timeout=6.0)
    pr, s = run(w, prim, body_xy(w, "glass"), seconds=30)
    assert pr.status is Status.FAILED and "did not take" in pr.reason
    assert_safe(s)


def test_a_hand_seen_holding_but_not_holding_does_not_make_the_robot_let_go():
    """The cameras read the person's hand as holding the glass (``human_holds`` always True: a hand closing
    around it hides it), but nobody takes it: the robot lets go only of what it feels taken, so the glass
    is not dropped; not taken in time, it is set down for the person."""
    w, robot = make("HWS:closed", "RWS:full@0.18,-0.10")
    prim = P.HandOver(robot, "glass", timeout=6.0, human_holds=lambda: True)
    pr, s = run(w, prim, body_xy(w, "glass"), seconds=40)
    assert pr.status is Status.FAILED and "did not take" in pr.reason
    settle(w, 0.5)
    st = w.state()
    assert upright(w, "glass") and w.data.xpos[w.body_id["glass"]][2] < 0.76, st.summary()
    assert st.liquid.spilled < 0.1 * st.liquid.total, st.summary()
    assert_safe(s)


class _GraspThenReachTooFar(P.Primitive):
    """Grasp and lift the target, then carry it toward a goal out of the arm's reach: a failure while carrying."""

    name = "grasp_then_reach_too_far"

    def phases(self):
        from assistbot.robot import poses

        far = poses.pose(mink.SO3.identity(), np.array([-0.45, -0.35, 0.95]))
        return P.reach_and_grasp_phases(self) + [
            P.Move("lift", lambda p: P.side_grasp_pose(p, up=P.LIFT), duration=1.2),
            P.Move("too far", lambda p: far, duration=1.5),
        ]


def test_an_action_failing_while_carrying_sets_the_object_down_before_it_reports():
    w, robot = make("HWS:closed", "RWS:empty@0.20,-0.10")
    pr, s = run(w, _GraspThenReachTooFar(robot, "glass"), body_xy(w, "glass"), seconds=40.0)
    assert pr.status is Status.FAILED and "out of reach" in pr.reason, pr.reason
    settle(w, 0.5)
    st = w.state()
    assert st.robot_holds is None and not robot.gripper.grasps()
    assert upright(w, "glass") and st.objects["glass"].zone == "RWS", st.summary()
    assert w.data.xpos[w.body_id["glass"]][2] < 0.76  # standing on the table, not dropped from the air
    assert_safe(s)


def test_a_turned_glass_not_taken_is_set_down_upright():
    w, robot = make("HWS:closed", "RWS:inverted@0.18,-0.08")
    pr, s = run(w, P.TurnAndHandOver(robot, "glass", timeout=3.0), body_xy(w, "glass"), seconds=60.0)
    assert pr.status is Status.FAILED and "did not take" in pr.reason, pr.reason
    settle(w, 0.5)
    st = w.state()
    assert st.robot_holds is None and upright(w, "glass"), st.summary()
    assert_safe(s)


# --------------------------------------------------------------------------- receiving from the human
@pytest.mark.parametrize("obj, arrangement", [("bottle", ("HWS:closed@-0.22,-0.12", "RWS:empty")),
                                              ("glass", ("RWS:closed@0.2,0.2", "HWS:empty@-0.20,0.05"))])
def test_receive_takes_the_object_from_the_human_hand_and_puts_it_in_rws(obj, arrangement):
    """The scripted human's own `hand_to_robot`: grasp, hold out, let go once the robot holds it."""
    w, robot = make(*arrangement)
    human = _holding_out(w, obj)
    assert w.human_holding() == obj
    hand = w.model.site("human_r_grasp").id
    prim = P.Receive(robot, obj, human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, obj),
                     locate=lambda name: body_xy(w, name)())
    pr, s = run(w, prim, lambda: tuple(w.data.site_xpos[hand][:2]), each_tick=human.tick)
    assert pr.status is Status.SUCCEEDED, pr.reason
    settle(w, 0.5, human)
    st = w.state()
    assert st.objects[obj].zone == "RWS" and upright(w, obj), st.summary()
    assert st.human_holds is None and st.robot_holds is None
    assert human.done[-1].status == "succeeded", human.done[-1].reason
    assert_safe(s)


def test_receive_does_not_reach_in_while_the_person_is_not_holding_it_out():
    """Seen doing something else with it (pouring, say): the hand waits beside the person's, then the
    action fails with the reason; nothing is grasped and the object stays in the person's hand."""
    w, robot = make("HWS:closed@-0.22,-0.12", "RWS:empty")
    human = _holding_out(w, "bottle")
    hand = w.model.site("human_r_grasp").id
    prim = P.Receive(robot, "bottle", human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, "bottle"),
                     locate=lambda name: body_xy(w, name)(), offered=lambda: False)
    pr, s = run(w, prim, lambda: tuple(w.data.site_xpos[hand][:2]), each_tick=human.tick)
    assert pr.status is Status.FAILED and pr.phase == "wait while it is held out", (pr.phase, pr.reason)
    assert "did not hold it out" in pr.reason
    assert w.human_holding() == "bottle" and not robot.gripper.grasps()
    assert_safe(s)


def test_receive_leaves_the_object_to_a_person_who_does_not_let_go():
    """Both hold it and the person keeps holding: after the wait the robot's hand opens and withdraws,
    the object stays in the person's hand (no tug of war, nothing carried off)."""
    w, robot = make("HWS:closed@-0.22,-0.12", "RWS:empty")
    human = _holding_out(w, "bottle")
    hand = w.model.site("human_r_grasp").id
    prim = P.Receive(robot, "bottle", human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, "bottle"),
                     locate=lambda name: body_xy(w, name)(), timeout=3.0)

    def person(t):   # from the robot's grasp on the person no longer acts: the arm stays, the grip stays shut
        if not robot.gripper.grasps():
            human.tick(t)

    pr, s = run(w, prim, lambda: tuple(w.data.site_xpos[hand][:2]), seconds=60.0, each_tick=person)
    assert pr.status is Status.FAILED and "did not let go" in pr.reason, pr.reason
    assert w.human_holding() == "bottle" and not robot.gripper.grasps()
    assert_safe(s)


@pytest.mark.parametrize("obj", ["glass", "bottle", "held_out"])
def test_an_object_held_up_is_grasped_where_the_whole_hand_lies_on_its_wall(obj):
    """The palm above the object's base and the upper finger below its wall's top (the glass's rim, the
    bottle's shoulder), read from the MJCF: a finger above the rim curls over it."""
    from assistbot.robot.gripper import hand_extent
    w, _ = make("HWS:closed", "RWS:empty")
    above, below = hand_extent(w.model)
    assert 0.03 < above < 0.04 and 0.04 < below < 0.05
    tops = [P.WALL_TOP[obj]] if obj in P.WALL_TOP else list(P.WALL_TOP.values())

    class Hand:
        reach_above, reach_below = above, below
    h = P.held_grasp_height(obj, Hand)
    for top in tops:
        assert h - below >= 0.0 and h + above <= top, (obj, h, top)


def test_a_grasp_that_closes_on_nothing_opens_and_withdraws_level():
    """The object is not where the hand closes (put down or dropped meanwhile): the action fails with the
    reason, and the hand opens and backs off before it rises, leaving what stands nearby where it stood."""
    from assistbot.robot.phases import OPENED

    w, robot = make("HWS:closed", "RWS:empty@0.20,-0.12")
    glass = w.data.xpos[w.body_id["glass"]].copy()
    spot = (0.22, 0.12)
    prim = P.PlaceInRWS(robot, "glass", spot=(0.25, 0.0))
    phases = []
    pr, s = run(w, prim, lambda: spot,
                each_tick=lambda t: phases.append(prim.progress.phase) if phases[-1:] != [prim.progress.phase] else None)
    assert pr.status is Status.FAILED and "closed on nothing" in pr.reason, pr.reason
    after = phases[phases.index("grasp") + 1:]
    assert after[:3] == ["open", "back off from the failed grasp", "rise"], after
    assert float(robot.gripper.finger_angles().max()) < OPENED
    tcp = robot.tcp_pose().translation()
    assert np.hypot(tcp[0] - spot[0], tcp[1] - spot[1]) > 0.15
    assert np.linalg.norm(w.data.xpos[w.body_id["glass"]] - glass) < 0.005
    assert_safe(s)


# --------------------------------------------------------------------------- request, retract, failures
@pytest.mark.parametrize("target, arrangement, from_ready", [
    ((-0.20, -0.25), ("HWS:closed", "HWS:empty@-0.20,-0.25"), False),
    ((-0.22, 0.12), ("RWS:closed@0.20,0.12", "HWS:empty"), False),
    ((-0.22, 0.121), ("RWS:open@0.20,0.12", "HWS:empty"), False),
    ((-0.22, 0.05), ("RWS:open@0.20,0.12", "HWS:empty@-0.22,0.05"), False),
    ((-0.22, 0.115), ("RWS:open@0.19,0.125", "HWS:empty@-0.22,0.115"), True)])
def test_request_holds_open_hand_near_middle_line(target, arrangement, from_ready):
    """Also with the bottle standing in the RWS on the glass's side: the hand goes over it, out and
    back, and is held out where the forearm, which comes up from below to a palm-up hand, clears it
    (it stays standing where it was). From home, or from the ready pose another action ended in."""
    from assistbot.human.perception import see_robot

    w, robot = make(*arrangement)
    if from_ready:
        assert run(w, P.Retract(robot), seconds=8.0)[0].status is Status.SUCCEEDED
    bottle_xy = body_xy(w, "bottle")()
    prim = P.Request(robot, "glass", locate=lambda name: body_xy(w, name)())
    shown = []

    def watch(t):
        if prim.progress.phase == "show the open hand":
            site = w.model.site("robot_palm_face").id
            normal = -w.data.site_xmat[site].reshape(3, 3)[:, 0]
            shown.append((w.data.site_xpos[site].copy(), robot.gripper.finger_angles().max(), normal[2], see_robot(w).requests))

    pr, s = run(w, prim, lambda: target, seconds=15.0, each_tick=watch)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert len(shown) * CONTROL_DT >= 0.9 * P.Request.SHOW_SECONDS
    palm, fingers, normal_z, requests = shown[-1]
    assert abs(palm[0]) < 0.15
    assert fingers < 0.2  # open
    assert normal_z > 0.8  # palm up
    assert requests  # what the human sees: an open empty hand held out
    # then withdrawn: the robot's own cameras see past it again
    assert w.data.site_xpos[w.model.site("robot_palm_face").id][0] > 0.2
    assert_safe(s)
    bottle = w.state().objects["bottle"]
    assert bottle.upright and np.hypot(*(np.array(bottle.pos[:2]) - bottle_xy)) < 0.01


def test_retract_from_home():
    w, robot = make("HWS:closed", "HWS:empty")
    pr, s = run(w, P.Retract(robot), seconds=8.0)
    assert pr.status is Status.SUCCEEDED, pr.reason
    assert_safe(s)


def test_unreachable_target_fails_with_reason_in_bounded_time():
    w, robot = make("HWS:closed", "RWS:empty")
    pr, s = run(w, P.ReachAndGrasp(robot, "glass"), lambda: (-0.35, -0.50), seconds=15.0)
    assert pr.status is Status.FAILED
    assert "reach" in pr.reason
    assert pr.t < 10.0
    assert_safe(s)


class _MoveTo(P.Primitive):
    """One Move to a goal the test sets each tick."""

    name = "move_to"

    def __init__(self, robot, goal):
        super().__init__(robot, None)
        self._goal = goal

    def phases(self):
        return [P.Move("approach", lambda p: p._goal(), duration=1.5)]


@pytest.mark.parametrize("bad_seconds, ends", [(0.1, Status.SUCCEEDED), (0.6, Status.FAILED)])
def test_a_target_out_of_reach_for_a_moment_does_not_end_the_move(bad_seconds, ends):
    from assistbot.robot import poses

    w, robot = make("HWS:closed", "RWS:empty")
    home = robot.commanded_tcp_pose()
    near = poses.pose(home.rotation(), home.translation() + np.array([-0.05, 0.05, -0.05]))
    far = poses.pose(home.rotation(), np.array([-0.40, -0.30, 0.80]))  # a misread: deep in the person's side
    t0 = w.time
    pr, s = run(w, _MoveTo(robot, lambda: far if 0.5 <= w.time - t0 < 0.5 + bad_seconds else near), seconds=6.0)
    assert pr.status is ends, pr.reason
    if ends is Status.FAILED:
        assert "out of reach" in pr.reason
    else:
        assert np.linalg.norm(robot.tcp_pose().translation() - near.translation()) < 0.02
    assert_safe(s)


def test_ik_without_solution_is_reported_as_a_failure(monkeypatch):
    w, robot = make("HWS:closed", "RWS:empty")

    def no_solution(*a, **k):
        raise mink.NoSolutionFound("daqp")

    monkeypatch.setattr("assistbot.robot.ik.daqp.solve", lambda *a, **k: (np.zeros(7), 0.0, -1, {}))  # infeasible QP
    monkeypatch.setattr("assistbot.robot.ik.mink.solve_ik", no_solution)  # the same through mink (fast_qp=False)
    pr, _ = run(w, P.ReachAndGrasp(robot, "glass"), body_xy(w, "glass"), seconds=10.0)
    assert pr.status is Status.FAILED
    assert "no solution" in pr.reason and pr.t < 5.0


def test_every_moving_action_has_a_physical_primitive():
    for action in ROBOT_ACTIONS:
        entry = ACTION_PRIMITIVES[action.name]
        if action.moves:
            assert entry is not None, action.name
        else:
            assert entry is None, action.name
    # and every motion is one an action runs
    assert set(MOTIONS) == {a.motion for a in ROBOT_ACTIONS if a.moves}
