"""A lint worker process: runs one job at a time, fenced off from files, network and children.

The pool (``pool.py``) starts each worker with :func:`main`, sends it jobs over a pipe
and kills it when a job overruns the request's time limit. Inside, besides urdflint's own
confinement (``Context(root=...)``: the resolver, the mesh cache and xacro only see the
request's folder), every job runs under an audit hook (PEP 578) that refuses, while the job
runs, file access outside the request's folder and the Python installation, the network
and new processes (``fence.py``; with ``confirm``, only the engine probe: ``confirming.py``).
Each worker leads its own process group, so killing it kills the engines it started; each
also gets an address-space limit
(``RLIMIT_AS``) and, per job, a CPU-time limit (``RLIMIT_CPU``) a little over the request
timeout, as a second fence behind the pool's wall-clock kill.

The jobs themselves (:class:`CheckJob`, :class:`ReadyJob`) are in ``jobs.py``; their names,
and the fence's, are importable from here too.
"""

from __future__ import annotations

import contextlib
import os
import traceback
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdflint.server.threads import limit_threads

from .fence import (
    DENIED_ALWAYS,
    DEVICES,
    FENCE,
    PATH_EVENTS,
    WRITE_FLAGS,
    fenced,
    install_fence,
    set_cpu_limit,
    set_memory_limit,
)
from .jobs import TETRA, TINY, CheckJob, ReadyJob, check, ready, reply, run

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

__all__ = [
    "DENIED_ALWAYS",
    "DEVICES",
    "FENCE",
    "PATH_EVENTS",
    "TETRA",
    "TINY",
    "WRITE_FLAGS",
    "CheckJob",
    "ReadyJob",
    "WorkerConfig",
    "check",
    "fenced",
    "install_fence",
    "main",
    "ready",
    "reply",
    "run",
    "set_cpu_limit",
    "set_memory_limit",
]


@dataclass(frozen=True)
class WorkerConfig:
    """What a worker is started with: its address-space limit and the job time limit."""

    memory: int = 0
    timeout: float = 60.0


def own_process_group() -> None:
    """Lead a process group of its own, so the pool's kill reaches the engines this worker
    starts (``confirm``); and keep the current folder off their ``sys.path``."""
    with contextlib.suppress(OSError):
        os.setpgid(0, 0)
    os.environ["PYTHONSAFEPATH"] = "1"


def main(conn: Connection, config: WorkerConfig) -> None:
    """The worker loop: say ``"ready"`` (or ``("failed", reason)``), then receive a job and
    send its reply until ``None`` ends the loop. The pool starts it (``starting.BOOTSTRAP``).
    """
    try:
        limit_threads()
        set_memory_limit(config.memory)
        own_process_group()
        with contextlib.suppress(ImportError):
            from . import _preload  # noqa: F401  (already imported when forked from the forkserver)
        install_fence()
    except BaseException as exc:  # the pool reports why this worker could not start
        reason = traceback.format_exception_only(exc)[-1].strip()
        conn.send(("failed", reason, traceback.format_exc()))
        raise SystemExit(1) from None
    conn.send("ready")
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job is None:
            return
        set_cpu_limit(config.timeout * 1.5 + 5)
        answer = run(job)
        try:
            conn.send(answer)
        except (OSError, ValueError):
            return
