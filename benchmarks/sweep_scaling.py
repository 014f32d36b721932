"""Sweep throughput: episodes per minute with 1 and 2 local workers and with Ray on 2 CPUs.

Each configuration runs the same sweep (a fig5-like scenario cut to a few simulated seconds,
oracle perception, distinct seeds) into a fresh folder through `assistbot.sweep.run_sweep`,
the code path of `assistbot sweep`. Two rates per configuration:

- overall: episodes / wall time of the whole run, including process (or Ray) start-up and each
  worker's first-episode warm-up (imports, numba cache, MuJoCo model compile);
- steady: episodes after the first one per worker / time from the first row to the last.

Scaling efficiency = rate(2 workers) / (2 x rate(1 worker)). Goal >= 90% on a 2-core machine.
Also printed: the 1-core episode rate measured in this process (no pool), and the load average,
since other processes on a shared machine take CPU from the workers.
Run: .venv/bin/python benchmarks/sweep_scaling.py [--episodes 12] [--sim-seconds 4] [--no-ray]
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from _scenarios import FIG5_LIKE

SCENARIO = FIG5_LIKE.replace("{name}", "bench-fig5")


def run_config(scenario: Path, out: Path, episodes: int, executor) -> dict:
    from assistbot.sweep import Param, SweepSpec, run_sweep

    spec = SweepSpec(scenarios=[str(scenario)], seeds=list(range(episodes)), perception="oracle",
                     params=[Param.parse("cognition.k", "1.0")])
    stamps: list[float] = []
    rows: list[dict] = []

    def on_row(row: dict) -> None:
        stamps.append(time.perf_counter())
        rows.append(row)

    t0 = time.perf_counter()
    outcome = run_sweep(spec, out, executor=executor, progress=False, on_row=on_row, log=lambda msg: None)
    total = time.perf_counter() - t0
    assert outcome.ran == episodes and not outcome.crashed, outcome
    # after each worker's first episode: the share of a CPU an episode got (1.0 = a core to itself)
    later = rows[1:]
    share = sum(r["cpu_seconds"] for r in later) / max(1e-9, sum(r["wall_seconds"] for r in later))
    return {"overall": 60 * episodes / total, "stamps": stamps, "total": total, "executor": outcome.executor,
            "first": stamps[0] - t0, "share": share}


def steady_rate(stamps: list[float], workers: int) -> float:
    """Episodes per minute after each worker's first episode (start-up and warm-up excluded)."""
    if len(stamps) <= workers:
        return float("nan")
    return 60 * (len(stamps) - workers) / (stamps[-1] - stamps[workers - 1])


def in_process_rate(scenario: Path, n: int = 2) -> float:
    from assistbot.episode import run_scenario
    from assistbot.scenario import load_scenario

    s = load_scenario(scenario)
    run_scenario(s, perception="oracle", seed=99, video=False)  # warm-up
    t0 = time.perf_counter()
    for seed in range(n):
        run_scenario(s, perception="oracle", seed=seed, video=False)
    return 60 * n / (time.perf_counter() - t0)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=12, help="episodes per configuration (default 12)")
    ap.add_argument("--sim-seconds", type=float, default=4.0, help="simulated seconds per episode (default 4)")
    ap.add_argument("--no-ray", action="store_true", help="skip the Ray configuration")
    args = ap.parse_args()

    from assistbot.sweep import LocalExecutor, RayExecutor
    from assistbot.sweep.executors import available_cpus
    from assistbot.sweep.worker import limit_threads

    limit_threads()
    tmp = Path(tempfile.mkdtemp(prefix="sweep-bench-"))
    try:
        scenario = tmp / "bench.yaml"
        scenario.write_text(SCENARIO.format(t=args.sim_seconds))
        print(f"sweep scaling: {args.episodes} episodes x {args.sim_seconds:g} sim s each (oracle perception), "
              f"{available_cpus()} CPUs, load average before {os.getloadavg()[0]:.2f}")
        base = in_process_rate(scenario)
        print(f"  in-process, no pool         : {base:6.1f} episodes/min (warm)")
        results = {}
        configs = [("local, 1 worker", lambda: LocalExecutor(1), 1), ("local, 2 workers", lambda: LocalExecutor(2), 2)]
        if not args.no_ray:
            configs.append(("Ray, 2 CPUs (local)", lambda: RayExecutor(cpus=2), 2))
        for i, (name, make, workers) in enumerate(configs):
            r = run_config(scenario, tmp / f"out{i}", args.episodes, make())
            r["steady"] = steady_rate(r["stamps"], workers)
            results[name] = r
            print(f"  {name:<28}: {r['overall']:6.1f} episodes/min overall ({r['total']:.1f} s, first row after "
                  f"{r['first']:.1f} s), {r['steady']:6.1f} steady; CPU share per episode {r['share']:.2f}; "
                  f"load average {os.getloadavg()[0]:.2f}")
        one = results["local, 1 worker"]
        for name in list(results)[1:]:
            r = results[name]
            eff = r["overall"] / (2 * one["overall"])
            steady = r["steady"] / (2 * one["steady"])
            # the same with each episode's rate scaled to a full core: what is left is the sweep's own overhead
            # (start-up, pickling, writing rows), not CPU taken by other processes on a shared machine
            per_core = (r["steady"] / r["share"]) / (2 * one["steady"] / one["share"])
            print(f"  scaling efficiency, {name:<20}: {100 * eff:.0f}% overall, {100 * steady:.0f}% steady, "
                  f"{100 * per_core:.0f}% steady per CPU-second (goal >= 90%)")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
