"""Where a sweep's episodes run: a local process pool, or Ray tasks on a cluster.

Both take a list of jobs and yield result rows as the episodes finish, in
whatever order that is; the caller writes them. Each episode runs with one
thread (`worker.THREAD_ENV`): the processes are the parallelism.
"""

from __future__ import annotations

import os
from typing import Iterator

from assistbot.errors import UserError
from assistbot.sweep.jobs import Job
from assistbot.sweep.worker import THREAD_ENV, init_worker, limit_threads, run_job


def available_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


class LocalExecutor:
    """A pool of K spawned processes (a fresh interpreter each: no state shared with the parent)."""

    name = "local"

    def __init__(self, workers: int | None = None) -> None:
        if workers is not None and workers < 1:
            raise UserError("--workers", str(workers), "at least 1")
        self.workers = workers or available_cpus()
        self._pool = None

    def describe(self) -> str:
        return f"local pool, {self.workers} worker{'s' if self.workers != 1 else ''}"

    def run(self, jobs: list[Job]) -> Iterator[dict]:
        import multiprocessing as mp
        from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
        from concurrent.futures.process import BrokenProcessPool

        if not jobs:
            return
        limit_threads()  # inherited by the spawned workers' environment
        n = min(self.workers, len(jobs))
        self._pool = ProcessPoolExecutor(max_workers=n, mp_context=mp.get_context("spawn"), initializer=init_worker)
        queue = list(reversed(jobs))
        running = {}
        try:
            # keep a few jobs in flight per worker, not the whole list: fewer pickles in memory,
            # and an interrupt has little to cancel
            while queue or running:
                while queue and len(running) < 2 * n:
                    job = queue.pop()
                    running[self._pool.submit(run_job, job)] = job
                finished, _ = wait(running, return_when=FIRST_COMPLETED)
                for fut in finished:
                    job = running.pop(fut)
                    try:
                        yield fut.result()
                    except BrokenProcessPool:
                        raise UserError("sweep", "worker", "a worker process died (killed, out of memory or a crash "
                                        "in native code); finished rows are saved: run the same command to resume") from None
        finally:
            self.close()

    def close(self) -> None:
        pool, self._pool = self._pool, None
        if pool is None:
            return
        procs = list(getattr(pool, "_processes", {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for p in procs:  # an interrupted sweep does not wait for running episodes
            if p.is_alive():
                p.terminate()
        for p in procs:
            p.join(timeout=5)


def _ray_address_reachable(address: str) -> str | None:
    """None when ``host:port`` accepts a TCP connection, else why not ("auto" and ray:// are left to Ray)."""
    import socket

    if address == "auto" or "://" in address:
        return None
    host, sep, port = address.rpartition(":")
    if not sep or not port.isdigit():
        return f"expected HOST:PORT (e.g. 10.0.0.5:6379), auto, or ray://HOST:10001, got {address!r}"
    try:
        socket.create_connection((host, int(port)), timeout=5).close()
    except OSError as exc:
        return f"cannot connect to {address}: {exc.strerror or exc}"
    return None


class RayExecutor:
    """Episodes as Ray tasks (one CPU each): ``address="auto"`` or ``HOST:PORT`` joins a running
    cluster, ``ray://HOST:10001`` connects as a Ray client, None starts a local Ray with ``cpus`` CPUs.

    Every node must have assistbot installed (same version, with its assets): tasks import it.
    """

    name = "ray"

    def __init__(self, address: str | None = None, cpus: int | None = None) -> None:
        if cpus is not None and cpus < 1:
            raise UserError("--cpus", str(cpus), "at least 1")
        self.address = address
        self.cpus = cpus
        self._started = False
        self._ray = None

    def describe(self) -> str:
        if self._ray is None:
            return "ray"
        total = int(self._ray.cluster_resources().get("CPU", 0))
        where = f"cluster at {self.address}" if self.address else "local Ray"
        return f"{where}, {total} CPU{'s' if total != 1 else ''}"

    def start(self) -> None:
        limit_threads()
        try:
            import ray
        except ImportError:
            raise UserError("--executor", "ray", "Ray is not installed; pip install 'ray>=2.9'") from None
        if ray.is_initialized():
            self._ray = ray
            return
        if self.address:
            why = _ray_address_reachable(self.address)
            if why:
                raise UserError("--address", self.address, f"no Ray cluster there ({why}); start one with "
                                "'ray start --head' on the head node, or leave out --address for a local Ray")
        kwargs: dict = dict(logging_level="ERROR", log_to_driver=False, runtime_env={"env_vars": dict(THREAD_ENV)})
        if self.address:
            kwargs["address"] = self.address
        else:  # a private local Ray ("local": never an existing cluster, nor a stale /tmp/ray/ray_current_cluster)
            kwargs.update(address="local", num_cpus=self.cpus or available_cpus(), include_dashboard=False)
        try:
            with _quiet_stderr():  # Ray's C++ core logs each failed connection attempt
                ray.init(**kwargs)
        except (ConnectionError, TimeoutError, RuntimeError, ValueError) as exc:
            msg = " ".join(str(exc).split())[:300]
            hint = "for a cluster run 'ray start --head' there first"
            if self.address and self.address != "auto" and "://" not in self.address:
                hint += ("; if it uses token authentication (Ray >= 2.59 turns it on for clusters started on this "
                         "machine), set RAY_AUTH_MODE=token and its token (RAY_AUTH_TOKEN, see 'ray get-auth-token'), "
                         "or use --address auto on the head node")
            raise UserError("--address", str(self.address or "local"), f"cannot start or join Ray: {msg}; {hint}") from None
        self._ray = ray
        self._started = True

    def run(self, jobs: list[Job]) -> Iterator[dict]:
        if self._ray is None:
            self.start()
        ray = self._ray
        if not jobs:
            return
        task = ray.remote(num_cpus=1, max_retries=2)(run_job)
        cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
        queue = list(reversed(jobs))
        running: dict = {}
        try:
            while queue or running:
                while queue and len(running) < 2 * cpus:
                    job = queue.pop()
                    running[task.remote(job)] = job
                ready, _ = ray.wait(list(running), num_returns=1)
                for ref in ready:
                    job = running.pop(ref)
                    try:
                        yield ray.get(ref)
                    except ray.exceptions.RayError as exc:  # the task's worker died; the row is a crash
                        yield {"job_id": job.id, "scenario": job.scenario, **job.params, "seed": job.seed,
                               "status": "crashed", "error": f"{type(exc).__name__}: {str(exc).splitlines()[0][:300]}",
                               "traceback": "", "wall_seconds": None}
        finally:
            for ref in running:
                try:
                    ray.cancel(ref, force=True)
                except Exception:  # noqa: BLE001 - best effort on the way out
                    pass

    def close(self) -> None:
        if self._ray is not None and self._started:
            self._ray.shutdown()
        self._ray = None
        self._started = False


class _quiet_stderr:
    """Send file descriptor 2 to /dev/null for a moment (C++ logs bypass Python's sys.stderr)."""

    def __enter__(self):
        import sys

        sys.stderr.flush()
        self._saved = os.dup(2)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
        os.close(devnull)
        return self

    def __exit__(self, *exc) -> None:
        os.dup2(self._saved, 2)
        os.close(self._saved)


def make_executor(kind: str, workers: int | None = None, address: str | None = None, cpus: int | None = None):
    if kind == "local":
        if address:
            raise UserError("--address", address, "only with --executor ray")
        return LocalExecutor(workers)
    if kind == "ray":
        return RayExecutor(address, cpus if cpus is not None else workers)
    raise UserError("--executor", kind, "use local or ray")
