"""Parameter sweeps: many episodes over a grid of parameter values and seeds, resumable, local or on Ray.

    from assistbot.sweep import SweepSpec, Param, run_sweep, LocalExecutor, RayExecutor
    spec = SweepSpec(scenarios=["paper-fig5"], seeds=3, perception="oracle",
                     params=[Param.parse("cognition.k", "0.6:1.4:3"),
                             Param.parse("human.reaction_delay", "0.3,1.5,3")])
    run_sweep(spec, "render/sweeps/k-delay", executor=LocalExecutor(workers=2))
    write_report("render/sweeps/k-delay")

Parts, one idea each: `spec` (value specs, paths, sweep files), `jobs` (the grid x seeds
as jobs with stable ids), `worker` (one job -> one row), `results` (results.csv row by row,
results.parquet), `executors` (local process pool, Ray), `runner` (resume, progress, interrupt),
`stats` and `report` (tables with confidence intervals, plots, Markdown).
"""

from __future__ import annotations

from assistbot.sweep.executors import LocalExecutor, RayExecutor, make_executor
from assistbot.sweep.jobs import Job, build_jobs, job_id
from assistbot.sweep.runner import SweepOutcome, run_sweep
from assistbot.sweep.spec import Param, SweepSpec, is_sweep_file, load_sweep_file, parse_param_arg, parse_seeds, parse_values, valid_paths
from assistbot.sweep.worker import run_job


def write_report(results_dir, out=None, expect=None, by=None):
    """Summary tables, plots and report.md for a sweep folder (see `assistbot.sweep.report`)."""
    from assistbot.sweep.report import write_report as _write

    return _write(results_dir, out, expect, by)


__all__ = ["Job", "LocalExecutor", "Param", "RayExecutor", "SweepOutcome", "SweepSpec", "build_jobs", "is_sweep_file",
           "job_id", "load_sweep_file", "make_executor", "parse_param_arg", "parse_seeds", "parse_values", "run_job",
           "run_sweep", "valid_paths", "write_report"]
