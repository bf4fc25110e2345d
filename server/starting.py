"""How a lint worker process starts, and why it did not.

:func:`launch` starts one worker from the fork server (``_preload`` warmed it), running
:data:`BOOTSTRAP`: only builtins are unpickled before it (``exec``, the pipe, two numbers),
so when urdflint cannot be imported in the worker, the bootstrap catches the error and sends
its last line back as the reason, with the traceback. :func:`greeting` waits for the
worker's hello and turns anything else (that reason, a silent worker, an early death) into
a sentence for ``/readyz`` and the details for the log.

Workers never import from the folder the server was started in
(:func:`away_from_current_folder`): a ``urdflint`` folder or an ``xacro.py`` there would
shadow the installed packages, because a worker gets the server's ``sys.path`` (where
uvicorn put ``''``) and the fork server runs ``python -c`` (which puts ``''`` first).
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import sys
import threading
from collections.abc import Iterator
from typing import Any

STARTUP_TIMEOUT = 60.0  # seconds a new worker may take to import urdflint and say hello
# What a new worker runs (``conn``, ``memory`` and ``timeout`` are its globals).
BOOTSTRAP = """
try:
    from urdflint.server.worker import WorkerConfig, main
except BaseException as exc:
    import sys, traceback
    reason = traceback.format_exception_only(exc)[-1].strip()
    found = getattr(sys.modules.get("urdflint"), "__path__", None)
    if found is not None:
        reason += f" (urdflint imported from {', '.join(found)})"
    conn.send(("failed", reason, traceback.format_exc()))
    raise SystemExit(1) from None
main(conn, WorkerConfig(memory=memory, timeout=timeout))
"""
_STARTING = threading.Lock()  # a start changes sys.path and the environment briefly


def signal_name(exitcode: int | None) -> str:
    """How a process ended: ``SIGKILL``, ``exit code 1``, or ``unknown``."""
    if exitcode is None:
        return "unknown"
    if exitcode < 0:
        with contextlib.suppress(ValueError):
            return signal.Signals(-exitcode).name
    return f"exit code {exitcode}"


def context() -> Any:
    """The fork server (preloading ``_preload``), or ``spawn`` where there is none."""
    try:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["urdflint.server._preload"])
        return ctx
    except ValueError:  # pragma: no cover - no fork server on this platform
        return multiprocessing.get_context("spawn")


@contextlib.contextmanager
def away_from_current_folder() -> Iterator[None]:
    """While a worker (and the fork server) starts: the current folder off ``sys.path``.

    ``PYTHONSAFEPATH=1`` keeps ``''`` off the fork server's path. An entry that
    ``PYTHONPATH`` names on purpose stays; both are restored afterwards.
    """
    here = os.path.realpath(os.curdir)
    chosen = {os.path.realpath(p) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p}

    def keep(entry: str) -> bool:
        real = os.path.realpath(entry or os.curdir)
        return real != here or (bool(entry) and real in chosen)

    with _STARTING:
        saved_path, saved_safe = list(sys.path), os.environ.get("PYTHONSAFEPATH")
        sys.path[:] = [entry for entry in saved_path if keep(entry)]
        os.environ["PYTHONSAFEPATH"] = "1"
        try:
            yield
        finally:
            sys.path[:] = saved_path
            if saved_safe is None:
                os.environ.pop("PYTHONSAFEPATH", None)
            else:
                os.environ["PYTHONSAFEPATH"] = saved_safe


def launch(memory: int, timeout: float) -> tuple[Any, Any]:
    """Start one worker process; its process object and the parent's end of its pipe."""
    ctx = context()
    parent, child = ctx.Pipe(duplex=True)
    setup = {"conn": child, "memory": memory, "timeout": timeout}
    process = ctx.Process(target=exec, args=(BOOTSTRAP, setup), name="urdflint-worker")
    process.daemon = True
    with away_from_current_folder():
        process.start()
    child.close()
    return process, parent


def greeting(process: Any, conn: Any, wait: float = STARTUP_TIMEOUT) -> tuple[str, str] | None:
    """Wait for the worker's hello: ``None`` once it is ready, else why it did not start
    (a sentence) and the details (the worker's traceback, when it could send one)."""
    hello: Any = None
    with contextlib.suppress(EOFError, OSError):
        hello = conn.recv() if conn.poll(wait) else "silent"
    if hello == "ready":
        return None
    if isinstance(hello, tuple) and len(hello) == 3 and hello[0] == "failed":
        return str(hello[1]), str(hello[2])
    if hello == "silent":
        return f"a worker did not answer within {wait:g} s", ""
    process.join(1)  # it is ending: its exit code tells how
    ended = signal_name(process.exitcode)
    return f"a worker ended ({ended}) before it could say why (see the server log)", ""
