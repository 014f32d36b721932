"""`assistbot think`: figures and log from a timeline; user mistakes are one line and exit status 2."""

from __future__ import annotations

from pathlib import Path

import pytest

from assistbot.cli import main

TIMELINES = Path(__file__).resolve().parents[1] / "scenarios" / "timelines"


def test_think_writes_figures_and_log(tmp_path, capsys):
    assert main(["think", str(TIMELINES / "fig4.yaml"), "--out", str(tmp_path)]) == 0
    for name in ("asl.png", "ael.png", "csgl.png", "log.txt"):
        assert (tmp_path / name).stat().st_size > 0
    log = (tmp_path / "log.txt").read_text()
    assert "DECIDE   Reach-grasp-open-bottle-fill-glass" in log and "DECIDE   Reach-full-glass-to-hand-over" in log
    assert "SAY AEL" in log and "<inform:fill_glass>" in log
    assert "fig4" in capsys.readouterr().out


BAD = {
    "unknown_key.yaml": "name: x\nduration: 2\nevents:\n  - {t: 0, hnad: {posture: none}}\n",
    "unknown_item.yaml": "name: x\nduration: 2\nevents:\n  - {t: 0, hand: {posture: wave}}\n",
    "bad_state.yaml": "name: x\nduration: 2\nevents:\n  - {t: 0, glass: {zone: RWS, state: closed}}\n",
    "not_yaml.yaml": "name: [x\n",
    "no_events.yaml": "name: x\nduration: 2\n",
    "bad_time.yaml": "name: x\nduration: 2\nevents:\n  - {t: -1, hand: {posture: none}}\n",
    "bad_action.yaml": "name: x\nduration: 2\nevents:\n  - {t: 0, robot: {status: succeeded, action: Dance}}\n",
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_timeline_is_one_line_and_exit_2(tmp_path, capsys, name):
    path = tmp_path / name
    path.write_text(BAD[name])
    assert main(["think", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: ") and str(path) in err
    assert "Traceback" not in err


def test_missing_file_and_bad_config_path_are_exit_2(tmp_path, capsys):
    assert main(["think", str(tmp_path / "nope.yaml")]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert main(["think", str(TIMELINES / "fig4.yaml"), "--no-figures", "--out", str(tmp_path), "--set", "fields.AEL.hh=-3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "fields.AEL.hh" in err
    assert main(["think", str(TIMELINES / "fig4.yaml"), "--no-figures", "--out", str(tmp_path), "--set", "k"]) == 2
    bad_cfg = tmp_path / "cfg.yaml"
    bad_cfg.write_text("name: x\nduration: 1\nconfig: {'couplings.IL->AEL.table.Wait.Nope': 1}\n"
                       "events:\n  - {t: 0, hand: {posture: none}}\n")
    assert main(["think", str(bad_cfg), "--no-figures", "--out", str(tmp_path)]) == 2
    assert "Nope" in capsys.readouterr().err
