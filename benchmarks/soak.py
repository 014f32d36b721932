"""Soak: many episodes in one process, the way a sweep worker runs them, and the resident memory after each ten.

Each episode goes through `assistbot.sweep.worker.run_job` (the code path of every sweep worker) with vision,
so each builds and releases a world, a head-camera renderer (on its own thread), the vision pipeline and a
field network. Target: the resident memory after the last ten episodes is at most 5 % above that after the
first ten (renderers, threads and caches released). Prints one line per ten and the verdict; exit status 1
when over the target.

Run: .venv/bin/python benchmarks/soak.py [--episodes 50] [--sim-seconds 8] [--perception vision]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import threading
import time
from pathlib import Path

from _scenarios import FIG5_LIKE

SCENARIO = FIG5_LIKE.replace("{name}", "soak")
TARGET = 0.05


def rss_mib() -> float:
    """This process's resident memory now (MiB), from /proc."""
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=50)
    ap.add_argument("--sim-seconds", type=float, default=8.0)
    ap.add_argument("--perception", choices=["vision", "oracle"], default="vision")
    args = ap.parse_args()

    from assistbot.sweep.jobs import Job
    from assistbot.sweep.worker import limit_threads, run_job

    limit_threads()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "soak.yaml"
        text = SCENARIO.format(t=args.sim_seconds)
        path.write_text(text)
        import yaml

        data = yaml.safe_load(text)
        print(f"soak: {args.episodes} episodes of {args.sim_seconds:g} simulated s, {args.perception}, one process "
              f"(pid {os.getpid()})")
        marks: list[float] = []
        t0 = time.perf_counter()
        for i in range(args.episodes):
            job = Job(id=f"soak{i}", scenario="soak", scenario_path=str(path), scenario_data=data, scenario_sha="-",
                      params={}, overrides={}, seed=i, perception=args.perception, time_limit=args.sim_seconds)
            row = run_job(job)
            if row["status"] != "ok":
                print(f"episode {i} crashed: {row['error']}", file=sys.stderr)
                return 1
            if (i + 1) % 10 == 0:
                marks.append(rss_mib())
                print(f"  after {i + 1:3d} episodes: RSS {marks[-1]:7.1f} MiB, threads {threading.active_count()}, "
                      f"{time.perf_counter() - t0:6.1f} s")
    if len(marks) < 2:
        print("too few episodes to compare (need 20 or more)")
        return 0
    growth = marks[-1] / marks[0] - 1.0
    verdict = "ok" if growth <= TARGET else "OVER TARGET"
    print(f"growth after the first ten: {100 * growth:+.1f} % (target <= {100 * TARGET:.0f} %): {verdict}")
    return 0 if growth <= TARGET else 1


if __name__ == "__main__":
    raise SystemExit(main())
