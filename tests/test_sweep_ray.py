"""The Ray executor (a local Ray with 2 CPUs) gives the same rows as the local pool, and resumes the same way.

One Ray start for the module (it takes ~10 s): the Ray folder starts with two rows copied
from the local sweep, so the Ray run must run only the four missing episodes, and the
result must equal the local sweep's rows for the same seeds (wall time excluded).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("ray")

from _scenarios import TINY  # noqa: E402
from assistbot.sweep.results import VOLATILE, read_rows  # noqa: E402

SWEEP = ["--param", "cognition.k=0.8,1.2,1.6", "--seeds", "2", "--perception", "oracle", "--no-progress"]


def sweep(scenario, out, *extra):
    return subprocess.run([sys.executable, "-m", "assistbot.cli", "sweep", str(scenario), *SWEEP, "--out", str(out), *extra],
                          capture_output=True, text=True, timeout=600)


def stable(rows):
    return {r["job_id"]: {k: v for k, v in r.items() if k not in VOLATILE} for r in rows}


def test_ray_and_local_give_identical_rows_and_ray_resumes(tmp_path):
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(TINY)
    local = sweep(scenario, tmp_path / "local", "--workers", "2")
    assert local.returncode == 0, local.stderr
    header, local_rows = read_rows(tmp_path / "local" / "results.csv")
    assert len(local_rows) == 6

    ray_dir = tmp_path / "ray"
    ray_dir.mkdir()
    text = (tmp_path / "local" / "results.csv").read_text().splitlines(keepends=True)
    (ray_dir / "results.csv").write_text("".join(text[:3]))  # header + two finished rows
    r = sweep(scenario, ray_dir, "--executor", "ray", "--cpus", "2")
    assert r.returncode == 0, r.stderr
    assert "4 of 6 episodes to run (2 done) on local Ray, 2 CPUs" in r.stderr
    _, ray_rows = read_rows(ray_dir / "results.csv")
    assert len(ray_rows) == 6 and len({x["job_id"] for x in ray_rows}) == 6
    assert ray_rows[:2] == local_rows[:2]
    assert stable(ray_rows) == stable(local_rows)
    import pyarrow.parquet as pq

    assert pq.read_table(ray_dir / "results.parquet").num_rows == 6


@pytest.mark.slow
def test_joins_a_running_cluster_with_address_auto(tmp_path):
    """A cluster started with 'ray start --head' (stopped again by its pid) runs the sweep via --address auto."""
    import os
    import shutil
    import signal
    import socket
    import time

    ray_cli = shutil.which("ray", path=os.path.dirname(sys.executable))
    assert ray_cli, "the ray command is installed with the ray package"
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    head = subprocess.Popen([ray_cli, "start", "--head", "--block", "--num-cpus", "2", "--port", str(port),
                             "--include-dashboard=false", "--disable-usage-stats"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        time.sleep(12)
        assert head.poll() is None
        scenario = tmp_path / "tiny.yaml"
        scenario.write_text(TINY)
        r = subprocess.run([sys.executable, "-m", "assistbot.cli", "sweep", str(scenario), "--param", "cognition.k=0.8,1.2",
                            "--perception", "oracle", "--no-progress", "--out", str(tmp_path / "out"),
                            "--executor", "ray", "--address", "auto"], capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        assert "on cluster at auto" in r.stderr
        assert len(read_rows(tmp_path / "out" / "results.csv")[1]) == 2
    finally:
        head.send_signal(signal.SIGTERM)  # 'ray start --block' stops the processes it started
        try:
            head.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(head.pid, signal.SIGKILL)
        current = "/tmp/ray/ray_current_cluster"  # left behind by a stopped head: remove ours, or ray.init() trips on it
        try:
            with open(current) as fh:
                ours = fh.read().strip().endswith(f":{port}")
            if ours:
                os.remove(current)
        except OSError:
            pass
