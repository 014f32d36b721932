"""A run folder is complete or says it is not: an earlier run is never mixed with a new one, and a run killed at
any moment leaves either the earlier run's complete files or the PARTIAL marker."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from _scenarios import TINY
from assistbot import cli
from assistbot.episode.outputs import PARTIAL, RUN_FILES, claim, finish

ASSISTBOT = [sys.executable, "-m", "assistbot.cli"]


def _earlier_run(out: Path) -> None:
    out.mkdir(parents=True)
    (out / "summary.json").write_text('{"scenario": "earlier"}\n')
    (out / "log.jsonl").write_text('{"t": 0}\n')


def test_a_folder_with_an_earlier_run_is_refused_without_force(tmp_path, capsys):
    scenario, out = tmp_path / "tiny.yaml", tmp_path / "out"
    scenario.write_text(TINY)
    _earlier_run(out)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert cli.main(["run", str(scenario), "--out", str(out), "--no-video"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {out}: --out: holds an earlier run") and "--force" in err and err.count("\n") == 1
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before, "the earlier run was touched"


def test_an_output_folder_that_is_a_file_is_one_line(tmp_path, capsys):
    scenario, out = tmp_path / "tiny.yaml", tmp_path / "out"
    scenario.write_text(TINY)
    out.write_text("not a folder")
    assert cli.main(["run", str(scenario), "--out", str(out), "--no-video"]) == 2
    assert capsys.readouterr().err == f"error: {out}: --out: is a file; name a folder\n"
    assert out.read_text() == "not a folder"


def test_an_unfinished_run_is_named_as_such(tmp_path, capsys):
    scenario, out = tmp_path / "tiny.yaml", tmp_path / "out"
    scenario.write_text(TINY)
    out.mkdir()
    (out / PARTIAL).write_text("killed\n")
    assert cli.main(["run", str(scenario), "--out", str(out), "--no-video"]) == 2
    assert "holds an unfinished run (PARTIAL)" in capsys.readouterr().err


def test_claiming_a_folder_marks_it_first_and_clears_the_earlier_run_but_nothing_else(tmp_path):
    out = tmp_path / "out"
    _earlier_run(out)
    (out / "video.mp4").write_bytes(b"old")
    (out / "notes.txt").write_text("the user's own file")
    claim(out)
    assert (out / PARTIAL).exists()
    assert sorted(p.name for p in out.iterdir()) == ["PARTIAL", "notes.txt"]
    finish(out)
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]
    assert {"summary.json", "inspect.html", "fields.npz"} <= set(RUN_FILES)


def test_a_run_replaced_with_force_leaves_only_its_own_files(tmp_path):
    scenario, out = tmp_path / "tiny.yaml", tmp_path / "out"
    scenario.write_text(TINY)
    _earlier_run(out)
    (out / "video.mp4").write_bytes(b"old")
    p = subprocess.run([*ASSISTBOT, "run", str(scenario), "--out", str(out), "--no-video", "--force"], capture_output=True, text=True)
    assert p.returncode == 1, p.stderr     # the tiny scenario ends at its time limit
    names = {q.name for q in out.iterdir()}
    assert "video.mp4" not in names and PARTIAL not in names, names
    assert json.loads((out / "summary.json").read_text())["scenario"] == "tiny"


def _complete(out: Path) -> bool:
    """The folder holds a whole run: a summary that parses, every file it names, a log whose every line parses."""
    summary = json.loads((out / "summary.json").read_text())
    for f in summary["figures"]:
        assert Path(f).exists() and Path(f).stat().st_size > 0, f
    for line in (out / "log.jsonl").read_text().splitlines():
        json.loads(line)
    assert not list(out.glob("*.tmp")), list(out.glob("*.tmp"))
    return True


@pytest.mark.slow
def test_a_run_killed_at_any_moment_leaves_the_earlier_run_or_says_it_is_partial(tmp_path):
    scenario, out = tmp_path / "tiny.yaml", tmp_path / "out"
    scenario.write_text(TINY.replace("time_limit: 3", "time_limit: 5"))
    args = [*ASSISTBOT, "run", str(scenario), "--out", str(out), "--force"]
    t0 = time.monotonic()
    subprocess.run(args, capture_output=True, check=False)
    whole = time.monotonic() - t0
    assert _complete(out) and not (out / PARTIAL).exists()
    rng = np.random.default_rng(7)
    outcomes = []
    for at in sorted(rng.uniform(0.3, whole, size=6)):
        proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(at)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        if (out / PARTIAL).exists():
            outcomes.append("partial")
        else:                       # killed before it claimed the folder, or after it finished: a whole run
            assert _complete(out)
            outcomes.append("complete")
    # an interrupt (Ctrl-C) once the run has claimed its folder is the same: exit 130, the folder marked partial
    (out / PARTIAL).unlink(missing_ok=True)
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    t_end = time.monotonic() + whole
    while not (out / PARTIAL).exists() and time.monotonic() < t_end:
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate()
    assert proc.returncode == 130 and "Traceback" not in err, err
    assert (out / PARTIAL).exists()
    assert "partial" in outcomes, outcomes     # the kills did land during runs
    # a complete run afterwards clears the marker and every partial file
    assert subprocess.run(args, capture_output=True).returncode == 1
    assert _complete(out) and not (out / PARTIAL).exists()
    assert os.path.getsize(out / "video.mp4") > 0
