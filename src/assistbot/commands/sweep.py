"""`assistbot sweep SCENARIO... --param PATH=VALUES ... --out DIR`: many episodes, resumable, local or on Ray."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "sweep"
HELP = "run a parameter sweep (scenarios x parameter grid x seeds) into results.csv/.parquet; resumable, local or Ray"
ORDER = 30

EPILOG = """\
value specs:  0.5,1,2 (list)   0.5:2:4 (4 values from 0.5 to 2)   0.1:10:3:log
              uniform(0.5,2)x4  loguniform(a,b)xN  normal(mean,sd)xN  randint(a,b)xN  choice(a|b)xN
              objects.glass.position=[-0.25,0.1],[-0.2,0.15]   objects.glass.position.x=-0.3:-0.2:3
examples:
  assistbot sweep paper-fig5 --param cognition.k=0.6:1.4:3 --param human.reaction_delay=0.3,1.5,3 \\
      --seeds 3 --out render/sweeps/k-delay
  assistbot sweep my-sweep.yaml --workers 2          (a sweep file; see assistbot.sweep.spec)
  assistbot sweep paper-fig5 --param vision.dropout=0:0.3:4 --executor ray --address auto --out DIR
Run the same command again to resume: finished episodes are skipped. Then: assistbot report DIR
"""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = EPILOG
    p.add_argument("specs", nargs="*", metavar="SCENARIO",
                   help="scenario files or shipped names, or one sweep file (YAML with params:)")
    p.add_argument("--param", action="append", default=[], metavar="PATH=VALUES",
                   help="a parameter to sweep and its values (repeatable; the grid is their product)")
    p.add_argument("--seeds", default=None, metavar="N|S1,S2",
                   help="N seeds (the scenario's seed and the N-1 after it) or a list 0,4,9 (default 1)")
    p.add_argument("--out", type=Path, default=None, help="results folder (required unless the sweep file names one)")
    p.add_argument("--perception", choices=["vision", "oracle"], default=None,
                   help="vision (the robot's cameras, default) or oracle (ground truth, for debugging)")
    p.add_argument("--time-limit", type=float, default=None, metavar="S",
                   help="simulated seconds per episode, replacing the scenarios' time limits")
    p.add_argument("--sample-seed", type=int, default=None, metavar="S", help="seed of the random value specs (default 0)")
    p.add_argument("--executor", choices=["local", "ray"], default="local",
                   help="local process pool (default) or Ray tasks")
    p.add_argument("--workers", type=int, default=None, metavar="K", help="local processes (default: one per CPU)")
    p.add_argument("--address", default=None, metavar="ADDR",
                   help="Ray cluster to join: auto, HOST:PORT or ray://HOST:10001 (default: start a local Ray)")
    p.add_argument("--cpus", type=int, default=None, metavar="N", help="CPUs of a local Ray (default: --workers or all)")
    p.add_argument("--keep-runs", action="store_true",
                   help="keep each episode's run folder (log, summary, figures, inspect.html; no video) in OUT/runs/, "
                        "linked from the report's report.html")
    p.add_argument("--dry-run", action="store_true", help="list the episodes (and which are done) without running them")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--list-paths", action="store_true", help="print every parameter path a sweep can vary and exit")


def build_spec(args: argparse.Namespace):
    from assistbot.errors import UserError
    from assistbot.sweep.spec import SweepSpec, is_sweep_file, load_sweep_file, parse_param_arg, parse_seeds

    files = [s for s in args.specs if is_sweep_file(s)]
    if files and len(args.specs) > 1:
        raise UserError("arguments", files[0], "give either one sweep file or scenarios, not both")
    sample_seed = args.sample_seed
    if files:
        spec = load_sweep_file(files[0], sample_seed)
    else:
        if not args.specs:
            raise UserError("arguments", "SCENARIO", "name at least one scenario or a sweep file (see 'assistbot list')")
        spec = SweepSpec(scenarios=list(args.specs), sample_seed=sample_seed or 0)
    for text in args.param:
        spec.with_param(parse_param_arg(text, spec.sample_seed))
    if args.seeds is not None:
        spec.seeds = parse_seeds(args.seeds)
    if args.perception is not None:
        spec.perception = args.perception
    if args.time_limit is not None:
        spec.time_limit = args.time_limit
    spec.__post_init__()  # re-check after the command line's changes
    out = args.out or (Path(spec.out) if spec.out else None)
    if out is None:
        raise UserError("arguments", "--out", "name the results folder, e.g. --out render/sweeps/k-delay")
    return spec, out


def run(args: argparse.Namespace) -> int:
    from assistbot.errors import UserError

    if args.list_paths:
        from assistbot.sweep.spec import valid_paths

        print("\n".join(valid_paths()))
        return 0
    if args.executor == "local" and args.address:
        raise UserError("--address", args.address, "joins a Ray cluster: add --executor ray")
    spec, out = build_spec(args)
    if args.dry_run:
        return _dry_run(spec, out)

    from assistbot.sweep.executors import make_executor
    from assistbot.sweep.runner import run_sweep

    executor = make_executor(args.executor, workers=args.workers, address=args.address, cpus=args.cpus)
    try:
        outcome = run_sweep(spec, out, executor=executor, progress=not args.no_progress, keep_runs=args.keep_runs)
    except KeyboardInterrupt as exc:
        o = getattr(exc, "outcome", None)
        done = f" ({o.skipped + o.ran} of {o.total} episodes saved)" if o is not None else ""
        sys.stderr.write(f"interrupted{done}; run the same command again to resume\n")
        return 130
    rate = f", {60 * outcome.ran / outcome.seconds:.1f} episodes/min" if outcome.ran and outcome.seconds > 0 else ""
    print(f"sweep: {outcome.skipped + outcome.ran} of {outcome.total} episodes in {out}/results.csv "
          f"({outcome.ran} run now, {outcome.succeeded} drank{rate})")
    if outcome.aborted:
        sys.stderr.write(f"sweep stopped: {outcome.aborted}; see {out}/errors.csv\n")
        return 1
    if outcome.crashed:
        sys.stderr.write(f"{outcome.crashed} episodes raised (see {out}/errors.csv); the same command runs them again:\n")
        for line in outcome.crashes:
            sys.stderr.write(f"  {line}\n")
        return 1
    print(f"report: assistbot report {out}")
    return 0


def _dry_run(spec, out: Path) -> int:
    from assistbot.sweep.jobs import build_jobs
    from assistbot.sweep.results import read_rows

    jobs = build_jobs(spec)
    _, rows = read_rows(out / "results.csv")
    done = {r["job_id"] for r in rows}
    paths = [p.path for p in spec.params]
    print(f"{len(jobs)} episodes ({len([j for j in jobs if j.id in done])} done in {out}): "
          f"{len(spec.scenarios)} scenario(s) x {spec.grid_size()} grid point(s) x seeds; perception {spec.perception}")
    for p in spec.params:
        print(f"  {p.path}: {', '.join(str(v) for v in p.value_list())}")
    for j in jobs[:50]:
        vals = " ".join(f"{k}={j.params[k]}" for k in paths)
        print(f"  {j.id}  {'done' if j.id in done else 'todo'}  {j.scenario} seed={j.seed} {vals}")
    if len(jobs) > 50:
        print(f"  ... and {len(jobs) - 50} more")
    return 0
