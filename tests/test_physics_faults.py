"""A physics that blows up ends the episode as `diverged`, with the state of the last good tick in the log:
never a hang, a traceback or a run to the time limit on garbage."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from _scenarios import TINY
from assistbot.episode import run_scenario
from assistbot.human.controller import HumanController

AT = 1.0   # s: when the fault is injected


def _inject(monkeypatch, what: str) -> None:
    """At AT s, just before the physics steps, the glass's velocity becomes NaN or absurdly large."""
    tick = HumanController.tick

    def faulty(self, t):
        tick(self, t)
        if t >= AT:
            w = self.world
            dof = w.model.body_dofadr[w.body_id["glass"]]
            w.data.qvel[dof:dof + 3] = np.nan if what == "nan" else (2e3, 0.0, 0.0)

    monkeypatch.setattr(HumanController, "tick", faulty)


@pytest.mark.parametrize("what, cause", [("nan", "MuJoCo: bad velocity"), ("explosion", "glass moves at")])
def test_a_blown_up_physics_ends_the_episode_as_diverged_with_the_last_good_state(tmp_path, monkeypatch, what, cause):
    monkeypatch.chdir(tmp_path)     # MuJoCo writes its warnings to MUJOCO_LOG.TXT where it runs
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY.replace("time_limit: 3", "time_limit: 30"))
    _inject(monkeypatch, what)
    result = run_scenario(scenario, out=tmp_path / "out", perception="oracle", video=False)
    assert result.end_reason == "diverged"
    assert AT - 0.05 <= result.time <= AT + 0.05, result.time      # not reset to 0, not run on
    detail = result.end_detail
    assert detail["cause"].startswith(cause), detail
    assert AT - 0.05 <= detail["at"] < AT + 0.001
    good = detail["last_good"]
    assert {"glass", "bottle", "stopper"} <= set(good) and any(k.startswith("robot_") for k in good)
    assert all(math.isfinite(v) for val in good.values() for v in (val if isinstance(val, list) else [val]))
    assert good["glass"][2] > 0.5, "the glass stands on the table in the last good state"
    # the log ends with it, and the summary says it
    rows = [json.loads(line) for line in (tmp_path / "out" / "log.jsonl").read_text().splitlines()]
    end = [r for r in rows if r.get("event") == "end"]
    assert end and end[-1]["reason"] == "diverged" and end[-1]["last_good"] == good
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["end_reason"] == "diverged"
