"""``--executor ray``: a run's files as tasks on a Ray cluster.

- Files go in chunks (up to :data:`CHUNK` files per task, small enough that every CPU gets
  several tasks): a task costs about a millisecond of Ray's time, a small URDF about as
  much to check. Each task lints its files exactly as a ``--jobs`` worker does.
- With ``--confirm``, each engine runs in its own probe process beside the worker
  (:mod:`urdflint.engines.warm`), kept warm from one file to the next, as in a local run:
  an engine's segfault costs its probe process and that one load, which is tried once
  more in a new process and then reported (E005). One task per (file, engine) pair, the
  model handed from task to task, was built and measured first: 2.3 times slower (each
  file read twice, 4 tasks per file, and a worker per concurrent probe, each with its
  own engines to import).
- A task whose worker process dies is retried once by Ray. A chunk lost twice is split
  into single files, each tried again; a file whose task is lost twice more is reported
  as an error of the run (exit 2), never silently left out.

Outcomes come back in the order tasks finish; the run puts them back in input order for
the JSON, SARIF and text reports (the same as ``--jobs 1``), and writes records as they
come. Workers run from the driver's working folder with its environment, so relative
paths, ``$(env)`` and package paths mean the same on a worker: a cluster of several
machines needs the files at the same paths on every node (a shared file system) and
urdflint installed in the same version.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
import uuid
from collections.abc import Iterator, Sequence
from dataclasses import replace
from typing import Any

from urdflint.cli import parallel
from urdflint.cli.common import UsageError

CHUNK = 16  # most files per task
TASKS_PER_CPU = 8  # chunks are small enough for this many tasks per CPU
IN_FLIGHT_PER_CPU = 4  # tasks submitted ahead of the finished ones, per CPU


def connect(args: argparse.Namespace) -> Any:
    """The ``ray`` module, connected: ``--ray-address``, ``$RAY_ADDRESS``, a Ray already
    running on this machine, or a new local one with ``--jobs`` CPUs (default: all)."""
    try:
        import ray
    except ImportError:
        from urdflint.model.optional import install_command

        raise UsageError(
            f"--executor ray needs Ray, which is not installed: {install_command('cluster')}"
        ) from None
    if ray.is_initialized():
        return ray
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
    quiet: dict[str, Any] = {"log_to_driver": False, "logging_level": logging.ERROR}
    address = args.ray_address or os.environ.get("RAY_ADDRESS")
    if address and address != "auto":
        problem = unreachable(address)
        if problem:
            raise UsageError(f"--executor ray: no Ray cluster answers at {address}: {problem}")
    running = address or _running_here()
    try:
        if running:
            ray.init(address=running, **quiet)
        else:  # no Ray here: a new one for this run, on this machine's CPUs
            cpus = args.jobs or parallel.cpu_count()
            ray.init(num_cpus=cpus, include_dashboard=False, **quiet)
    except Exception as exc:  # (Ray raises many kinds; one line for each)
        where = running or "a new local Ray"
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise UsageError(f"--executor ray: cannot start or join {where}: {reason}") from None
    return ray


def unreachable(address: str, timeout: float = 3.0) -> str | None:
    """Why nothing answers at ``host:port`` (``ray://host:port``), or None: Ray itself
    retries an address that does not answer for minutes."""
    import socket

    text = address.removeprefix("ray://")
    host, _, port = text.rpartition(":")
    if not host or not port.isdigit():
        return "expected host:port or ray://host:port"
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout):
            return None
    except OSError as exc:
        return exc.strerror or str(exc) or type(exc).__name__


def _running_here() -> str | None:
    """The address of a Ray started on this machine (``ray start --head``) that answers."""
    import tempfile

    folder = os.environ.get("RAY_TMPDIR") or os.path.join(tempfile.gettempdir(), "ray")
    try:
        with open(os.path.join(folder, "ray_current_cluster"), encoding="utf-8") as handle:
            address = handle.read().strip()
    except OSError:
        return None
    return address if address and unreachable(address, 1.0) is None else None


def run(
    tasks: Sequence[parallel.Task], context: Any, flags: parallel.Flags, args: argparse.Namespace
) -> Iterator[tuple[int, parallel.Outcome]]:
    """Each task's ``(index, outcome)``, in the order they finish."""
    if not tasks:
        return
    ray = connect(args)
    cpus = max(1, int(ray.cluster_resources().get("CPU", 1)))
    work = parallel.lint_recorded if flags.record else parallel.lint_one
    run_id = uuid.uuid4().hex  # a worker keeps one context per run (its mesh cache...)
    shared = ray.put((run_id, replace(context, environ=dict(os.environ)), flags, work, os.getcwd()))
    lint = ray.remote(max_retries=1)(_lint_chunk)  # retried once when its worker dies
    progress = parallel.Progress(len(tasks), sys.stderr)
    try:
        yield from _chunked(ray, lint, shared, tasks, cpus, progress)
    finally:
        progress.close()


def _chunked(
    ray: Any,
    lint: Any,
    shared: Any,
    tasks: Sequence[parallel.Task],
    cpus: int,
    progress: parallel.Progress,
) -> Iterator[tuple[int, parallel.Outcome]]:
    size = max(1, min(CHUNK, len(tasks) // (cpus * TASKS_PER_CPU)))
    waiting = [list(range(i, min(i + size, len(tasks)))) for i in range(0, len(tasks), size)]
    waiting.reverse()  # popped from the end: input order
    running: dict[Any, list[int]] = {}  # ref -> its files' indexes
    limit = cpus * IN_FLIGHT_PER_CPU
    while waiting or running:
        while waiting and len(running) < limit:
            chunk = waiting.pop()
            ref = lint.remote(shared, [tasks[i] for i in chunk])
            running[ref] = chunk
        (ref,), _ = ray.wait(list(running), num_returns=1)
        chunk = running.pop(ref)
        try:
            outcomes = ray.get(ref)
        except Exception as exc:  # (the worker died, twice: Ray retried once)
            if len(chunk) > 1:
                waiting.extend([i] for i in reversed(chunk))  # find the file that kills it
                continue
            outcomes = [_lost(tasks[chunk[0]], exc)]
        for index, outcome in zip(chunk, outcomes, strict=True):
            progress.step()
            yield index, outcome


def _lost(task: parallel.Task, exc: BaseException) -> parallel.Outcome:
    """A file whose task failed: its worker died twice, or the task raised."""
    import ray.exceptions

    if isinstance(exc, ray.exceptions.RayTaskError):  # raised in the task: say what
        cause = exc.cause if exc.cause is not None else exc
        why = f"{type(cause).__name__}: {cause}".strip().splitlines()[0]
        return parallel.Outcome(task.shown, error=f"{task.shown}: internal error on Ray: {why}")
    reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    return parallel.Outcome(
        task.shown, error=f"{task.shown}: its Ray worker was lost twice ({reason[:200]})"
    )


# -- on the workers ---------------------------------------------------------------------------


_RUN: tuple[str, Any] | None = None  # this worker's run: its id and (context, flags, ...)


def _shared(value: Any) -> tuple[Any, Any, Any, str]:
    """The run's (context, flags, work, cwd), deserialized once per worker and run: Ray
    hands each task a new copy, and a context per task would read every mesh again."""
    global _RUN
    run_id, *rest = value
    if _RUN is None or _RUN[0] != run_id:
        _RUN = (run_id, tuple(rest))
    context, flags, work, cwd = _RUN[1]
    return context, flags, work, cwd


def _enter(cwd: str) -> None:
    """Run from the driver's working folder (relative paths, as given)."""
    if os.getcwd() != cwd:
        try:
            os.chdir(cwd)
        except OSError as exc:
            raise RuntimeError(
                f"this Ray node has no folder {cwd} (the files must be at the same paths "
                "on every node)"
            ) from exc


def _lint_chunk(shared: Any, tasks: list[parallel.Task]) -> list[parallel.Outcome]:
    context, flags, work, cwd = _shared(shared)
    _enter(cwd)
    return [work(task, context, flags) for task in tasks]
