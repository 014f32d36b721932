"""Vision and the partner population: scenes of other people, a library built from some of them, and
scoring on people it was not built from (issue 24, item 2)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from assistbot.cli import main
from assistbot.human.arm import own_point, shoulder_and_reach
from assistbot.human.behaviours import HOLD_OUT
from assistbot.human.ikmodel import arm_model
from assistbot.human.population import LIBRARY_SEEDS, UNSEEN_FROM, sample_partner
from assistbot.vision.evaluate import run as evaluate
from assistbot.vision.scenes import POSE_TOLERANCE, SceneSampler, pose
from assistbot.world import PAPER_ARRANGEMENTS, build_world
from assistbot.world.arrangement import Arrangement, Placement
from assistbot.world.layout import TABLE_Z

#: a partner seated back and aside with arms of another length than the default person's
PARTNER = 1082


def _request_scene(partner):
    spec = SceneSampler(5, "test").sample("open_palm_request")
    return dataclasses.replace(spec, jitter=(0.0, 0.0, 0.0), partner=partner)


def test_a_scene_of_a_partner_shows_their_body_holding_the_open_hand_out_at_their_own_point():
    p = sample_partner(PARTNER)
    world = build_world(PAPER_ARRANGEMENTS["fig3"], 0, body=p.body)
    lab = pose(world, _request_scene(PARTNER))
    shoulder, reach = shoulder_and_reach(arm_model(p.body))
    own = own_point(HOLD_OUT + np.array([p.hold_out_dx, p.hold_out_dy, p.hold_out_dz]), shoulder, reach)
    hand = np.array(lab.hand_position) + np.array([0.0, 0.0, TABLE_Z])
    assert lab.pose_miss <= POSE_TOLERANCE
    assert np.linalg.norm(hand - own) < 0.01
    # the default person's scene, the same spec: the hand where the behaviours name it, elsewhere than hers
    default = pose(build_world(PAPER_ARRANGEMENTS["fig3"], 0), _request_scene(None))
    d_hand = np.array(default.hand_position) + np.array([0.0, 0.0, TABLE_Z])
    assert np.linalg.norm(d_hand - HOLD_OUT) < 0.01
    assert np.linalg.norm(hand - d_hand) > 0.03


def test_an_object_out_of_a_bodys_reach_is_not_posed_as_grasped():
    """A grasp of an object near the middle line: the default person reaches it; the posed hand of a
    short-armed partner seated far back stays off it, and the scene says so (it is then not scored)."""
    small = min((sample_partner(s) for s in range(UNSEEN_FROM, UNSEEN_FROM + 100)),
                key=lambda q: q.body.upper_arm + q.body.forearm - 4 * q.body.seat_back)
    spec = SceneSampler(5, "test").sample("grasp_sg")
    far = Arrangement(bottle=Placement("RWS", "closed"), glass=Placement("HWS", "empty", (-0.05, 0.10))).validate()
    spec = dataclasses.replace(spec, arrangement=far, target="glass", variant="table", partner=small.seed)
    assert pose(build_world(PAPER_ARRANGEMENTS["fig3"], 0), dataclasses.replace(spec, partner=None)).pose_miss <= POSE_TOLERANCE
    assert pose(build_world(PAPER_ARRANGEMENTS["fig3"], 0, body=small.body), spec).pose_miss > POSE_TOLERANCE


def test_a_population_library_is_built_from_the_default_person_and_library_seeds_only():
    s = SceneSampler(0, "library", LIBRARY_SEEDS, default_share=0.5)
    people = [s.sample().partner for _ in range(400)]
    drawn = [p for p in people if p is not None]
    assert all(p in LIBRARY_SEEDS and p < UNSEEN_FROM for p in drawn)
    assert 0.4 < 1 - len(drawn) / len(people) < 0.6
    assert len(set(drawn)) > 150
    # without partners: the default person only, and the same scenes as before partners existed
    a, b = SceneSampler(3, "bench"), SceneSampler(3, "bench", None)
    assert all(x == y and x.partner is None for x, y in ((a.sample(), b.sample()) for _ in range(20)))


def test_scoring_on_unseen_partners_shows_several_people_and_scores_what_they_can_pose():
    score = evaluate(16, seed=2, purpose="test", partners=range(UNSEEN_FROM, UNSEEN_FROM + 3))
    assert 2 <= score.people <= 3
    assert score.frames + score.unposable == 16
    assert len(score.truth["hand"]) + score.unseen["hand"] <= score.frames


@pytest.mark.parametrize("value", ["5", "9:3", "a:b"])
def test_templates_partners_must_be_a_seed_range_or_none(value, tmp_path, capsys):
    assert main(["templates", "--scenes", "12", "--partners", value, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--partners" in err[0] and "A:B" in err[0]
    assert not any(tmp_path.iterdir())

