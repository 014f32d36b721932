"""The same scenario and seed give byte-identical log.jsonl and the same summary (wall times and the output
folder's own paths aside): run after run in one process, in two processes at once, on the pipelined vision
path (the render thread) and on the synchronous one. (That the pipelined path delivers the synchronous one's
percept one perception tick late is tests/test_render_thread.py.)"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from assistbot.episode import run_scenario

#: the seed's Fig. 3 opening, cut short: the person shows the closed bottle, the robot answers
SHORT = """\
name: short
seed: 5
time_limit: 20
objects:
  bottle: {zone: HWS, state: closed}
  glass: {zone: RWS, state: inverted}
human:
  profile: active
  script:
    - {do: grasp, object: bottle, grip: side, hold_out: true}
"""


def _summary(out: Path) -> dict:
    data = json.loads((out / "summary.json").read_text())
    data.pop("wall_seconds")
    data["figures"] = [Path(f).name for f in data["figures"]]
    return data


def _at_once(scenario: Path, outs: list[Path], *extra: str) -> None:
    procs = [subprocess.Popen([sys.executable, "-m", "assistbot.cli", "run", str(scenario), "--out", str(o), "--no-video", *extra],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True) for o in outs]
    for p in procs:
        _, err = p.communicate()
        assert p.returncode in (0, 1), err


@pytest.mark.slow
@pytest.mark.parametrize("pipelined", [True, False], ids=["pipelined", "synchronous"])
def test_two_processes_at_once_write_the_same_log_and_summary(tmp_path, pipelined):
    scenario = tmp_path / "short.yaml"
    scenario.write_text(SHORT)
    a, b = tmp_path / "a", tmp_path / "b"
    _at_once(scenario, [a, b], "--set", f"vision.pipelined={str(pipelined).lower()}")
    assert (a / "log.jsonl").read_bytes() == (b / "log.jsonl").read_bytes()
    assert _summary(a) == _summary(b)
    assert _summary(a)["decisions"], "the short scenario decides something: the comparison covers cognition"


@pytest.mark.slow
@pytest.mark.parametrize("perception", ["vision", "oracle"])
def test_run_after_run_in_one_process_is_the_same(tmp_path, perception):
    scenario = tmp_path / "short.yaml"
    scenario.write_text(SHORT)
    outs = [tmp_path / "first", tmp_path / "second"]
    for o in outs:
        run_scenario(scenario, out=o, perception=perception, video=False)
    assert (outs[0] / "log.jsonl").read_bytes() == (outs[1] / "log.jsonl").read_bytes()
    assert _summary(outs[0]) == _summary(outs[1])
