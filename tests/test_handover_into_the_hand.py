"""An object brought into the robot's open hand is taken. The person holds the glass out beyond the robot's
reach; the robot's hand reaches out as far as it goes and waits there, open; the person, seeing it, brings
the glass into it. The cameras, the robot's hand in front, no longer see where the glass went (the robot
keeps reaching for where it was seen), but the palm feels it pressed in: the hand closes on it. In the
physics, perception a stand-in that keeps the first sight."""

from __future__ import annotations

from _handover import hold_out_until_there
from assistbot.human.controller import HumanController
from assistbot.human.population import Body, Partner
from assistbot.human.script import parse_human
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.phases import move
from assistbot.robot.sim import body_lift, body_xy, run
from assistbot.world import Arrangement, build_world

#: a person whose held-out glass the robot cannot reach: arms a little short, holding out far to the side
FAR = Partner(body=Body(upper_arm=0.90, forearm=0.94, shoulder_height=0.95, seat_back=0.0, seat_side=-0.03, rom=0.07),
              hold_out_dx=-0.03, hold_out_dy=-0.063, hold_out_dz=-0.01)


def _receive_what_is_brought(monkeypatch, feel: bool):
    if not feel:
        monkeypatch.setattr(move, "GRASP_N", float("inf"))
        # nor closing where it was last seen after waiting for it (`Move.close_short`): only the touch tells
        monkeypatch.setattr(move, "CLOSE_SHORT_WAIT", float("inf"))
    w = build_world(Arrangement.from_options("RWS:closed@0.20,0.20", "HWS:inverted"), seed=0, body=FAR.body)
    robot = RobotController(w.model, w.data)
    human = HumanController(w, config=parse_human({"profile": "passive", "partner": FAR.to_dict()}))
    human.start("hand_to_robot", object="glass", grip="ag")
    hold_out_until_there(w, human, "glass", 0.03)
    seen_xy, seen_lift = body_xy(w, "glass")(), body_lift(w, "glass")()   # the last sight of it
    prim = P.Receive(robot, "glass", human_holds=lambda: w.human_holding() is not None, lifted=lambda: seen_lift,
                     locate=lambda name: body_xy(w, name)())
    pr, _ = run(w, prim, lambda: seen_xy, seconds=45.0, each_tick=human.tick)
    return w, human, pr, seen_xy


def test_the_robot_takes_the_glass_brought_into_its_open_hand(monkeypatch):
    w, human, pr, seen_xy = _receive_what_is_brought(monkeypatch, feel=True)
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    st = w.state()
    assert st.human_holds is None and st.robot_holds is None, st.summary()
    assert st.objects["glass"].zone == "RWS" and st.objects["glass"].inverted, st.summary()   # standing as it came
    handed = [b for b in human.done if b.name == "hand_to_robot"]
    assert handed and handed[-1].status == "succeeded", handed[-1].reason if handed else human.done


def test_not_feeling_it_the_robot_waits_where_the_glass_was_seen_and_does_not_take_it(monkeypatch):
    w, human, pr, _ = _receive_what_is_brought(monkeypatch, feel=False)
    assert pr.status is not P.Status.SUCCEEDED
    assert w.state().robot_holds is None
