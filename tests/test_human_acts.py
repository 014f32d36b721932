"""Every behaviour in physics from two placements, the passive profile's answer to each kind of
request, and scripts whose steps wait for events.  The robot side is `human.standin`: a mocap
block that holds an object only through a weld (physics decides; the human only sees it)."""

import numpy as np
import pytest

from assistbot.human.arm import HANDOVER_X_MAX
from assistbot.human.behaviours import POINT_X_MAX
from assistbot.human.controller import HumanController
from assistbot.human.profiles import PROFILES
from assistbot.human.script import parse_human
from assistbot.human.standin import StandIn, build_world_with_standin
from assistbot.task import DRINK_FRACTION
from assistbot.world import Arrangement, build_world, layout


def _arr(bottle: dict, glass: dict) -> Arrangement:
    return Arrangement.from_mapping({"bottle": bottle, "glass": glass})


def _setup(arr: Arrangement, profile: str = "passive", script=None):
    w = build_world_with_standin(arr, seed=0)
    s = StandIn(w)
    cfg = parse_human({"profile": profile, "script": script}) if script is not None else None
    hc = HumanController(w, profile=profile, config=cfg, see=s.view)
    return w, s, hc


def _run_until_done(hc, s, limit: float, name: str | None = None):
    """Run until a behaviour (named `name`, or any) has ended; return the ending events."""
    t_end = hc.world.time + limit
    while hc.world.time < t_end:
        hc.run(0.5, robot=s.tick)
        ends = [e for e in hc.events() if e.kind in ("succeeded", "failed") and (name is None or e.what == name)]
        if ends and hc.current is None:
            return ends
    return [e for e in hc.events() if e.kind in ("succeeded", "failed")]


class _HandWatch:
    """Robot tick that also records how far the human's hand geoms reach toward the robot (max world x)."""

    def __init__(self, w, s):
        m = w.model
        self.w, self.s = w, s
        self.geoms = [g for g in range(m.ngeom) if m.body(m.geom_bodyid[g]).name.startswith(("human_r_hand", "human_r_index",
                                                                                            "human_r_fingers", "human_r_thumb"))]
        self.x_max = -1.0

    def __call__(self, t):
        self.s.tick(t)
        self.x_max = max(self.x_max, float(self.w.data.geom_xpos[self.geoms, 0].max()))


def _ok(ends, name):
    mine = [e for e in ends if e.what == name]
    assert mine and mine[-1].kind == "succeeded", ends
    return mine[-1]


# ---------------------------------------------------------------------------- drink
@pytest.mark.parametrize("where", [(-0.22, 0.12), (-0.18, -0.15)])
def test_drink_from_a_full_glass_counts(where):
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "HWS", "state": "full", "position": list(where)}))
    n0 = w.state().liquid.in_glass
    assert n0 >= 0.6 * layout.N_PARTICLES
    hc.start("drink")
    _ok(_run_until_done(hc, s, 25.0), "drink")
    st = w.state()
    assert st.liquid.drunk >= DRINK_FRACTION * n0          # particles that passed within 4 cm of the mouth
    assert st.liquid.in_glass == 0 and st.liquid.spilled <= n0 - DRINK_FRACTION * n0
    g = st.objects["glass"]                                 # put back upright where it stood
    assert st.human_holds is None and g.upright and np.linalg.norm(np.array(g.pos[:2]) - where) < 0.05


def test_drink_does_not_count_with_an_empty_glass():
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "HWS", "state": "empty"}))
    hc.start("drink")
    top = 0.0
    while w.time < 25.0 and (hc.current is not None or not hc.done):
        hc.run(0.2, robot=s.tick)
        top = max(top, float(w.data.xpos[w.body_id["glass"]][2]))
    ends = [e for e in hc.events() if e.kind in ("succeeded", "failed")]
    assert ends[-1].what == "drink" and ends[-1].kind == "failed" and "empty" in ends[-1].detail["reason"]
    assert w.state().liquid.drunk == 0
    assert top > 1.05                                       # the glass really was brought up to the mouth


# ---------------------------------------------------------------------------- turn glass, put down, point, request
@pytest.mark.parametrize("where", [(-0.22, 0.12), (-0.18, -0.15)])
def test_turn_glass_upright(where):
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "HWS", "state": "inverted", "position": list(where)}))
    hc.start("turn_glass")
    _ok(_run_until_done(hc, s, 25.0), "turn_glass")
    g = w.state().objects["glass"]
    assert g.upright and g.held_by is None and g.pos[2] < layout.TABLE_Z + 0.01
    assert np.linalg.norm(np.array(g.pos[:2]) - where) < 0.05


@pytest.mark.parametrize("obj,grip,start,spot", [
    ("bottle", "ag", (-0.22, -0.12), (-0.30, 0.05)),
    ("glass", "sg", (-0.28, 0.05), (-0.20, -0.15)),
])
def test_put_down_at_a_spot_by_script(obj, grip, start, spot):
    other = "glass" if obj == "bottle" else "bottle"
    arr = {obj: {"zone": "HWS", "state": "closed" if obj == "bottle" else "empty", "position": list(start)},
           other: {"zone": "RWS", "state": "open" if other == "bottle" else "empty"}}
    w, s, hc = _setup(Arrangement.from_mapping(arr),
                      script=[{"do": "grasp", "object": obj, "grip": grip}, {"do": "put_down", "object": obj, "at": list(spot)}])
    _ok(_run_until_done(hc, s, 25.0, "put_down"), "put_down")
    o = w.state().objects[obj]
    assert w.state().human_holds is None and o.upright and o.pos[2] < layout.TABLE_Z + 0.01
    assert np.linalg.norm(np.array(o.pos[:2]) - spot) < 0.05


def _tilt(w, obj: str) -> float:
    return float(np.degrees(np.arccos(np.clip(w.data.xmat[w.body_id[obj]][8], -1.0, 1.0))))


@pytest.mark.parametrize("grip", ["sg", "ag"])
def test_an_object_held_tilted_is_put_down_upright(grip):
    """A pour given up half way leaves the bottle tilted in the hand: put down as it is held, it would land
    on its edge and fall over. The hand turns it upright on the way down."""
    from assistbot.human.behaviours import _rodrigues

    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed", "position": [-0.22, -0.12]}, {"zone": "RWS", "state": "empty"}))
    hc.start("grasp", object="bottle", grip=grip)
    _ok(_run_until_done(hc, s, 20.0, "grasp"), "grasp")
    p, R = hc.arm.hand_pose()
    hc.arm.move_to(p + np.array([0.0, 0.0, 0.05]), _rodrigues(np.array([0.0, 1.0, 0.0]), np.radians(50)) @ R, t=w.time)
    hc.run(3.0, robot=s.tick)
    assert w.human_holding() == "bottle" and _tilt(w, "bottle") > 25.0
    spot = np.array([-0.28, 0.0])
    hc.start("put_down", object="bottle", at=list(spot))
    _ok(_run_until_done(hc, s, 25.0, "put_down"), "put_down")
    hc.run(2.0, robot=s.tick)
    o = w.state().objects["bottle"]
    assert w.human_holding() is None and _tilt(w, "bottle") < 5.0 and o.pos[2] < layout.TABLE_Z + 0.01, w.state().summary()
    assert np.linalg.norm(np.array(o.pos[:2]) - spot) < 0.05


@pytest.mark.parametrize("bottle,glass,obj", [
    ({"zone": "HWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}, "glass"),
    ({"zone": "RWS", "state": "closed", "position": [0.25, -0.30]}, {"zone": "HWS", "state": "empty", "position": [-0.30, 0.10]}, "glass"),
    ({"zone": "RWS", "state": "closed", "position": [0.25, -0.30]}, {"zone": "HWS", "state": "empty"}, "bottle"),
])
def test_point_at_an_object(bottle, glass, obj):
    w, s, hc = _setup(_arr(bottle, glass))
    hc.start("point", object=obj, hold=1.0)
    aims = []
    t_end = w.time + 8.0
    while w.time < t_end and (hc.current is not None or not aims):
        hc.run(0.1, robot=s.tick)
        p, R = hc.arm.hand_pose()
        v = w.data.xpos[w.body_id[obj]] + [0, 0, 0.10] - p
        aims.append(float(np.arccos(np.clip(-R[:, 2] @ v / np.linalg.norm(v), -1, 1))))
        assert p[0] <= POINT_X_MAX + 0.02
    _ok(hc.events(), "point")
    assert min(aims) < 0.35                                   # the index finger was aimed at the object
    assert hc.events("clamped") == []                         # pointing never tried to cross the line


@pytest.mark.parametrize("bottle,glass", [
    ({"zone": "RWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}),
    ({"zone": "HWS", "state": "open"}, {"zone": "RWS", "state": "inverted"}),
])
def test_request_holds_out_an_open_palm(bottle, glass):
    w, s, hc = _setup(_arr(bottle, glass))
    hc.start("request", hold=1.0)
    t_end = w.time + 8.0
    palm_up = []
    while w.time < t_end and hc.current is not None:
        hc.run(0.1, robot=s.tick)
        p, R = hc.arm.hand_pose()
        palm_up.append((p[0], R[2, 1], w.qpos("human_r_index_prox")))
    _ok(hc.events(), "request")
    held_out = [(x, up, flex) for x, up, flex in palm_up if -0.20 < x < 0.0 and up > 0.8 and flex < 0.3]
    assert len(held_out) >= 5                                   # in the hand-over zone, palm up, fingers open, for a while
    assert palm_up[-1][0] < held_out[-1][0] - 0.1               # then the hand is lowered back toward the body


# ---------------------------------------------------------------------------- hand-overs with the stand-in
@pytest.mark.parametrize("obj,grip,where", [("bottle", "ag", (-0.22, -0.12)), ("glass", "sg", (-0.28, 0.05))])
def test_hand_to_robot(obj, grip, where):
    other = "glass" if obj == "bottle" else "bottle"
    arr = {obj: {"zone": "HWS", "state": "closed" if obj == "bottle" else "empty", "position": list(where)},
           other: {"zone": "RWS", "state": "open" if other == "bottle" else "empty"}}
    w, s, hc = _setup(Arrangement.from_mapping(arr))
    s.take_when_offered = obj
    hc.start("hand_to_robot", object=obj, grip=grip)
    _ok(_run_until_done(hc, s, 25.0), "hand_to_robot")
    hc.run(2.0, robot=s.tick)
    st = w.state()
    assert st.human_holds is None and s.holds() == obj
    assert st.objects[obj].pos[0] > 0.1                       # the stand-in carried it into the RWS


def test_asked_again_for_what_she_is_handing_over_she_does_not_hand_it_over_twice():
    # the robot asks for the glass a second time while she holds it out: once it has taken the glass, the
    # request queued meanwhile is stale, and she does not reach for the glass in the robot's hand
    arr = {"glass": {"zone": "HWS", "state": "empty", "position": [-0.28, 0.05]}, "bottle": {"zone": "RWS", "state": "open"}}
    w, s, hc = _setup(Arrangement.from_mapping(arr))
    s.take_when_offered = "glass"
    hc.hear("request:glass", w.time)
    while (hc.current is None or hc.current.name != "hand_to_robot") and w.time < 5.0:
        hc.run(0.1, robot=s.tick)
    hc.hear("request:glass", w.time)
    _ok(_run_until_done(hc, s, 25.0, "hand_to_robot"), "hand_to_robot")
    hc.run(6.0, robot=s.tick)
    assert [e.what for e in hc.events("start")] == ["hand_to_robot"]
    assert [e.detail.get("object") for e in hc.events("note") if e.what == "dropped"] == ["glass"]
    assert s.holds() == "glass" and w.state().human_holds is None


@pytest.mark.parametrize("obj,at,glass_zone", [("glass", (0.0, -0.05, 0.78), "RWS"), ("bottle", (-0.02, 0.05, 0.80), "HWS")])
def test_take_from_robot(obj, at, glass_zone):
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": glass_zone, "state": "empty"}))
    s.grasp_at(obj)
    s.release_when_taken = True
    hc.run(0.02, robot=s.tick)
    s.carry_to(at)
    hc.start("take_from_robot", object=obj)
    watch = _HandWatch(w, s)
    hc.run(12.0, robot=watch)
    _ok(hc.events(), "take_from_robot")
    st = w.state()
    assert s.holds() is None and st.objects[obj].pos[0] < -0.15
    if obj == "glass":   # an empty glass is not held for ever: set down upright on her side
        assert st.human_holds is None and st.objects[obj].upright
    else:
        assert st.human_holds == obj
    assert watch.x_max <= HANDOVER_X_MAX                      # the hand stayed in the hand-over zone


def test_handed_the_bottle_with_the_glass_out_of_reach_puts_it_down_on_his_side():
    """He cannot pour into a glass in the robot's workspace: he does not hold the bottle for ever."""
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "RWS", "state": "empty"}))
    s.grasp_at("bottle")
    s.release_when_taken = True
    hc.run(0.02, robot=s.tick)
    s.carry_to((-0.02, 0.05, 0.80))
    hc.start("take_from_robot", object="bottle")
    hc.run(20.0, robot=s.tick)
    done = [(e.what, e.kind) for e in hc.events() if e.kind in ("succeeded", "failed")]
    assert done[:2] == [("take_from_robot", "succeeded"), ("put_down", "succeeded")], done
    st = w.state()
    assert st.human_holds is None and st.objects["bottle"].upright and st.objects["bottle"].pos[0] < 0


@pytest.mark.parametrize("where", [(0.15, -0.05), (0.15, 0.10)])
def test_stopper_pull_succeeds_while_the_robot_holds_the_bottle_out(where):
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed", "position": list(where)}, {"zone": "HWS", "state": "empty"}))
    s.grasp_at("bottle")
    hc.run(0.02, robot=s.tick)
    s.carry_to((-0.06, where[1] * 0.5, layout.TABLE_Z + 0.03))
    hc.run(3.0, robot=s.tick)
    hc.start("pull_stopper")
    _ok(_run_until_done(hc, s, 20.0), "pull_stopper")
    st = w.state()
    assert st.bottle_open and st.objects["stopper"].pos[0] < -0.2 and st.liquid.in_bottle == layout.N_PARTICLES


# ---------------------------------------------------------------------------- the passive profile answers requests
def test_passive_pulls_the_stopper_when_invited():
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed", "position": [0.15, -0.05]}, {"zone": "HWS", "state": "empty"}))
    s.grasp_at("bottle")
    hc.run(0.02, robot=s.tick)
    s.carry_to((-0.06, -0.03, layout.TABLE_Z + 0.03))
    hc.run(3.0, robot=s.tick)
    assert hc.events("start") == []
    t_said = w.time
    hc.hear("invite:remove_stopper", t_said)
    ends = _run_until_done(hc, s, 20.0)
    start = hc.events("start")[0]
    assert start.what == "pull_stopper" and start.t >= t_said + hc.profile.reaction_delay - 1e-6
    _ok(ends, "pull_stopper")
    assert w.state().bottle_open


def test_passive_hands_over_the_object_asked_for_to_the_open_hand():
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}))
    s.place((0.03, -0.05, 0.95))                               # the robot's open hand held out
    s.take_when_offered = "bottle"
    hc.run(2.0, robot=s.tick)
    assert hc.view.requests and hc.events("start") == []       # seeing the open hand alone is no request
    t_said = w.time
    hc.hear("request:bottle", t_said)
    _ok(_run_until_done(hc, s, 25.0), "hand_to_robot")
    assert hc.events("start")[0].t >= t_said + hc.profile.reaction_delay - 1e-6
    assert s.holds() == "bottle" and w.state().human_holds is None


def test_passive_takes_the_object_offered():
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "RWS", "state": "empty"}))
    s.grasp_at("glass")
    s.release_when_taken = True
    hc.run(0.02, robot=s.tick)
    s.carry_to((0.0, -0.05, 0.78))
    hc.run(3.0, robot=s.tick)
    assert hc.view.offers == "glass" and hc.events("start") == []
    hc.hear("offer:glass", w.time)
    _ok(_run_until_done(hc, s, 40.0, "put_down"), "put_down")
    # an empty glass is not held for ever: taken, then set down on her side, to pour into or to be filled
    assert [e.what for e in hc.events("succeeded")] == ["take_from_robot", "put_down"]
    st = w.state()
    assert st.human_holds is None and s.holds() is None
    assert st.objects["glass"].zone == "HWS" and st.objects["glass"].upright


def test_passive_drinks_from_a_full_glass_handed_to_him():
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "RWS", "state": "full"}))
    s.grasp_at("glass")
    s.release_when_taken = True
    hc.run(0.02, robot=s.tick)
    s.carry_to((0.0, -0.05, 0.78), speed=0.15)
    hc.run(3.0, robot=s.tick)
    assert w.state().glass_state == "full"
    hc.hear("offer:glass", w.time)
    _ok(_run_until_done(hc, s, 40.0, "drink"), "drink")
    assert [e.what for e in hc.events("start")] == ["take_from_robot", "drink"]
    assert w.state().liquid.drunk >= DRINK_FRACTION * layout.N_PARTICLES


def test_passive_drinks_when_told_the_glass_is_ready():
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "HWS", "state": "full"}))
    hc.run(2.0, robot=s.tick)
    assert hc.events("start") == []
    hc.hear("suggest:drink", w.time)
    _ok(_run_until_done(hc, s, 25.0), "drink")
    assert w.state().liquid.drunk >= DRINK_FRACTION * layout.N_PARTICLES


def test_told_to_drink_with_the_bottle_in_hand_the_person_puts_it_down_first():
    """The full glass stands on her side and she holds the open bottle: told that the glass is ready,
    she sets the bottle down and drinks (the drink needs the hand)."""
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "open", "position": [-0.22, -0.12]},
                           {"zone": "HWS", "state": "full", "position": [-0.22, 0.12]}))
    hc.start("grasp", object="bottle", grip="sg")
    _ok(_run_until_done(hc, s, 15.0, "grasp"), "grasp")
    assert w.state().human_holds == "bottle"
    hc.hear("suggest:drink", w.time)
    _ok(_run_until_done(hc, s, 40.0, "drink"), "drink")
    assert [e.what for e in hc.events("start")] == ["grasp", "put_down", "drink"]
    st = w.state()
    assert st.objects["bottle"].upright and st.objects["bottle"].pos[0] < 0
    assert st.liquid.drunk >= DRINK_FRACTION * layout.N_PARTICLES


def test_invited_to_pull_the_stopper_while_handing_the_glass_over_she_sets_the_glass_down_first():
    """Holding the glass out to the robot (which does not take it: the stand-in holds the bottle out
    instead, too far aside for the hand-over), she is invited to remove the stopper: once the hand-over
    ends, the glass goes down upright on her side before she turns to the stopper; it does not fall from
    her opened hand. (Whether she then reaches the stopper held out there is not this test's.)"""
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed", "position": [0.15, -0.05]}, {"zone": "HWS", "state": "empty"}))
    hc.start("hand_to_robot", object="glass", grip="ag", timeout=6.0)
    hc.run(4.5, robot=s.tick)
    assert w.state().human_holds == "glass"
    s.grasp_at("bottle")
    hc.run(0.02, robot=s.tick)
    s.carry_to((-0.07, 0.26, layout.TABLE_Z + 0.03))     # held out away from the glass she holds out
    hc.hear("invite:remove_stopper", w.time)
    _run_until_done(hc, s, 60.0, "pull_stopper")
    assert [e.what for e in hc.events("start")] == ["hand_to_robot", "put_down", "pull_stopper"]
    assert [e.what for e in hc.events("succeeded")][:1] == ["put_down"]
    st = w.state()
    assert st.objects["glass"].upright and st.objects["glass"].zone == "HWS" and st.objects["glass"].held_by is None


# ---------------------------------------------------------------------------- scripts wait for their events
def test_script_steps_wait_for_after_events():
    script = [
        {"do": "pull_stopper", "after": {"robot_holds": "bottle"}},
        {"do": "request", "hold": 0.5, "after": {"robot_said": "inform:fill_glass"}},
    ]
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed", "position": [0.15, 0.10]}, {"zone": "RWS", "state": "empty"}),
                      profile="active", script=script)
    hc.run(2.0, robot=s.tick)
    assert hc.events("start") == []                           # nothing held yet: the first step waits
    s.grasp_at("bottle")
    t_hold = w.time
    s.carry_to((-0.06, -0.03, layout.TABLE_Z + 0.03))
    _ok(_run_until_done(hc, s, 20.0, "pull_stopper"), "pull_stopper")
    assert hc.events("start")[0].t >= t_hold + hc.profile.reaction_delay - 1e-6
    hc.run(2.0, robot=s.tick)
    assert [e.what for e in hc.events("start")] == ["pull_stopper"]   # the second step waits for its words
    t_said = w.time
    hc.hear("inform:fill_glass", t_said)
    _ok(_run_until_done(hc, s, 10.0, "request"), "request")
    assert hc.events("start")[1].t >= t_said + hc.profile.reaction_delay - 1e-6


# ---------------------------------------------------------------------------- the middle line and the slow profile
def test_a_request_toward_an_object_deep_in_the_rws_stops_at_the_line():
    """A script asks the hand to put something down in the RWS: the parser refuses it; a hold-out
    toward a robot far away is clamped and logged, and the fingers never cross the hand-over zone."""
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}))
    s.place((0.30, -0.05, 0.95))
    hc.start("grasp", object="bottle", grip="ag", hold_out=True)
    watch = _HandWatch(w, s)
    hc.run(6.0, robot=watch)
    hc.arm.move_to((0.30, -0.05, 0.95), t=w.time)              # reach on toward the robot's hand
    hc.run(3.0, robot=watch)
    assert hc.events("clamped") and hc.events("clamped")[-1].detail["target"][0] == pytest.approx(0.30)
    assert watch.x_max <= HANDOVER_X_MAX


def test_slow_profile_is_two_to_three_times_slower():
    times = {}
    for profile in ("active", "slow"):
        w = build_world(Arrangement.from_options("HWS:closed", "RWS:inverted"), seed=0)
        hc = HumanController(w, profile=profile, seed=2)
        hc.run(25.0)
        ends = [e for e in hc.events() if e.kind in ("succeeded", "failed") and e.what == "grasp"]
        assert ends and ends[0].kind == "succeeded"
        times[profile] = ends[0].t - hc.events("start")[0].t
    assert 2.0 <= times["slow"] / times["active"] <= 3.5, times


def test_active_wrong_grip_then_corrected_after_the_robots_error():
    """The default policy's seeded wrong grip (here certain): side grip held out; told that the robot
    cannot open it so, the active partner puts the bottle down and hands it over from above."""
    w = build_world_with_standin(Arrangement.from_options("HWS:closed", "RWS:inverted"), seed=0)
    s = StandIn(w)
    hc = HumanController(w, profile=PROFILES["active"].with_(wrong_grip=1.0), seed=0, see=s.view)
    hc.run(6.0, robot=s.tick)
    first = hc.events("start")[0]
    assert first.what == "grasp" and first.detail["grip"] == "sg" and hc.events("note")[0].what == "wrong_grip"
    assert w.state().human_holds == "bottle"
    hc.hear("error:cannot_remove_stopper", w.time)
    s.take_when_offered = "bottle"
    _ok(_run_until_done(hc, s, 20.0, "hand_to_robot"), "hand_to_robot")
    starts = [(e.what, e.detail.get("grip")) for e in hc.events("start")]
    assert starts[:3] == [("grasp", "sg"), ("put_down", None), ("hand_to_robot", "ag")]
    assert s.holds() == "bottle" and w.state().human_holds is None


def test_drink_does_not_count_with_a_glass_that_is_not_full():
    """A few particles in the glass (the rest spilled on the table): drinking them is no drink."""
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "open"}, {"zone": "HWS", "state": "full"}))
    qa = w.particle_qadr[: layout.N_PARTICLES // 2]
    for i, a in enumerate(qa):                                # half the liquid on the table, out of the glass
        w.data.qpos[a:a + 3] = (-0.05 - 0.013 * (i % 10), -0.30 - 0.013 * (i // 10), layout.TABLE_Z + layout.PARTICLE_RADIUS)
    w.step(1)
    st = w.state()
    assert st.glass_state == "empty" and 0 < st.liquid.in_glass < 0.6 * layout.N_PARTICLES
    hc.start("drink")
    ends = _run_until_done(hc, s, 25.0)
    assert ends[-1].what == "drink" and ends[-1].kind == "failed" and "not full" in ends[-1].detail["reason"]
    assert w.state().liquid.drunk > 0                         # the particles did reach the mouth: not counted as a drink


# ---------------------------------------------------------------------------- the grip gives way
@pytest.mark.parametrize("pull, yields", [(8.0, False), (35.0, True)])
def test_the_persons_grip_holds_a_light_pull_and_gives_way_to_a_strong_one(pull, yields):
    """A tug of war cannot last: a pull on what the person holds beyond HUMAN_GRIP_YIELD_FORCE frees it."""
    from assistbot.world.world import HUMAN_GRIP_YIELD_FORCE

    assert 8.0 < HUMAN_GRIP_YIELD_FORCE < 35.0
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed"}, {"zone": "HWS", "state": "empty"}))
    hc.start("grasp", object="glass", grip="sg", lift=True)
    _ok(_run_until_done(hc, s, 12.0, "grasp"), "grasp")
    assert w.human_holding() == "glass"
    g = w.body_id["glass"]
    w.data.xfrc_applied[g, 0] = pull           # toward the robot, as a hand taking it would pull
    hc.run(1.0, robot=s.tick)
    w.data.xfrc_applied[g, 0] = 0.0
    assert (w.human_holding() is None) == yields
    assert bool(w.grip_yields) == yields and (not yields or w.grip_yields[0][1] == "glass")


# ---------------------------------------------------------------------------- pour
@pytest.mark.parametrize("bottle, glass", [((-0.22, -0.12), (-0.22, 0.12)), ((-0.18, 0.15), (-0.22, -0.12))])
def test_pour_fills_the_glass_on_this_side_and_puts_the_bottle_back(bottle, glass):
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "open", "position": list(bottle)},
                           {"zone": "HWS", "state": "empty", "position": list(glass)}))
    hc.start("pour")
    _ok(_run_until_done(hc, s, 40.0, "pour"), "pour")
    st = w.state()
    assert st.glass_state == "full" and st.liquid.spilled <= 0.1 * st.liquid.total, st.summary()
    b = w.data.xpos[w.body_id["bottle"]]
    assert np.hypot(b[0] - bottle[0], b[1] - bottle[1]) < 0.05 and w.data.xmat[w.body_id["bottle"]][8] > 0.99
    assert st.human_holds is None


@pytest.mark.parametrize("glass", [(-0.06, 0.12), (-0.06, 0.0)])
def test_a_person_who_cannot_hold_the_mouth_over_the_glass_does_not_pour_beside_it(glass):
    """The glass at the middle line, at the edge of the person's reach: the arm gets the hand near its pose,
    but the bottle's mouth stays off the glass; the person stops tilting before the liquid runs."""
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "open", "position": [-0.22, -0.12]},
                           {"zone": "HWS", "state": "empty", "position": list(glass)}))
    hc.start("pour")
    ends = _run_until_done(hc, s, 40.0, "pour")
    assert ends[-1].kind == "failed" and ends[-1].detail["reason"] == "could not hold the bottle over the glass", ends
    st = w.state()
    assert st.liquid.in_bottle >= 0.95 * st.liquid.total, st.summary()
    assert w.data.xmat[w.body_id["bottle"]][8] > 0.99 and st.human_holds is None


def test_an_active_person_pours_when_both_are_on_their_side_and_a_closed_bottle_cannot():
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "open"}, {"zone": "HWS", "state": "empty"}), profile="active")
    hc.run(1.0, robot=s.tick)
    assert hc.events("start")[0].what == "pour"
    w2, s2, hc2 = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "HWS", "state": "empty"}))
    hc2.start("pour")
    assert _run_until_done(hc2, s2, 2.0, "pour")[-1].kind == "failed"


def test_the_hold_out_habit_is_checked_against_the_region():
    from assistbot.errors import UserError

    cfg = parse_human({"profile": "passive", "hold_out_dx": -0.08, "hold_out_dz": 0.06})
    assert cfg.profile_params().hold_out_offset == (-0.08, 0.0, 0.06)
    for key, value in (("hold_out_dx", 0.09), ("hold_out_dz", -0.07), ("hold_out_dy", "far")):
        with pytest.raises(UserError) as e:
            parse_human({"profile": "active", key: value})
        assert e.value.key == f"human.{key}"


@pytest.mark.slow
@pytest.mark.parametrize("bottle, glass, fills", [((-0.18, 0.15), (-0.22, -0.12), True),
                                                  ((-0.22, -0.12), (-0.22, 0.12), False)])
def test_a_person_pours_from_above_where_their_arm_can_tip_the_bottle_and_spills_nothing_where_it_cannot(bottle, glass, fills):
    """From above, the arm tips the bottle far enough only from some places beside the glass: with the glass in
    front of the right shoulder the glass fills, and no slower than from the side (the bottle tips over the
    glass as the way was planned, not carried up over it at each step); with the glass on the left (the HWS's
    usual places) the person gives up before the liquid runs."""
    arrangement = _arr({"zone": "HWS", "state": "open", "position": list(bottle)},
                       {"zone": "HWS", "state": "empty", "position": list(glass)})
    w, s, hc = _setup(arrangement)
    hc.start("pour", grip="ag")
    ends = _run_until_done(hc, s, 45.0, "pour")
    st = w.state()
    if fills:
        _ok(ends, "pour")
        assert st.glass_state == "full" and st.liquid.spilled <= 0.1 * st.liquid.total, st.summary()
        w_side, s_side, hc_side = _setup(arrangement)
        hc_side.start("pour", grip="sg")
        _ok(_run_until_done(hc_side, s_side, 45.0, "pour"), "pour")
        assert w.time <= w_side.time + 1.0, (w.time, w_side.time)
    else:
        assert ends[-1].kind == "failed" and ends[-1].detail["reason"] == "could not hold the bottle over the glass", ends
        assert st.liquid.in_bottle >= 0.95 * st.liquid.total, st.summary()
    assert w.data.xmat[w.body_id["bottle"]][8] > 0.99 and st.human_holds is None


def test_asked_to_set_it_down_with_an_empty_hand_she_fetches_what_she_was_handing_over():
    # a hand-over of hers that failed (the robot could not take the glass from her hand) left the glass on
    # her side; the robot then shows a spot and asks her to set "it" down there: she fetches the glass
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed"}, {"zone": "HWS", "state": "empty"}))
    hc.policy_state["offered"] = "glass"          # as `hand_to_robot` leaves it
    spot = (-0.06, 0.0)
    s.place((spot[0], spot[1], layout.TABLE_Z + 0.30))      # the robot's open hand held above the spot
    hc.run(1.0, robot=s.tick)
    assert hc.events("start") == []                  # the sight alone is no request
    hc.hear("request:put_down_here", w.time)
    _ok(_run_until_done(hc, s, 40.0, "put_down_for_robot"), "put_down_for_robot")
    assert [e.what for e in hc.events("start")] == ["grasp", "put_down_for_robot"]
    g = w.data.xpos[w.body_id["glass"]]
    assert w.state().human_holds is None and w.state().objects["glass"].upright
    assert np.hypot(g[0] - spot[0], g[1] - spot[1]) < 0.05, g


def test_asked_to_set_it_down_while_she_puts_it_down_on_her_side_she_picks_it_up_again():
    # her hand-over failed and she is putting the bottle down on her side when the robot shows a spot and asks
    # her to set "it" down there: asked with the bottle in hand, she answers once it stands on her side, by
    # picking it up again and setting it down there
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}))
    hc.start("grasp", object="bottle", grip="ag")
    _ok(_run_until_done(hc, s, 20.0, "grasp"), "grasp")
    hc.policy_state["offered"] = "bottle"          # as `hand_to_robot` leaves it
    hc.start("put_down", object="bottle")
    hc.run(0.05, robot=s.tick)
    spot = (-0.06, 0.0)
    s.place((spot[0], spot[1], layout.TABLE_Z + 0.30))      # the robot's open hand held above the spot
    hc.hear("request:put_down_here", w.time)      # heard while the bottle is still in her hand
    _ok(_run_until_done(hc, s, 60.0, "put_down_for_robot"), "put_down_for_robot")
    assert [e.what for e in hc.events("start")] == ["grasp", "put_down", "put_down_for_robot"]
    b = w.data.xpos[w.body_id["bottle"]]
    assert w.state().human_holds is None and w.state().objects["bottle"].upright
    assert np.hypot(b[0] - spot[0], b[1] - spot[1]) < 0.05, b


def test_what_she_set_down_for_the_robot_she_leaves_to_it():
    # an active person asked to set the closed bottle down under the robot's hand does so and then leaves it
    # there for the robot to take: her own initiative (hold the closed bottle out to have it opened) would
    # snatch it from under the hand closing on it, and the robot lifting it there looks like one offering it
    w, s, hc = _setup(_arr({"zone": "HWS", "state": "closed"}, {"zone": "RWS", "state": "empty"}), profile="active")
    hc.start("grasp", object="bottle", grip="ag")      # in her hand without her initiative: asked for it, say
    _ok(_run_until_done(hc, s, 20.0, "grasp"), "grasp")
    spot = (-0.06, 0.0)
    s.place((spot[0], spot[1], layout.TABLE_Z + 0.30))      # the robot's open hand held above the spot
    hc.hear("request:put_down_here", w.time)
    _ok(_run_until_done(hc, s, 40.0, "put_down_for_robot"), "put_down_for_robot")
    hc.run(4.0, robot=s.tick)
    s.grasp_at("bottle")
    s.move(s.pos + [0.0, 0.0, 0.08], duration=1.0)       # taken up where she set it down
    hc.run(6.0, robot=s.tick)
    assert s.view().offers == "bottle"
    starts = [(e.what, e.detail.get("object")) for e in hc.events("start")]
    assert starts[:2] == [("grasp", "bottle"), ("put_down_for_robot", None)], starts
    assert not [b for b in starts[2:] if b[1] == "bottle"], starts        # (asking for the glass is hers to do)
    assert w.state().human_holds is None


def test_a_remark_of_the_robot_does_not_break_off_what_she_does_at_its_request():
    # asked to set "it" down under the robot's hand, she first fetches the glass: the robot remarking on what
    # it sees meanwhile (a remark, asking nothing) leaves the fetch and the setting down to go on
    w, s, hc = _setup(_arr({"zone": "RWS", "state": "closed"}, {"zone": "HWS", "state": "empty"}))
    hc.policy_state["offered"] = "glass"          # as `hand_to_robot` leaves it
    spot = (-0.06, 0.0)
    s.place((spot[0], spot[1], layout.TABLE_Z + 0.30))      # the robot's open hand held above the spot
    hc.hear("request:put_down_here", w.time)
    while hc.current is None and w.time < 5.0:
        hc.run(0.1, robot=s.tick)
    assert hc.current is not None and hc.current.name == "grasp"
    hc.hear("understood:request", w.time)
    _ok(_run_until_done(hc, s, 40.0, "put_down_for_robot"), "put_down_for_robot")
    assert [e.what for e in hc.events("start")] == ["grasp", "put_down_for_robot"]
    assert not hc.events("failed")
