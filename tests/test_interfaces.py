"""The episode knows its parts by interface (`assistbot.interfaces`): another agent plugs in from the
scenario file, without touching the loop."""

from __future__ import annotations

import ast
import inspect
import json
import subprocess
import sys
from pathlib import Path

import yaml

from assistbot.episode import run_scenario
from assistbot.episode.runner import Episode

TESTS = Path(__file__).parent
SCENARIO = {"name": "scripted-fill", "seed": 0, "time_limit": 90,
            "objects": {"bottle": {"zone": "RWS", "state": "open"}, "glass": {"zone": "RWS", "state": "empty"}},
            "human": {"profile": "active"}, "agent": "scripted_agent:fill_and_hand_over"}


def test_an_agent_without_fields_runs_the_episode_from_the_scenario_file(tmp_path, monkeypatch):
    monkeypatch.syspath_prepend(str(TESTS))
    path = tmp_path / "scripted.yaml"
    path.write_text(yaml.safe_dump(SCENARIO))
    r = run_scenario(path, out=tmp_path / "out", perception="oracle", video=False)
    assert [a for _, a in r.decisions] == ["Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over", "Suggest-drink"]
    # the active person, handed the full glass, may drink while the robot is still suggesting it
    assert [(a["action"], a["status"]) for a in r.actions][:2] == [
        ("Reach-grasp-open-bottle-fill-glass", "succeeded"), ("Reach-full-glass-to-hand-over", "succeeded")]
    assert r.actions[2]["action"] == "Suggest-drink" and r.actions[2]["status"] in ("succeeded", "running")
    # the robot filled, the person took the glass from it, then drank: the task is done
    events = [e["event"] for e in r.world_events]
    assert events.index("glass_filled") < events.index("drink")
    assert [(e["what"], e["kind"]) for e in r.human_events if e["what"] == "take_from_robot"] == [
        ("take_from_robot", "start"), ("take_from_robot", "succeeded")]
    assert r.success and r.end_reason == "drink"
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["figures"] == []       # no fields to draw
    ticks = [json.loads(line) for line in (tmp_path / "out" / "log.jsonl").read_text().splitlines()]
    assert any(row.get("doing") == "Reach-full-glass-to-hand-over" for row in ticks if row["kind"] == "tick")


def test_an_unknown_agent_is_one_line_naming_the_file_and_the_key(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump({**SCENARIO, "agent": "behaviour-tree"}))
    p = subprocess.run([sys.executable, "-m", "assistbot.cli", "run", str(path), "--no-video", "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    line = p.stderr.strip()
    assert "\n" not in line and str(path) in line and "agent" in line and "dnf" in line, line
    assert not (tmp_path / "o").exists()


def test_the_loop_imports_no_concrete_part_and_fits_on_a_screen():
    import assistbot.episode.runner as runner

    tree = ast.parse(Path(runner.__file__).read_text())
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)} | {
        a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    # data types and interfaces only: no vision, oracle, cognition, executor, human controller or world
    assert imported <= {"__future__", "time", "dataclasses", "typing", "assistbot.cognition.percept",
                        "assistbot.interfaces", "assistbot.speech"}, imported
    assert len(inspect.getsource(Episode.run).splitlines()) <= 30


def test_a_field_agent_episode_writes_the_seed_figures_with_its_decisions(tmp_path):
    """The closed loop hands the recording and the decision history to the figures (as `think` does)."""
    spec = {**SCENARIO, "name": "dnf-figures", "time_limit": 12, "agent": "dnf"}
    path = tmp_path / "dnf.yaml"
    path.write_text(yaml.safe_dump(spec))
    r = run_scenario(path, out=tmp_path / "out", perception="oracle", video=False)
    assert r.decisions, "the field architecture decides within 12 s with both objects ready in the RWS"
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert sorted(Path(p).name for p in summary["figures"]) == sorted(
        f"{layer}.png" for layer in ("asl", "ael", "csgl", "il", "aml", "oml"))
    assert all(Path(p).stat().st_size > 10_000 for p in summary["figures"])
