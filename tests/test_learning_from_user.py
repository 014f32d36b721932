"""Learning from the user (`assistbot.cognition.learning`): the grip-to-chain weights move after a success, toward
the chain the person's act turned out to be, and only then; the seed's experiments keep their decisions while the
robot learns from the default person; weights persist in a file, and a bad one is one line and exit status 2."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from _scenarios import TINY
from assistbot import cli, task
from assistbot.cognition import Cognition
from assistbot.cognition.learning import LEARNING_RATE, read_weights
from assistbot.cognition.replay import replay
from assistbot.cognition.timeline import load_timeline, timeline_from_dict
from assistbot.errors import UserError

TIMELINES = Path(__file__).resolve().parents[1] / "scenarios" / "timelines"
POUR_ABOVE = TIMELINES / "pour_above_grip.yaml"
POUR_CHAIN = "Reach-grasp-SG-open-bottle-to-pour"
OPEN_HAND_OVER = "Reach-grasp-AG-open-bottle-to-hand-over"
CLOSED_HAND_OVER = "Reach-grasp-AG-closed-bottle-to-hand-over"


def decided(rep) -> list[str]:
    return [a for _, kind, a in rep.agent.decisions() if kind == "decide"]


def weights(path: Path) -> dict:
    return read_weights(path)[0]["OL->ASL"]


def test_without_learning_nothing_is_learnt_and_the_priors_stay():
    cog = Cognition()
    assert not cog.learns and cog.learned_weights() == {} and "GRIP" not in cog.net.spec.fields
    prior = cog.net.table("OL->ASL")
    rep = replay(load_timeline(POUR_ABOVE), record=False)
    assert np.array_equal(rep.agent.net.table("OL->ASL"), prior)


def test_an_above_grip_that_pours_is_misread_then_read_right_after_one_success(tmp_path):
    """The seed's priors read an above grip on the open bottle as a hand-over: the robot decides to receive it.
    The pour seen while a pour is read, and the glass filled (a sub-goal reached), open SUCCESS; the next time the
    robot answers the grip by waiting."""
    path = tmp_path / "weights.json"
    tl = load_timeline(POUR_ABOVE)
    first = replay(tl, record=False, learn=path)
    assert decided(first) == ["Receive-object"]
    w = weights(path)
    assert w[POUR_CHAIN]["grasp_ag_bottle"] > 0.95                    # 0 in the priors
    assert w[OPEN_HAND_OVER]["grasp_ag_bottle"] == pytest.approx(0.5)  # 1 in the priors: read, given up; half kept
    assert w[CLOSED_HAND_OVER]["grasp_ag_bottle"] == 1.0               # never read here: kept
    assert w[POUR_CHAIN]["grasp_sg_bottle"] == 1.0                     # a grip not seen: kept
    second = replay(tl, record=False, learn=path)
    assert decided(second) == ["Wait"]
    assert read_weights(path)[1] == 2
    every = [v for row in weights(path).values() for v in row.values()]
    assert min(every) >= 0.0 and max(every) <= 1.0


def test_a_person_of_the_seeds_convention_is_read_again_after_one_success(tmp_path):
    """After learning from the person who pours with an above grip, a person who hands the open bottle over with
    that grip: the robot still receives it (a little later), and after that success as early as the priors do."""
    path = tmp_path / "weights.json"
    for _ in range(2):
        replay(load_timeline(POUR_ABOVE), record=False, learn=path)
    hand_over = load_timeline(TIMELINES / "hand_over_open_bottle.yaml")
    with_priors = replay(hand_over, record=False)

    def receive_at(rep) -> float:
        return next(t for t, kind, a in rep.agent.decisions() if kind == "decide" and a == "Receive-object")

    first = replay(hand_over, record=False, learn=path)
    assert decided(first) == decided(with_priors) and receive_at(first) > receive_at(with_priors) + 0.1
    assert weights(path)[OPEN_HAND_OVER]["grasp_ag_bottle"] > 0.95
    again = replay(hand_over, record=False, learn=path)
    assert receive_at(again) == pytest.approx(receive_at(with_priors), abs=0.02)


def _pour_above(name: str, keep=lambda e: True, extra=()) -> object:
    data = load_timeline(POUR_ABOVE)
    events = sorted([e for e in data.events if keep(e)] + list(extra), key=lambda e: e["t"])
    return timeline_from_dict({"name": name, "duration": data.duration, "events": events})


def test_seeing_the_partner_do_what_the_reading_predicts_is_a_success(tmp_path):
    """The glass is never seen full (the person drinks at once, the hand hides it): the pour seen while the robot
    reads a pour is success enough to learn what the above grip meant."""
    tl = _pour_above("pour_unseen_fill", keep=lambda e: "glass" not in e or e["t"] == 0.0)
    path = tmp_path / "weights.json"
    replay(tl, record=False, learn=path)
    assert weights(path)[POUR_CHAIN]["grasp_ag_bottle"] > 0.5
    assert decided(replay(tl, record=False, learn=path)) == ["Wait"]


def test_a_grip_read_on_the_other_object_while_carrying_leaves_the_grip_in_hand(tmp_path):
    """Carried beside the glass, the bottle in hand is read for a while as a side grip on the glass (as vision
    does): the above grip on the bottle stays the grip in hand (GRIP) and learns the pour; the misread grip, on
    the glass, learns nothing about the bottle's chains (and none of the glass's was read)."""
    misread = [{"t": 3.0, "hand": {"posture": "grasp_sg", "object_in_hand": "glass"}}]
    tl = _pour_above("pour_misread", extra=misread)
    upto = timeline_from_dict({"name": "upto", "duration": 4.3, "events": [e for e in tl.events if e["t"] <= 4.3]})
    net = replay(upto, record=False, overrides={"learning.rate": LEARNING_RATE}).agent.net
    held = dict(zip(net.spec.fields["GRIP"].items, net.presence("GRIP")))
    assert held["grasp_ag_bottle"] > 0.9 and held["grasp_sg_glass"] > 0.9
    path = tmp_path / "weights.json"
    replay(tl, record=False, learn=path)
    w = weights(path)
    prior = Cognition(overrides={"learning.rate": LEARNING_RATE}).learned_weights()["OL->ASL"]
    assert w[POUR_CHAIN]["grasp_ag_bottle"] > 0.95
    assert all(w[c]["grasp_sg_glass"] == pytest.approx(prior[c]["grasp_sg_glass"], abs=1e-3)
               for c in w if "grasp_sg_glass" in w[c])


def test_nothing_is_learnt_without_a_success(tmp_path):
    # the glass never fills and the pour is never seen: the above grip, then nothing
    tl = _pour_above("no_success", keep=lambda e: ("glass" not in e or e["t"] == 0.0)
                     and e.get("hand", {}).get("posture") != "pour")
    path = tmp_path / "weights.json"
    replay(tl, record=False, learn=path)
    prior = Cognition(overrides={"learning.rate": LEARNING_RATE}).learned_weights()["OL->ASL"]
    learnt = weights(path)
    assert all(learnt[c][g] == pytest.approx(prior[c][g], abs=1e-3) for c in prior for g in prior[c])


@pytest.mark.parametrize("name", ["fig3", "fig4", "fig5", "give_glass", "hand_over_open_bottle", "error_drink_empty_glass"])
def test_the_seeds_experiments_keep_their_decisions_while_learning_from_the_default_person(name, tmp_path):
    tl = load_timeline(TIMELINES / f"{name}.yaml")
    with_priors = decided(replay(tl, record=False))
    path = tmp_path / "weights.json"
    for _ in range(5):
        assert decided(replay(tl, record=False, learn=path)) == with_priors


def test_only_what_a_grip_means_learns():
    """The weights from each grip item onto the chains a grip on the same object begins; a grip on the bottle
    never comes to mean something about the glass, and the gestures' chains keep their own cues."""
    cog = Cognition(overrides={"learning.rate": LEARNING_RATE})
    tables = cog.learned_weights()
    assert list(tables) == ["OL->ASL"]
    learning = {(g, chain) for chain, row in tables["OL->ASL"].items() for g in row}
    assert learning == {(g, chain) for g, chains in task.GRIP_CHAINS.items() for chain in chains}
    assert ("grasp_ag_bottle", "Reach-grasp-SG-open-bottle-to-pour") in learning
    assert ("grasp_ag_bottle", "Reach-grasp-AG-glass-to-hand-over") not in learning
    assert ("grasp_sg_glass", "Reach-grasp-AG-open-bottle-to-hand-over") not in learning
    assert not any(chain.startswith(("Request", "Point")) for _, chain in learning)


@pytest.mark.parametrize("content, key, words", [
    ("not json", "line 1", "not JSON"),
    ('{"format": "something else"}', "format", "not a weights file"),
    ('{"format": "assistbot learned weights", "couplings": {"OL->IL": {}}}', "couplings.OL->IL", "does not learn"),
    ('{"format": "assistbot learned weights", "couplings": {"OL->ASL": {"Reach-grasp-SG-glass-to-turn": {"grasp_ag_glass": 3}}}}',
     "couplings.OL->ASL.Reach-grasp-SG-glass-to-turn.grasp_ag_glass", "outside learn.bounds"),
    ('{"format": "assistbot learned weights", "couplings": {"OL->ASL": {"Point-to-glass": {"grasp_ag_glass": 0.5}}}}',
     "couplings.OL->ASL.Point-to-glass.grasp_ag_glass", "does not learn"),
    ('{"format": "assistbot learned weights", "couplings": {"OL->ASL": {"Point-to-glass": {"pour": 0.5}}}}',
     "couplings.OL->ASL.Point-to-glass.pour", "does not learn"),
    ('{"format": "assistbot learned weights", "episodes": -1, "couplings": {}}', "episodes", ">= 0"),
])
def test_a_bad_weights_file_names_itself_and_the_key(tmp_path, content, key, words):
    path = tmp_path / "w.json"
    path.write_text(content)
    with pytest.raises(UserError) as err:
        replay(load_timeline(POUR_ABOVE), record=False, learn=path)
    assert err.value.where == str(path) and err.value.key == key and words in err.value.message
    assert path.read_text() == content, "a refused file is left as it was"


def test_the_cli_learns_on_a_timeline_and_refuses_an_agent_that_does_not_learn(tmp_path, capsys):
    path = tmp_path / "w.json"
    args = ["think", str(POUR_ABOVE), "--learn", str(path), "--no-figures", "--out", str(tmp_path / "t")]
    assert cli.main(args) == 0 and cli.main(args) == 0
    out = capsys.readouterr().out
    assert "DECIDE   Receive-object" in out and "DECIDE   Wait" in out and read_weights(path)[1] == 2
    assert cli.main(args + ["--agent", "fsm"]) == 2
    assert "only the field architecture" in capsys.readouterr().err


def test_assistbot_learn_writes_one_row_per_episode_and_the_curve(tmp_path, capsys):
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY)
    out = tmp_path / "learn"
    assert cli.main(["learn", str(scenario), "--episodes", "2", "--perception", "oracle", "--out", str(out),
                     "--compare"]) == 0
    rows = list(csv.DictReader(open(out / "learning.csv")))
    assert [(r["episode"], r["seed"], r["weights"]) for r in rows] == [
        ("1", "0", "learnt"), ("1", "0", "priors"), ("2", "1", "learnt"), ("2", "1", "priors")]
    assert all(r["end_reason"] == "time limit" and float(r["distance_from_priors"]) >= 0 for r in rows)
    assert (out / "learning.png").stat().st_size > 0 and read_weights(out / "weights.json")[1] == 2
    assert cli.main(["learn", str(scenario), "--episodes", "1", "--out", str(out)]) == 2, "an earlier run is kept"
    assert "--force" in capsys.readouterr().err
    assert json.loads((out / "weights.json").read_text())["episodes"] == 2
