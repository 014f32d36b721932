"""Sweeps on the local process pool, run as a user runs them (the CLI in a subprocess), on a 3-second scenario.

A 2x2x2 sweep writes 8 rows; the same command again runs nothing; killed (SIGKILL) and
interrupted (SIGINT) part way and restarted, it ends with exactly the full set, no
duplicates, the finished rows unchanged and the same rows as the uninterrupted sweep;
the report renders from the results.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from _scenarios import TINY
from assistbot.sweep.results import VOLATILE, read_rows

SWEEP = ["--param", "cognition.k=0.8,1.2", "--param", "human.reaction_delay=0.2:1:2", "--seeds", "2",
         "--perception", "oracle", "--workers", "2", "--no-progress"]


def cli_args(scenario: Path, out: Path) -> list[str]:
    return [sys.executable, "-m", "assistbot.cli", "sweep", str(scenario), *SWEEP, "--out", str(out)]


def stable(rows: list[dict]) -> dict[str, dict]:
    """Rows by job id without the machine-dependent columns."""
    return {r["job_id"]: {k: v for k, v in r.items() if k not in VOLATILE} for r in rows}


@pytest.fixture(scope="module")
def scenario(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("scen") / "tiny.yaml"
    p.write_text(TINY)
    return p


@pytest.fixture(scope="module")
def sweep8(scenario, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("sweep") / "k-delay"
    r = subprocess.run(cli_args(scenario, out), capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "8 of 8 episodes" in r.stdout
    return out


def test_2x2x2_sweep_writes_8_rows(sweep8, scenario):
    header, rows = read_rows(sweep8 / "results.csv")
    assert len(rows) == 8
    assert header[:4] == ["job_id", "scenario", "cognition.k", "human.reaction_delay"]
    assert len({r["job_id"] for r in rows}) == 8
    assert {(r["cognition.k"], r["human.reaction_delay"], r["seed"]) for r in rows} == {
        (k, d, s) for k in ("0.8", "1.2") for d in ("0.2", "1.0") for s in ("0", "1")}
    assert all(r["perception"] == "oracle" and r["success"] in ("true", "false") and r["end_reason"] for r in rows)
    from assistbot.sweep import SweepSpec, build_jobs, load_sweep_file

    spec = load_sweep_file(sweep8 / "sweep.yaml")
    assert isinstance(spec, SweepSpec)
    assert {j.id for j in build_jobs(spec)} == {r["job_id"] for r in rows}
    import pyarrow.parquet as pq

    table = pq.read_table(sweep8 / "results.parquet")
    assert table.num_rows == 8 and str(table.schema.field("success").type) == "bool"
    assert sorted(table.column("job_id").to_pylist()) == sorted(r["job_id"] for r in rows)


def test_same_command_again_runs_nothing(sweep8, scenario):
    before = (sweep8 / "results.csv").read_bytes()
    r = subprocess.run(cli_args(scenario, sweep8), capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "0 run now" in r.stdout and "nothing to run" in r.stderr
    assert (sweep8 / "results.csv").read_bytes() == before


def test_report_renders_tables_and_plots(sweep8):
    r = subprocess.run([sys.executable, "-m", "assistbot.cli", "report", str(sweep8)], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    rep = sweep8 / "report"
    md = (rep / "report.md").read_text()
    assert "## cognition.k" in md and "## human.reaction_delay" in md and "95% CI (Wilson)" in md
    assert "| 0.8 | 4 |" in md and "| 1.2 | 4 |" in md
    pngs = ["success_vs_cognition.k.png", "success_vs_human.reaction_delay.png",
            "heatmap_cognition.k__human.reaction_delay.png"]
    for name in pngs:
        assert f"]({name})" in md
        assert (rep / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    header, rows = read_rows(rep / "summary.csv")
    assert [r["factor"] for r in rows] == ["cognition.k"] * 2 + ["human.reaction_delay"] * 2
    assert all(0 <= float(r["rate_low"]) <= float(r["success_rate"]) <= float(r["rate_high"]) <= 1 for r in rows)


def test_the_report_page_lists_every_episode_and_links_the_kept_runs(scenario, tmp_path):
    out = tmp_path / "kept"
    args = [sys.executable, "-m", "assistbot.cli", "sweep", str(scenario), "--param", "cognition.k=0.8,1.2",
            "--perception", "oracle", "--workers", "1", "--no-progress", "--out", str(out), "--keep-runs"]
    assert subprocess.run(args, capture_output=True, text=True, timeout=600).returncode == 0
    assert subprocess.run([sys.executable, "-m", "assistbot.cli", "report", str(out)], capture_output=True,
                          timeout=120).returncode == 0
    _, rows = read_rows(out / "results.csv")
    page = (out / "report" / "report.html").read_text()
    assert "<h2>cognition.k</h2>" in page and "Each episode links to its inspector page." in page
    for r in rows:
        run = out / "runs" / r["job_id"]
        assert (run / "summary.json").exists() and (run / "inspect.html").exists() and not (run / "video.mp4").exists()
        assert f'href="../runs/{r["job_id"]}/inspect.html"' in page


def _start(args: list[str]) -> subprocess.Popen:
    return subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)


def _wait_rows(csv: Path, n: int, proc: subprocess.Popen, timeout: float = 300) -> int:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        rows = len(read_rows(csv)[1]) if csv.exists() else 0
        if rows >= n:
            return rows
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.2)
    raise AssertionError(f"fewer than {n} rows after {timeout} s")


def _kill_group(proc: subprocess.Popen) -> None:
    try:  # workers orphaned by a SIGKILL of the parent: clean up after the test
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def test_killed_and_interrupted_then_restarted_ends_with_exactly_the_full_set(sweep8, scenario, tmp_path):
    out = tmp_path / "resumed"
    csv = out / "results.csv"
    # 1. killed outright (no chance to clean up) once two rows are written
    p = _start(cli_args(scenario, out))
    try:
        _wait_rows(csv, 2, p)
        p.send_signal(signal.SIGKILL)
        p.wait(timeout=30)
    finally:
        _kill_group(p)
    _, first = read_rows(csv)
    assert 2 <= len(first) < 8
    # 2. restarted: runs only what is missing; Ctrl-C (SIGINT) after one more row saves and exits 130
    p = _start(cli_args(scenario, out))
    try:
        _wait_rows(csv, len(first) + 1, p)
        if p.poll() is None:
            p.send_signal(signal.SIGINT)
        stdout, stderr = p.communicate(timeout=60)
    finally:
        _kill_group(p)
    assert f"{8 - len(first)} of 8 episodes to run ({len(first)} done)" in stderr
    _, second = read_rows(csv)
    if len(second) < 8:  # (a fast machine may have finished before the interrupt)
        assert p.returncode == 130, stderr
        assert "run the same command again to resume" in stderr and "Traceback" not in stderr
        import pyarrow.parquet as pq

        assert pq.read_table(out / "results.parquet").num_rows == len(second)  # rewritten on interrupt
    assert second[: len(first)] == first
    # 3. restarted again: completes
    r = subprocess.run(cli_args(scenario, out), capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    _, rows = read_rows(csv)
    assert len(rows) == 8 and len({r["job_id"] for r in rows}) == 8
    assert rows[: len(second)] == second  # finished rows unchanged, in place
    # and the same results as the sweep that was never interrupted
    _, whole = read_rows(sweep8 / "results.csv")
    assert stable(rows) == stable(whole)
