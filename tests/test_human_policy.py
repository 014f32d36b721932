"""The active default policy takes a first step within 5 s where it has one; passive never starts."""

import numpy as np
import pytest

from assistbot.human.controller import HumanController
from assistbot.human.perception import RobotView
from assistbot.human.script import parse_human
from assistbot.world import Arrangement, all_arrangements, build_world


@pytest.mark.parametrize("bottle,glass,first", [
    ("HWS:closed", "RWS:inverted", "grasp"),
    ("RWS:open", "HWS:inverted", "turn_glass"),
    ("RWS:closed", "RWS:empty", "request"),
])
def test_active_first_step_within_5_s(bottle, glass, first):
    w = build_world(Arrangement.from_options(bottle, glass), seed=1)
    hc = HumanController(w, profile="active", seed=1)
    p0 = hc.arm.hand_pose()[0]
    hc.run(5.0)
    starts = hc.events("start")
    assert starts and starts[0].what == first and starts[0].t <= 5.0
    assert np.linalg.norm(hc.arm.hand_pose()[0] - p0) > 0.05   # the hand really moved


@pytest.mark.slow
@pytest.mark.parametrize("arr", all_arrangements(), ids=lambda a: a.label())
def test_active_first_step_in_every_arrangement_with_one(arr):
    w = build_world(arr, seed=0)
    hc = HumanController(w, profile="active", seed=0)
    hc.run(5.0)
    b, g = arr.bottle, arr.glass
    # the policy's order: drink, turn the glass, pour, hand the closed bottle over, ask for the glass
    first = ("drink" if g.zone == "HWS" and g.state == "full" else
             "turn_glass" if g.zone == "HWS" and g.state == "inverted" else
             "pour" if b.zone == "HWS" and b.state == "open" and g.zone == "HWS" and g.state == "empty" else
             "grasp" if b.zone == "HWS" and b.state == "closed" else
             "request" if g.zone == "RWS" else None)
    starts = hc.events("start")
    assert (starts[0].what if starts else None) == first


def _robot(offers: bool):
    """What the person sees of the robot: the bottle held out toward her, or an idle hand."""
    return RobotView("bottle", (0.2, 0.0, 0.25), True, False) if offers else RobotView(None, (0.45, 0.0, 0.3), False, True)


@pytest.mark.parametrize("offer_until, takes", [(1.5, False), (None, True)])
def test_what_the_robot_held_out_while_the_hand_was_busy_is_taken_only_if_still_held_out(offer_until, takes):
    """An active person sees the robot hold the bottle out while her open hand is held out (a
    request): she will take it once her hand is free -- if the robot still holds it out then. If the
    robot has taken it back meanwhile, she does not start waiting for it (which would leave the
    robot's next request unanswered)."""
    w = build_world(Arrangement.from_options("RWS:open", "RWS:empty"), seed=0)
    clock = {"t": 0.0}
    hc = HumanController(w, profile="active", seed=0,
                         see=lambda world: _robot(0.5 <= clock["t"] and (offer_until is None or clock["t"] < offer_until)))
    hc.run(12.0, robot=lambda t: clock.update(t=t))
    starts = [e.what for e in hc.events("start")]
    assert starts[0] == "request"
    assert ("take_from_robot" in starts) == takes, starts
    dropped = [e for e in hc.events("note") if e.what == "dropped"]
    assert bool(dropped) == (not takes)
    assert [e.what for e in hc.events("saw")].count("robot_offers:bottle") == 1


def test_the_robot_holding_the_bottle_out_again_is_seen_again():
    w = build_world(Arrangement.from_options("RWS:open", "RWS:empty"), seed=0)
    clock = {"t": 0.0}
    hc = HumanController(w, profile="passive", seed=0, see=lambda world: _robot(0.5 <= clock["t"] < 1.5 or clock["t"] >= 3.0))
    hc.run(6.0, robot=lambda t: clock.update(t=t))
    saw = [round(e.t, 1) for e in hc.events("saw") if e.what == "robot_offers:bottle"]
    assert len(saw) == 2 and saw[1] >= 3.0, saw


@pytest.mark.parametrize("convention, grip", [("seed", "sg"), ("swapped", "ag")])
def test_an_active_person_pours_with_the_grip_of_their_convention(convention, grip):
    w = build_world(Arrangement.from_mapping({"bottle": {"zone": "HWS", "state": "open"},
                                              "glass": {"zone": "HWS", "state": "empty"}}), seed=0)
    hc = HumanController(w, config=parse_human({"profile": "active", "grip_convention": convention}))
    hc.run(1.0)
    start = hc.events("start")[0]
    assert start.what == "pour" and start.detail["grip"] == grip


def test_the_robots_latest_request_is_the_one_answered_once_the_hand_is_free():
    """Busy (waiting to take what the robot would offer), the person hears "give me the glass", then "you can
    drink now": once free they drink; the earlier request, not begun, is dropped as superseded."""
    w = build_world(Arrangement.from_mapping({"bottle": {"zone": "RWS", "state": "open"},
                                              "glass": {"zone": "HWS", "state": "full"}}), seed=0)
    hc = HumanController(w, config=parse_human({"profile": "passive"}))
    hc.start("take_from_robot", object="bottle", timeout=3.0)
    hc.hear("request:glass", 0.2)
    hc.hear("suggest:drink", 1.0)
    hc.run(4.5)
    starts = [e.what for e in hc.events("start")]
    assert starts[:2] == ["take_from_robot", "drink"], starts
    dropped = [e for e in hc.events("note") if e.what == "dropped"]
    assert any(e.detail["behaviour"] == "hand_to_robot" and "superseded by suggest:drink" in e.detail["reason"]
               for e in dropped), dropped
