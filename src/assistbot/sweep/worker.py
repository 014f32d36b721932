"""One job -> one result row, in whatever process runs it (a pool worker, a Ray task, or this one).

The row holds plain values only (str, int, float, bool, None), so it pickles
cheaply and writes to CSV without conversion. An episode that raises gives a
row with ``status = "crashed"`` and the error, which the sweep keeps out of
results.csv (it goes to errors.csv and runs again on resume).
"""

from __future__ import annotations

import gc
import os
import time
import traceback
from typing import Any

from assistbot.sweep.jobs import Job

#: threads per episode: workers are the parallelism, nested BLAS/numba threads only contend
THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}


def limit_threads() -> None:
    for k, v in THREAD_ENV.items():
        os.environ.setdefault(k, v)


def init_worker() -> None:
    """Pool initializer: Ctrl-C is the parent's to handle (it stops the workers), one thread each."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    limit_threads()


def run_job(job: Job) -> dict[str, Any]:
    """Run one episode without video and return its result row (see `assistbot.sweep.results.FIXED`); its run
    folder goes to ``job.run_dir`` when the sweep keeps runs."""
    from assistbot.episode import run_scenario
    from assistbot.scenario import parse_scenario

    t0, c0 = time.perf_counter(), time.process_time()
    row: dict[str, Any] = {"job_id": job.id, "scenario": job.scenario, **job.params, "seed": job.seed,
                           "perception": job.perception, "time_limit": job.time_limit}
    try:
        scenario = parse_scenario(job.scenario_data, job.scenario_path)
        result = run_scenario(scenario, out=job.run_dir, perception=job.perception, seed=job.seed,
                              overrides=dict(job.overrides), video=False, progress=False)
        s = result.summary()
    except Exception as exc:  # noqa: BLE001 - a crashed episode must not end the sweep
        tb = traceback.format_exc(limit=-3).strip().splitlines()
        row.update(status="crashed", error=f"{type(exc).__name__}: {exc}", traceback=" | ".join(tb[-6:]),
                   wall_seconds=round(time.perf_counter() - t0, 3))
        return row
    finally:
        # An episode's parts reference each other (the robot's primitives and their phases, the person's
        # behaviours), so a finished episode waits for the cycle collector, holding its MuJoCo model, data and
        # images; freed now, before the next episode is built, a long-lived worker's memory stays level
        # (benchmarks/soak.py) instead of creeping up through fragmentation.
        gc.collect()
    decisions = s["decisions"]
    cues = s.get("cues")   # the cue ledger's counts (`assistbot.episode.cues`), where the episode kept one
    row.update(
        status="ok",
        success=bool(s["success"]),
        time_to_drink=s["time_to_drink"],
        end_reason=str(s["end_reason"]),
        end_detail=" ".join(f"{k}={v}" for k, v in s["end_detail"].items()),
        decisions=" > ".join(decisions),
        n_decisions=len(decisions),
        n_failed_actions=result.n_failed_actions,
        errors_communicated=int(s["errors_communicated"]),
        answered_cues=None if cues is None else int(cues["answered"]),
        ignored_cues=None if cues is None else int(cues["ignored"]),
        uncued_decisions=None if cues is None else int(cues["without_cue"]),
        spilled_fraction=float(s["spilled_fraction"]),
        min_distance_human=float(s["min_distance_human"]),
        touched_person=bool(s["touched_person"]["touched"]),
        touch_depth=float(s["touched_person"]["depth"]),
        touch_force=float(s["touched_person"]["force"]),
        sim_time=float(s["time"]),
        scenario_sha=job.scenario_sha,
        wall_seconds=round(time.perf_counter() - t0, 3),
        cpu_seconds=round(time.process_time() - c0, 3),  # < wall_seconds: the worker waited for a CPU
    )
    return row
