"""The partner population (human.population, human.body): a seed gives one person, built in the physics with
their own body, who reaches their own hold-out point, trembles at their own frequency and, weak, lets a
lifted object fall."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from assistbot.errors import UserError
from assistbot.human import behaviours
from assistbot.human.arm import DEFAULT_REACH, DEFAULT_SHOULDER, FINGER_REACH, HANDOVER_X_MAX, TREMOR_DIRECTION, HumanArm
from assistbot.human.controller import HumanController
from assistbot.human.ikmodel import arm_model
from assistbot.human.population import LIMITS, Body, Partner, sample_partner
from assistbot.human.profiles import PROFILES
from assistbot.human.script import parse_human
from assistbot.world import Arrangement, build_world

#: the smallest and the largest body the population draws, seated farthest back and aside
SMALLEST = Body(upper_arm=LIMITS["upper_arm"][0], forearm=LIMITS["forearm"][0], shoulder_height=LIMITS["shoulder_height"][0],
                seat_back=LIMITS["seat_back"][1], seat_side=LIMITS["seat_side"][0], rom=LIMITS["rom"][1])
LARGEST = Body(upper_arm=LIMITS["upper_arm"][1], forearm=LIMITS["forearm"][1], shoulder_height=LIMITS["shoulder_height"][1],
               seat_back=0.0, seat_side=LIMITS["seat_side"][1])


def test_the_same_seed_gives_the_same_partner_and_every_attribute_lies_in_its_range():
    assert sample_partner(7) == sample_partner(7)
    drawn = [sample_partner(s) for s in range(300)]
    assert len({p.body for p in drawn}) == 300
    for p in drawn:
        for k, v in p.to_dict().items():
            if k in LIMITS:
                lo, hi = LIMITS[k]
                assert lo - 1e-9 <= v <= hi + 1e-9, (p.seed, k, v)
    # the impairments occur, and not in everyone
    for k in ("tremor_amplitude", "drop_chance", "hesitation"):
        share = np.mean([getattr(p, k) > 0 for p in drawn])
        assert 0.15 < share < 0.6, (k, share)
    assert 0.15 < np.mean([p.body.rom > 0 for p in drawn]) < 0.6


def test_a_partner_is_built_in_the_physics_with_the_same_arm_as_the_one_it_plans_with():
    body = Body(upper_arm=1.1, forearm=0.9, shoulder_height=0.92, seat_back=0.05, seat_side=-0.04, rom=0.2)
    w = build_world(Arrangement.from_options("HWS:open", "RWS:empty"), body=body)
    m, d = w.model, w.data
    mujoco.mj_forward(m, d)
    default = build_world(Arrangement.from_options("HWS:open", "RWS:empty"))
    mujoco.mj_forward(default.model, default.data)

    def seg(model, data, a, b):
        return float(np.linalg.norm(data.xpos[model.body(b).id] - data.xpos[model.body(a).id]))

    assert seg(m, d, "human_r_upper_arm", "human_r_forearm") == pytest.approx(
        1.1 * seg(default.model, default.data, "human_r_upper_arm", "human_r_forearm"))
    assert seg(m, d, "human_r_forearm", "human_r_hand") == pytest.approx(
        0.9 * seg(default.model, default.data, "human_r_forearm", "human_r_hand"))
    shoulder = d.xpos[m.body("human_r_upper_arm").id]
    assert shoulder[:2] == pytest.approx(DEFAULT_SHOULDER[:2] + np.array([-0.05, -0.04]))
    assert shoulder[2] < DEFAULT_SHOULDER[2] - 0.03                      # sits lower
    # the mouth moved with the shoulders; the table and the robot's workspace did not
    assert d.site_xpos[m.site("human_mouth").id][2] == pytest.approx(
        default.data.site_xpos[default.model.site("human_mouth").id][2] + shoulder[2] - DEFAULT_SHOULDER[2])
    assert d.xpos[w.body_id["glass"]] == pytest.approx(default.data.xpos[default.body_id["glass"]])
    # the bottle in the person's workspace stands at this person's own place for it: back and aside with them
    bottle = d.xpos[w.body_id["bottle"]][:2] - default.data.xpos[default.body_id["bottle"]][:2]
    assert bottle[0] < -0.04 and bottle[1] < -0.02
    # the IK model is the same arm
    arm = HumanArm(w)
    assert arm.shoulder == pytest.approx(shoulder)
    ik = arm_model(body)
    for j in ("human_r_elbow", "human_r_shoulder_flex"):
        assert ik.joint(j).range == pytest.approx(m.joint(j).range)
        assert m.jnt_range[m.joint(j).id][1] - m.jnt_range[m.joint(j).id][0] < (
            default.model.jnt_range[default.model.joint(j).id][1] - default.model.jnt_range[default.model.joint(j).id][0])
    # the joints that orient the hand for a grip keep their range
    assert m.joint("human_r_forearm_rot").range == pytest.approx(default.model.joint("human_r_forearm_rot").range)
    # the default body changes nothing
    assert HumanArm(default).reach == pytest.approx(DEFAULT_REACH)


def _grasps(world, body, obj: str, grip: str) -> bool:
    hc = HumanController(world, config=parse_human({"profile": "passive", "partner": Partner(body=body).to_dict()}))
    hc.start("grasp", object=obj, grip=grip)
    t_end = world.time + 15.0
    while hc.current is not None and world.time < t_end:
        hc.run(0.2)
    ends = [e for e in hc.events() if e.kind in ("succeeded", "failed")]
    return bool(ends) and ends[-1].kind == "succeeded" and world.human_holding() == obj


def test_objects_in_the_persons_workspace_stand_within_their_reach():
    """At the default person's place the glass is out of the smallest partner's reach (seated farthest back
    and aside); "in the HWS" puts it at that partner's own place for it, which they reach."""
    from assistbot import catalogue

    default_place = catalogue.BY_NAME["glass"].places["HWS"]
    there = build_world(Arrangement.from_options("RWS:closed", f"HWS:full@{default_place[0]},{default_place[1]}"), body=SMALLEST)
    assert not _grasps(there, SMALLEST, "glass", "sg")
    own = build_world(Arrangement.from_options("RWS:closed", "HWS:full"), body=SMALLEST)
    assert np.linalg.norm(np.array(own.arrangement.position("glass")) - default_place) > 0.05
    assert _grasps(own, SMALLEST, "glass", "sg")
    assert build_world(Arrangement.from_options("RWS:closed", "HWS:full")).arrangement.position("glass") == default_place


@pytest.mark.parametrize("who", [SMALLEST, LARGEST, sample_partner(2).body, sample_partner(4).body],
                         ids=["smallest", "largest", "p2", "p4"])
def test_a_partner_picks_up_the_bottle_and_holds_it_out_at_their_own_hold_out_point(who):
    w = build_world(Arrangement.from_options("HWS:open", "RWS:empty"), body=who)
    hc = HumanController(w, config=parse_human({"profile": "passive", "partner": Partner(body=who).to_dict()}))
    hc.start("grasp", object="bottle", grip="sg", hold_out=True)
    t_end = w.time + 20.0
    while hc.current is not None and w.time < t_end:
        hc.run(0.2)
    ends = [e for e in hc.events() if e.kind in ("succeeded", "failed")]
    assert ends and ends[-1].kind == "succeeded", ends
    assert w.human_holding() == "bottle"
    hand = hc.arm.hand_pose()[0]
    goal = behaviours.hold_out_point(hc)
    # short of the middle line: the hand-over zone ends there for every body
    assert np.linalg.norm(hand[:2] - [min(goal[0], HANDOVER_X_MAX - FINGER_REACH), goal[1]]) < 0.03, (hand, goal)
    # held out where this body holds things: in proportion to its reach from its own shoulder
    assert np.linalg.norm(goal - hc.arm.shoulder) == pytest.approx(
        np.linalg.norm(behaviours.HOLD_OUT - DEFAULT_SHOULDER) * hc.arm.reach / DEFAULT_REACH)


@pytest.mark.parametrize("frequency", [5.0, 8.0])
def test_a_tremor_moves_the_hand_at_its_frequency_by_its_amplitude(frequency):
    # 5 Hz lies at the arm servos' resonance (commanded as drawn, the hand moved 3.4 times as far), 8 Hz above it
    w = build_world(Arrangement.from_options("HWS:open", "RWS:empty"))
    hc = HumanController(w, profile=PROFILES["passive"].with_(tremor_amplitude=0.01, tremor_frequency=frequency))
    hc.run(2.0)
    path, times = [], []
    for _ in range(200):                                     # 4 s, 50 samples a second
        hc.run(hc.dt)
        path.append(hc.arm.hand_pose()[0])
        times.append(w.data.time)
    along = np.asarray(path) @ (TREMOR_DIRECTION / np.linalg.norm(TREMOR_DIRECTION))
    along -= np.mean(along)
    spectrum = np.abs(np.fft.rfft(along * np.hanning(len(along))))
    freqs = np.fft.rfftfreq(len(along), hc.dt)
    assert freqs[np.argmax(spectrum)] == pytest.approx(frequency, abs=0.3)
    phase = 2 * np.pi * frequency * np.asarray(times)
    amplitude = np.hypot(2 * np.mean(along * np.sin(phase)), 2 * np.mean(along * np.cos(phase)))
    assert amplitude == pytest.approx(0.01, rel=0.15)
    still = HumanController(build_world(Arrangement.from_options("HWS:open", "RWS:empty")), profile="passive")
    still.run(1.0)
    p0 = still.arm.hand_pose()[0]
    still.run(1.0)
    assert np.linalg.norm(still.arm.hand_pose()[0] - p0) < 1e-3


def test_a_weak_partner_lets_go_of_a_lifted_object_and_it_falls_in_the_physics():
    w = build_world(Arrangement.from_options("HWS:open", "RWS:empty"))
    hc = HumanController(w, profile=PROFILES["passive"].with_(drop_chance=1.0))
    bottle = w.body_id["bottle"]
    z0 = float(w.data.xpos[bottle][2])
    hc.start("grasp", object="bottle", grip="sg")
    highest = z0
    while hc.current is not None and w.time < 20.0:
        hc.run(0.02)
        highest = max(highest, float(w.data.xpos[bottle][2]))
    hc.run(1.5)
    ends = [e for e in hc.events() if e.kind in ("succeeded", "failed")]
    assert ends[-1].kind == "failed" and "let go" in ends[-1].detail.get("reason", str(ends[-1])), ends
    assert highest > z0 + 0.04                               # it was lifted
    assert w.human_holding() is None
    assert float(w.data.xpos[bottle][2]) < z0 + 0.01         # and fell back onto the table
    assert any(e.what == "dropped" for e in hc.events("note"))


def test_a_scenario_names_a_partner_by_seed_or_by_attributes_and_mistakes_name_the_key():
    hc = parse_human({"profile": "slow", "partner": 5})
    assert hc.partner == sample_partner(5)
    prof = hc.profile_params()
    assert prof.speed == pytest.approx(PROFILES["slow"].speed * sample_partner(5).speed_factor)
    # the scenario's own parameters override what the partner changes
    assert parse_human({"profile": "slow", "partner": 5, "speed": 0.1}).profile_params().speed == 0.1
    own = parse_human({"partner": {"seed": 5, "tremor_amplitude": 0.01}}).partner
    assert own.tremor_amplitude == 0.01 and own.body == sample_partner(5).body
    for bad, key in (({"partner": -1}, "human.partner"), ({"partner": "tall"}, "human.partner"),
                     ({"partner": {"height": 2}}, "human.partner.height"), ({"partner": {"upper_arm": 2.0}}, "human.partner.upper_arm"),
                     ({"tremor_amplitude": 0.5}, "human.tremor_amplitude")):
        with pytest.raises(UserError) as e:
            parse_human(bad, "s.yaml")
        assert e.value.key == key, (bad, e.value)


def test_the_partners_command_writes_a_contact_sheet_and_their_attributes(tmp_path, capsys):
    import csv

    import imageio.v3 as iio

    from assistbot.cli import main

    assert main(["partners", "--n", "2", "--first", "40", "--size", "160x120", "--out", str(tmp_path)]) == 0
    sheet = iio.imread(tmp_path / "partners.png")
    assert sheet.shape == (120, 320, 3) and sheet.std() > 10
    rows = list(csv.DictReader(open(tmp_path / "partners.csv")))
    assert [int(r["seed"]) for r in rows] == [40, 41]
    assert float(rows[0]["upper_arm"]) == sample_partner(40).body.upper_arm
    assert main(["partners", "--n", "0", "--out", str(tmp_path)]) == 2
    assert "--n" in capsys.readouterr().err


def test_a_grip_convention_is_a_scenario_key_and_a_partner_attribute_and_mistakes_name_the_key():
    """The swapped convention hands over from the side and pours from above; the seed's, the other way round."""
    seed = parse_human({"profile": "active"}).profile_params()
    assert (seed.grip, seed.pour_grip) == ("ag", "sg")
    swapped = parse_human({"profile": "active", "grip_convention": "swapped"}).profile_params()
    assert (swapped.grip, swapped.pour_grip) == ("sg", "ag")
    by_partner = parse_human({"profile": "passive", "partner": {"seed": 3, "grip_convention": "swapped"}})
    assert by_partner.partner.body == sample_partner(3).body
    assert (by_partner.profile_params().grip, by_partner.profile_params().pour_grip) == ("sg", "ag")
    # an explicit hand-over grip still overrides what the convention sets
    assert parse_human({"grip_convention": "swapped", "grip": "ag"}).profile_params().grip == "ag"
    for bad, key in (({"grip_convention": "mirror"}, "human.grip_convention"),
                     ({"partner": {"grip_convention": 1}}, "human.partner.grip_convention")):
        with pytest.raises(UserError) as e:
            parse_human(bad, "s.yaml")
        assert e.value.key == key and "seed, swapped" in e.value.message, (bad, e.value)
