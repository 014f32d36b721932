"""Scenario files: the shipped ones load; every mistake is one exit-2 line naming the file and the key."""

from __future__ import annotations

import subprocess
import sys

import pytest

from assistbot.errors import UserError
from assistbot.scenario import load_scenario, shipped_scenarios

GOOD = """name: t
seed: 3
time_limit: 30
objects:
  bottle: {zone: HWS, state: closed}
  glass: {zone: RWS, state: inverted}
human:
  profile: passive
"""


def cli(*args):
    return subprocess.run([sys.executable, "-m", "assistbot.cli", *args], capture_output=True, text=True)


def test_shipped_scenarios_include_the_papers_and_four_more():
    names = {p.stem for p in shipped_scenarios()}
    assert {"paper-fig3-4", "paper-fig5"} <= names
    assert len(names) >= 6
    for p in shipped_scenarios():
        s = load_scenario(p)
        assert s.name == p.stem
    fig5 = load_scenario("paper-fig5")
    assert (fig5.objects.bottle.zone, fig5.objects.bottle.state) == ("RWS", "closed")
    assert (fig5.objects.glass.zone, fig5.objects.glass.state) == ("HWS", "empty")
    assert fig5.human.profile == "passive"
    fig34 = load_scenario("paper-fig3-4")
    assert [st.do for st in fig34.human.script] == ["grasp", "request"]


@pytest.mark.parametrize("edit, key", [
    (("zone: HWS", "zone: MIDDLE"), "objects.bottle.zone"),
    (("state: inverted", "state: upside-down"), "objects.glass.state"),
    (("profile: passive", "profile: sleepy"), "human.profile"),
    (("seed: 3", "seed: -1"), "seed"),
    (("time_limit: 30", "time_limit: forever"), "time_limit"),
    (("name: t", "name: t\ncolour: red"), "colour"),
])
def test_bad_scenario_names_the_key(tmp_path, edit, key):
    p = tmp_path / "bad.yaml"
    p.write_text(GOOD.replace(*edit))
    with pytest.raises(UserError) as err:
        load_scenario(p)
    assert err.value.where == str(p)
    assert err.value.key == key


def test_position_in_the_wrong_half_is_refused(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text(GOOD.replace("{zone: HWS, state: closed}", "{zone: HWS, state: closed, position: [0.2, 0.0]}"))
    with pytest.raises(UserError) as err:
        load_scenario(p)
    assert err.value.key.startswith("objects.bottle")


def test_run_with_a_bad_scenario_exits_2_with_one_line(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text(GOOD.replace("profile: passive", "profile: sleepy"))
    r = cli("run", str(p), "--no-video")
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [r.stderr.strip()]
    assert str(p) in r.stderr and "human.profile" in r.stderr
    assert "Traceback" not in r.stderr


def test_run_with_unknown_override_suggests_valid_paths(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(GOOD)
    r = cli("run", str(p), "--no-video", "--set", "cognition.kk=1")
    assert r.returncode == 2
    assert "cognition.kk" in r.stderr and "did you mean" in r.stderr and "cognition.k" in r.stderr


def test_unknown_scenario_name_lists_the_shipped_ones():
    r = cli("run", "no-such-scenario")
    assert r.returncode == 2
    assert "paper-fig3-4" in r.stderr


def test_list_shows_every_shipped_scenario():
    r = cli("list")
    assert r.returncode == 0
    for p in shipped_scenarios():
        assert p.stem in r.stdout


def test_run_sets_the_arrangement_and_the_partner_as_a_sweep_row_does(tmp_path):
    """`assistbot run SCENARIO --set objects.glass.zone=HWS --set human.profile=slow` runs the episode a sweep's
    row with those values runs: the summary's world starts from the edited arrangement."""
    import json

    p = tmp_path / "s.yaml"
    p.write_text(GOOD.replace("time_limit: 30", "time_limit: 1"))
    out = tmp_path / "out"
    r = cli("run", str(p), "--no-video", "--perception", "oracle", "--out", str(out),
            "--set", "objects.glass.zone=HWS", "--set", "objects.glass.state=full", "--set", "human.profile=slow")
    assert r.returncode == 1 and "time limit" in r.stdout, r.stderr   # 1: did not drink in its 1 s
    log = [json.loads(line) for line in (out / "log.jsonl").read_text().splitlines()]
    first = next(e for e in log if e.get("kind") == "tick")
    assert first["percept"]["objects"]["glass"]["zone"] == "HWS" and first["percept"]["objects"]["glass"]["state"] == "full"


def test_run_with_a_bad_arrangement_value_exits_2_naming_set(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(GOOD)
    r = cli("run", str(p), "--no-video", "--set", "objects.glass.zone=TABLE")
    assert r.returncode == 2 and r.stderr.strip().startswith("error: --set") and "objects.glass.zone" in r.stderr
    assert "Traceback" not in r.stderr
