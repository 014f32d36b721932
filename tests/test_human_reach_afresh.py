"""A reach the arm cannot make from where it is starts afresh from the resting place. A person with short arms,
seated back, whose range of motion is narrowed, holds out an open palm (a request) and is then asked for the
bottle on her side: from the outstretched posture the reach above the bottle stops with joints at their limits,
short of the approach point; from the resting place it gets there. In the physics."""

from __future__ import annotations

from assistbot.human import behaviours as B
from assistbot.human.arm import HumanArm
from assistbot.human.controller import HumanController
from assistbot.human.population import Body, Partner
from assistbot.human.script import parse_human
from assistbot.world import Arrangement, build_world

SHORT_STIFF = Body(upper_arm=0.94, forearm=0.94, shoulder_height=0.93, seat_back=0.07, seat_side=0.06, rom=0.13)


def _asked_for_the_bottle_with_the_palm_held_out():
    w = build_world(Arrangement.from_options("HWS:open", "RWS:empty"), seed=1, body=SHORT_STIFF)
    hc = HumanController(w, config=parse_human({"profile": "passive", "partner": Partner(body=SHORT_STIFF).to_dict()}))
    hc.start("request", hold=30.0)
    hc.run(3.0)
    assert hc.current is not None and hc.current.name == "request"
    held_out = hc.arm.hand_pose()[0]
    hc.start("grasp", object="bottle", grip="ag")      # what the answer to "give me the bottle" begins with
    lowest, t_end = held_out[2], w.time + 15.0
    while hc.current is not None and w.time < t_end:
        hc.run(0.1)
        lowest = min(lowest, float(hc.arm.hand_pose()[0][2]))
    return w, hc, held_out, lowest


def test_a_stiff_arm_reaches_the_bottle_from_a_held_out_palm_by_starting_afresh():
    w, hc, held_out, lowest = _asked_for_the_bottle_with_the_palm_held_out()
    grasp = [b for b in hc.done if b.name == "grasp"]
    assert grasp and grasp[-1].status.value == "succeeded", hc.done
    assert w.human_holding() == "bottle"
    # it went by the resting place: the hand came down from the held-out palm to rest height on the way
    rest = hc.arm.own_point(B.REST)
    assert lowest < rest[2] + 0.05 < held_out[2], (lowest, rest, held_out)


def test_without_starting_afresh_the_same_reach_stops_short(monkeypatch):
    # the arm's sense of itself says every reach can be made: the reach goes straight from where the hand is
    monkeypatch.setattr(HumanArm, "rehearse", lambda self, moves, t=0.0: len(moves))
    w, hc, _, _ = _asked_for_the_bottle_with_the_palm_held_out()
    grasp = [b for b in hc.done if b.name == "grasp"]
    assert grasp and grasp[-1].status.value == "failed" and grasp[-1].reason == "could not reach the approach pose", hc.done
    assert w.human_holding() is None
