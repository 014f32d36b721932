"""Run a sweep into a folder: skip finished jobs, run the rest, write each row as it arrives.

    DIR/sweep.yaml        the sweep as last run (scenarios, parameter values, seeds, perception)
    DIR/results.csv       one row per finished episode, appended and flushed row by row
    DIR/results.parquet   the same, typed; rewritten from the CSV now and then, at the end and on interrupt
    DIR/errors.csv        episodes that raised (they run again when the sweep is resumed)
"""

from __future__ import annotations

import dataclasses
import signal
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import yaml

from assistbot.errors import UserError
from assistbot.sweep.jobs import Job, build_jobs
from assistbot.sweep.results import ResultStore, columns_for
from assistbot.sweep.spec import SweepSpec


@dataclass
class SweepOutcome:
    out: Path
    total: int  # jobs in the sweep
    skipped: int  # already in results.csv
    ran: int = 0  # finished now (rows written)
    crashed: int = 0  # raised (in errors.csv, to run again)
    succeeded: int = 0  # of those that ran now
    interrupted: bool = False
    aborted: str = ""  # why the sweep stopped early (every episode so far raised)
    seconds: float = 0.0
    executor: str = ""
    crashes: list[str] = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return not self.interrupted and not self.aborted and self.skipped + self.ran == self.total


#: stop when this many episodes have raised and none has finished: the code, not the parameters, is broken
ABORT_AFTER = 4


def check_perception(perception: str) -> None:
    """The vision path may be absent while it is being built: say so once, before any worker starts."""
    if perception != "vision":
        return
    try:
        import assistbot.episode.vision_perception  # noqa: F401
    except ImportError as exc:
        raise UserError("--perception", "vision", f"the vision perception cannot be imported ({exc}); "
                        "use --perception oracle") from None


def write_spec(spec: SweepSpec, out: Path, jobs: list[Job]) -> None:
    (out / "sweep.yaml").write_text(
        f"# written by 'assistbot sweep': {len(jobs)} episodes; 'assistbot sweep {out}/sweep.yaml --out {out}'"
        " resumes or repeats it\n" + yaml.safe_dump(spec.to_dict(), sort_keys=False), encoding="utf-8")


class _Terminate(KeyboardInterrupt):
    """SIGTERM handled like Ctrl-C: stop the workers, rewrite the Parquet file, exit 130."""


#: the folder of the kept episodes' run folders in a sweep's results folder (--keep-runs)
RUNS = "runs"


def run_sweep(spec: SweepSpec, out: str | Path, executor=None, progress: bool = True,
              on_row: Callable[[dict], None] | None = None, log: Callable[[str], None] | None = None,
              keep_runs: bool = False) -> SweepOutcome:
    """Run the jobs of ``spec`` that ``out/results.csv`` does not hold yet; with ``keep_runs`` each episode
    also writes its run folder (log, summary, figures, inspector page; no video) to ``out/runs/<job id>``.

    ``executor`` is a `LocalExecutor` or `RayExecutor` (default: a local pool on every CPU).
    Raises KeyboardInterrupt after saving when interrupted (Ctrl-C or SIGTERM); the outcome of an
    interrupted run is in the exception's ``outcome`` attribute.
    """
    from assistbot.sweep.executors import LocalExecutor

    log = log or (lambda msg: print(msg, file=sys.stderr))
    out = Path(out)
    jobs = build_jobs(spec)
    check_perception(spec.perception)
    store = ResultStore(out, columns_for(p.path for p in spec.params))
    done = store.open()
    try:
        write_spec(spec, out, jobs)
        pending = [j for j in jobs if j.id not in done]
        if keep_runs:
            pending = [dataclasses.replace(j, run_dir=str(out / RUNS / j.id)) for j in pending]
        outcome = SweepOutcome(out=out, total=len(jobs), skipped=len(jobs) - len(pending))
        stale = sorted({j.scenario for j in jobs if j.id in done and done[j.id].get("scenario_sha") not in ("", j.scenario_sha)})
        if stale:
            log(f"warning: {out}/results.csv has rows from an earlier version of {', '.join(stale)}; "
                "they are kept (use another --out to start afresh)")
        if not pending:
            log(f"sweep: all {len(jobs)} episodes are in {store.csv_path}; nothing to run")
            return outcome
        executor = executor or LocalExecutor()
        old_term = signal.getsignal(signal.SIGTERM)

        def on_term(signum, frame):
            raise _Terminate()

        in_main = _in_main_thread()
        if in_main:
            signal.signal(signal.SIGTERM, on_term)
        t0 = time.perf_counter()
        bar = None
        try:
            if hasattr(executor, "start"):
                executor.start()
            outcome.executor = executor.describe()
            log(f"sweep: {len(pending)} of {len(jobs)} episodes to run ({outcome.skipped} done) on {outcome.executor}"
                f" -> {store.csv_path}")
            if progress:
                from tqdm import tqdm

                bar = tqdm(total=len(jobs), initial=outcome.skipped, unit="ep", desc="sweep", dynamic_ncols=True,
                           smoothing=0.05, file=sys.stderr)
            for row in executor.run(pending):
                if row.get("status") == "crashed":
                    outcome.crashed += 1
                    store.append_error(row)
                    if len(outcome.crashes) < 5:
                        outcome.crashes.append(f"{row['job_id']}: {row.get('error')}")
                    if outcome.crashed >= min(ABORT_AFTER, len(pending)) and outcome.ran == 0 and not done:
                        outcome.aborted = (f"the first {outcome.crashed} episodes all raised (last: {row.get('error')}); "
                                           "stopped rather than run the rest the same way")
                        break
                else:
                    store.append(row)
                    outcome.ran += 1
                    outcome.succeeded += bool(row.get("success"))
                    if on_row is not None:
                        on_row(row)
                if bar is not None:
                    post = {"drank": f"{outcome.succeeded}/{outcome.ran}"}
                    if outcome.crashed:
                        post["crashed"] = outcome.crashed
                    bar.set_postfix(post, refresh=False)
                    bar.update(1)
        except KeyboardInterrupt as exc:
            outcome.interrupted = True
            exc.outcome = outcome  # type: ignore[attr-defined]
            raise
        finally:
            outcome.seconds = time.perf_counter() - t0
            if bar is not None:
                bar.close()
            if in_main:
                signal.signal(signal.SIGTERM, old_term)
            if hasattr(executor, "close"):
                executor.close()
        return outcome
    finally:
        store.close()


def _in_main_thread() -> bool:
    import threading

    return threading.current_thread() is threading.main_thread()
