"""A trembling hand braced on something stiff stops trembling: one that closes on an object standing on the table and
holds it there, and one whose object the robot's hand has taken hold of. Its grip then bears only what a still
hand's does. Were the commanded tremor to go on, the hand would press the object into the table, or pull it against
the robot's fingers, with a force no hand makes, and tear its own grip open (or, against the robot's fingers,
come near to it). In the physics."""

from __future__ import annotations

import pytest

from _handover import hold_out_until_there
from assistbot.human.controller import HumanController
from assistbot.human.population import Partner
from assistbot.human.script import parse_human
from assistbot.robot import primitives as P
from assistbot.robot.controller import RobotController
from assistbot.robot.sim import body_lift, body_xy, run
from assistbot.world import Arrangement, build_world
from assistbot.world.world import HUMAN_GRIP_YIELD_FORCE, World

AMPLITUDE = 0.015       # m, the population's largest tremor


def _grasp_on_the_table_and_hold(frequency: float, hold: float = 6.0):
    w = build_world(Arrangement.from_options("HWS:closed", "RWS:empty"), seed=1)
    hc = HumanController(w, config=parse_human({"profile": "passive",
                                                "partner": {"tremor_amplitude": AMPLITUDE, "tremor_frequency": frequency}}))
    hc.run(3.0)          # the tremor sets in on the free hand
    hc.start("grasp", object="bottle", grip="ag", lift=False)
    peak, t_end = 0.0, w.time + 12.0 + hold
    grasped_at = None
    while w.time < t_end and (grasped_at is None or w.time < grasped_at + hold):
        hc.run(0.02)
        peak = max(peak, w._grip_load)
        if grasped_at is None and hc.current is None:
            grasped_at = w.time
    return w, hc, peak


def _held_out_sway(w, hc, seconds: float = 4.0) -> float:
    """Hold the object out, and how far (m, peak to peak) it then moves up and down over ``seconds``."""
    hc.start("hold_out", object="bottle")
    while hc.current is not None:
        hc.run(0.1)
    z = []
    for _ in range(int(seconds / 0.02)):
        hc.run(0.02)
        z.append(float(w.data.xpos[w.body_id["bottle"]][2]))
    return max(z) - min(z)


@pytest.mark.parametrize("frequency", [4.0, 6.0])
def test_a_trembling_hand_holds_an_object_on_the_table_as_a_still_one_does(frequency):
    w, hc, peak = _grasp_on_the_table_and_hold(frequency)
    assert [(b.name, b.status.value) for b in hc.done] == [("grasp", "succeeded")], hc.done
    assert w.human_holding() == "bottle" and not w.grip_yields
    assert peak < 0.25 * HUMAN_GRIP_YIELD_FORCE, peak
    # lifted off the table again it trembles as a hand does (the still spell on the table is not taken for an
    # arm that hardly moves, to be driven harder): within the drawn amplitude, up and down, as the load lets it
    sway = _held_out_sway(w, hc)
    assert hc.done[-1].name == "hold_out" and hc.done[-1].status.value == "succeeded", hc.done
    assert w.human_holding() == "bottle" and not w.grip_yields
    assert sway < 4 * AMPLITUDE, sway


@pytest.mark.slow
def test_a_tremor_that_went_on_against_the_table_would_tear_the_grip_open(monkeypatch):
    monkeypatch.setattr(World, "hand_braced", lambda self: False)
    w, hc, peak = _grasp_on_the_table_and_hold(6.0)
    assert w.grip_yields and w.grip_yields[0][1] == "bottle", (w.grip_yields, peak)
    assert w.human_holding() is None


def _robot_takes_the_glass_from_a_trembling_hand():
    w = build_world(Arrangement.from_options("RWS:closed@0.20,0.20", "HWS:empty"), seed=0)
    robot = RobotController(w.model, w.data)
    partner = Partner(tremor_amplitude=AMPLITUDE, tremor_frequency=6.0)
    human = HumanController(w, config=parse_human({"profile": "passive", "partner": partner.to_dict()}))
    human.start("hand_to_robot", object="glass", grip="ag")
    hold_out_until_there(w, human, "glass", 0.04)
    prim = P.Receive(robot, "glass", human_holds=lambda: w.human_holding() is not None, lifted=body_lift(w, "glass"),
                     locate=lambda name: body_xy(w, name)())
    peak = [0.0]

    def tick(*a, **k):
        human.tick(*a, **k)
        peak[0] = max(peak[0], w._grip_load)
    pr, _ = run(w, prim, body_xy(w, "glass"), seconds=45.0, each_tick=tick)
    return w, human, pr, peak[0]


def test_a_trembling_hand_lets_go_of_what_the_robot_has_taken_hold_of():
    w, human, pr, peak = _robot_takes_the_glass_from_a_trembling_hand()
    # what a still hand's grip bears as the robot takes it: the fingers close at some phase of the tremor and the
    # arm then holds the glass there, up to the tremor's amplitude off where her hand settles (docs/measurements.md,
    # "The run at 3614824"); a tremor going on in the grip reaches 0.75 of the yield or tears it
    assert peak < 0.7 * HUMAN_GRIP_YIELD_FORCE, peak
    assert pr.status is P.Status.SUCCEEDED, pr.reason
    assert [(b.name, b.status.value) for b in human.done] == [("hand_to_robot", "succeeded")], human.done
    assert not w.grip_yields          # she let go; the glass was not torn from her fingers
    st = w.state()
    assert st.objects["glass"].zone == "RWS" and st.objects["glass"].upright and st.human_holds is None, st.summary()


@pytest.mark.slow
def test_a_tremor_that_went_on_in_the_robots_grip_would_pull_at_her_fingers_near_tearing_the_glass_from_them(monkeypatch):
    build = World.__init__

    def table_only(self, *a, **k):
        build(self, *a, **k)
        self.geom_stiff = self.geom_table.copy()
    monkeypatch.setattr(World, "__init__", table_only)
    w, _, _, peak = _robot_takes_the_glass_from_a_trembling_hand()
    # the command, watched on a hand that the robot's fingers hold still, is driven up toward its bound
    assert (w.grip_yields and w.grip_yields[0][1] == "glass") or peak > 0.75 * HUMAN_GRIP_YIELD_FORCE, (w.grip_yields, peak)
