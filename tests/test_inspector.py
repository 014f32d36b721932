"""The episode inspector: `assistbot run` writes inspect.html, `assistbot inspect` rebuilds it, and the page works
offline in a real browser (headless Chromium from Debian's packages): it loads without errors, draws a heat map
per field layer and the timeline, and seeking to a decision moves the video there."""

from __future__ import annotations

import base64
import html
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from _scenarios import TINY
from assistbot import cli
from assistbot.episode import run_scenario

#: CI installs Chromium (.ci/run) and sets this, so that the browser test cannot pass by being skipped there
REQUIRE_BROWSER = os.environ.get("ASSISTBOT_REQUIRE_CHROMIUM") == "1"


def _page_data(page: Path) -> dict:
    text = page.read_text(encoding="utf-8")
    m = re.search(r'<script type="application/json" id="data">(.*?)</script>', text, re.S)
    assert m, "the page carries its data"
    return json.loads(m.group(1).replace("<\\/", "</"))


def test_a_run_writes_its_inspector_page_with_the_fields_and_the_events(tmp_path):
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY.replace("time_limit: 3", "time_limit: 6"))
    result = run_scenario(scenario, out=tmp_path / "out", perception="oracle", video=False)
    page = tmp_path / "out" / "inspect.html"
    text = page.read_text(encoding="utf-8")
    own = re.sub(r"<script>.*?</script>", "", text, count=1, flags=re.S)   # the page without the inlined plotly.js
    assert len(text) - len(own) > 1_000_000, "plotly.js is inlined"
    assert not re.search(r'(src|href)\s*=\s*["\']https?:', own), "the page loads nothing from the network"
    data = _page_data(page)
    assert data["summary"]["scenario"] == "tiny" and data["summary"]["perception"] == "oracle"
    assert [d["action"] for d in data["decisions"]] == [a for _, a in result.decisions]
    layers = data["fields"]["layers"]
    assert {"OL", "ASL", "IL", "AML", "AEL", "CSGL_present"} <= set(layers)
    n, ael = len(data["fields"]["t"]), layers["AEL"]
    assert n >= 50
    # int16 base64 arrays: u over the kept positions, u and S per item, and the couplings' parts into AEL
    assert len(base64.b64decode(ael["u"])) == 2 * n * len(ael["rows"])
    assert len(base64.b64decode(ael["u_items"])) == 2 * n * len(ael["items"])
    assert ael["inputs"] and all(len(base64.b64decode(v)) == 2 * n * len(ael["items"]) for v in ael["inputs"].values())
    assert len(data["ticks"]) >= 50 and data["video"] is None


def test_inspect_rebuilds_the_page_and_refuses_a_folder_without_a_run(tmp_path, capsys):
    assert cli.main(["inspect", str(tmp_path / "nowhere")]) == 2
    assert cli.main(["inspect", str(tmp_path)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith("error: ") and "no such folder" in err[0] and "summary.json" in err[1]


def _chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.slow
def test_the_page_works_offline_in_a_browser_and_seeking_to_a_decision_moves_the_video(tmp_path):
    browser = _chromium()
    if browser is None:
        if REQUIRE_BROWSER:
            pytest.fail("Chromium is required here (apt-get install chromium) but not installed")
        pytest.skip("no Chromium (apt-get install chromium)")
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY.replace("time_limit: 3", "time_limit: 6"))
    out = tmp_path / "out"
    result = run_scenario(scenario, out=out, perception="vision", video=True)
    assert result.decisions, "the run decides something to seek to"
    # no name resolves: a page that needed the network would fail here
    p = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=15000",
                        "--host-resolver-rules=MAP * ~NOTFOUND", "--dump-dom", f"file://{out / 'inspect.html'}#selftest"],
                       capture_output=True, text=True, timeout=120)
    m = re.search(r'data-selftest="([^"]*)"', p.stdout)
    assert m, f"the page's self-test did not report: {p.stderr[-800:]}"
    report = json.loads(html.unescape(m.group(1)))
    assert report["errors"] == []
    assert report["heats"] == report["layers"] >= 9, report
    assert report["timeline"]
    # the decided pool, plotted with u, S and the part of S from each coupling into AEL that gave any
    assert report["pool"] == f"AEL:{result.decisions[0][1]}", report
    assert report["pool_traces"][:2] == ["activity u", "input S"] and any(n.startswith("from ") for n in report["pool_traces"])
    assert report["video"] and abs(report["video_time"] - result.decisions[0][0]) < 0.25, report
    assert all(r.startswith("file:") for r in report["resources"]), report["resources"]


def test_the_recorded_truth_stands_beside_vision_in_the_log_and_the_page_and_changes_nothing(tmp_path):
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY.replace("time_limit: 3", "time_limit: 5"))
    plain = run_scenario(scenario, out=tmp_path / "plain", perception="vision", video=False)
    kept = run_scenario(scenario, out=tmp_path / "truth", perception="vision", video=False, record_truth=True)
    # the truth goes to the log only: the robot decided and did the same
    assert kept.decisions == plain.decisions and kept.actions == plain.actions
    ticks = [json.loads(line) for line in (tmp_path / "truth" / "log.jsonl").read_text().splitlines()
             if '"kind": "tick"' in line]
    assert ticks and all("truth" in r for r in ticks)
    assert ticks[-1]["truth"]["objects"]["glass"] == {"zone": "HWS", "state": "empty"}
    page_ticks = _page_data(tmp_path / "truth" / "inspect.html")["ticks"]
    assert page_ticks[-1][5][0]["glass"] == ["HWS", "empty"]
    assert all(t[5] is None for t in _page_data(tmp_path / "plain" / "inspect.html")["ticks"])
