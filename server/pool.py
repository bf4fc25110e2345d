"""Warm lint worker processes with a hard per-job time limit.

Why processes and not threads: a runaway job (xacro evaluating ``${10**10**8}``, Pinocchio
on a pathological tree) cannot be stopped in a thread, and xacro keeps its state in
module globals. Each worker runs one job at a time (``worker.main``); the pool

- starts ``size`` workers from a fork server that has already imported urdflint and the
  heavy libraries (``_preload``), falling back to ``spawn`` where there is no fork server;
- hands a job to an idle worker from a thread, so the event loop only awaits: ``/healthz``
  and the other requests are answered while models are linted;
- kills the worker (SIGKILL) when a job overruns its time limit and raises
  :class:`JobTimeout`; a worker that dies on its own raises :class:`WorkerDied`. Either way a
  fresh worker takes the place, in the background, before the slot is given out again;
- replaces a worker after ``max_tasks`` jobs, to bound slow leaks;
- raises :class:`Busy` when no worker frees up within the wait limit.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import multiprocessing
import signal
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from .worker import WorkerConfig, main

log = logging.getLogger("urdflint.server.pool")
STARTUP_TIMEOUT = 60.0  # seconds a new worker may take to import urdflint and say hello


class PoolError(Exception):
    pass


class JobTimeout(PoolError):
    pass


class WorkerDied(PoolError):
    def __init__(self, exitcode: int | None) -> None:
        self.exitcode = exitcode
        name = _signal_name(exitcode)
        super().__init__(f"the lint worker ended ({name}) while checking this input")


class Busy(PoolError):
    pass


def _signal_name(exitcode: int | None) -> str:
    if exitcode is None:
        return "unknown"
    if exitcode < 0:
        with contextlib.suppress(ValueError):
            return signal.Signals(-exitcode).name
    return f"exit code {exitcode}"


def _context() -> Any:
    try:
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["urdflint.server._preload"])
        return ctx
    except ValueError:  # pragma: no cover - no fork server on this platform
        return multiprocessing.get_context("spawn")


@dataclass
class Worker:
    process: Any
    conn: Any
    jobs: int = 0
    alive: bool = True

    def call(self, job: Any, timeout: float) -> dict[str, Any]:
        """Send ``job`` and wait for the reply (in a pool thread, never on the event loop)."""
        self.jobs += 1
        try:
            self.conn.send(job)
            if not self.conn.poll(timeout):
                self.kill()
                raise JobTimeout()
            answer: dict[str, Any] = self.conn.recv()
            return answer
        except (EOFError, OSError, BrokenPipeError):
            self.kill()
            code = self.process.exitcode
            if code == -signal.SIGXCPU:
                raise JobTimeout() from None
            raise WorkerDied(code) from None

    def kill(self) -> None:
        self.alive = False
        with contextlib.suppress(Exception):
            self.process.kill()
        self.process.join(5)
        with contextlib.suppress(Exception):
            self.conn.close()

    def stop(self) -> None:
        """Ask the worker to finish, then make sure it is gone."""
        with contextlib.suppress(Exception):
            self.conn.send(None)
        self.process.join(2)
        if self.process.is_alive():
            self.kill()
        self.alive = False
        with contextlib.suppress(Exception):
            self.conn.close()


@dataclass
class Pool:
    size: int
    timeout: float
    memory: int = 0
    max_tasks: int = 500
    _idle: list[Worker] = field(default_factory=list)
    _all: set[int] = field(default_factory=set)
    _slots: asyncio.Semaphore | None = None
    _threads: ThreadPoolExecutor | None = None
    _started: asyncio.Event | None = None
    _starting: asyncio.Task[None] | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock)
    _tasks: set[asyncio.Task[None]] = field(default_factory=set)
    _closed: bool = False

    @property
    def ready(self) -> bool:
        return self._started is not None and self._started.is_set() and not self._closed

    def spawn(self) -> Worker:
        """Start one worker process (blocking: call it from a thread)."""
        ctx = _context()
        parent, child = ctx.Pipe(duplex=True)
        process = ctx.Process(
            target=main,
            args=(child, WorkerConfig(memory=self.memory, timeout=self.timeout)),
            name="urdflint-worker",
            daemon=True,
        )
        process.start()
        child.close()
        worker = Worker(process, parent)
        with self._lock:
            self._all.add(process.pid)
        try:  # the worker says hello once it has bootstrapped
            if parent.poll(STARTUP_TIMEOUT) and parent.recv() == "ready":
                return worker
        except (EOFError, OSError):
            pass
        worker.kill()
        with self._lock:
            self._all.discard(process.pid)
        raise PoolError(f"a lint worker did not start ({_signal_name(process.exitcode)})")

    async def start(self) -> None:
        """Start the workers once (in threads: the first start also starts the fork server).

        Concurrent callers share one attempt; a failed attempt raises :class:`PoolError`
        to each of them and the next call tries again.
        """
        if self._started is not None and self._started.is_set():
            return
        if self._starting is None:
            self._starting = asyncio.get_running_loop().create_task(self._start())
        starting = self._starting
        try:
            await asyncio.shield(starting)
        except PoolError:
            if self._starting is starting:
                self._starting = None
            raise

    async def _start(self) -> None:
        if self._threads is None:
            self._slots = asyncio.Semaphore(self.size)
            self._threads = ThreadPoolExecutor(
                max_workers=2 * self.size + 2, thread_name_prefix="urdflint-pool"
            )
        loop = asyncio.get_running_loop()
        started: list[Worker] = []
        try:
            started.append(await loop.run_in_executor(self._threads, self.spawn))
            started += await asyncio.gather(
                *(loop.run_in_executor(self._threads, self.spawn) for _ in range(self.size - 1))
            )
        except Exception as exc:
            for worker in started:
                worker.kill()
            log.error("the lint workers did not start: %r", exc)
            raise PoolError("the lint workers could not start (see the server log)") from exc
        self._idle.extend(started)
        self._started = self._started or asyncio.Event()
        self._started.set()

    async def run(self, job: Any, wait: float | None = None) -> dict[str, Any]:
        """Run ``job`` in a worker; :class:`Busy`, :class:`JobTimeout`, :class:`WorkerDied`."""
        if self._closed:
            raise Busy("the server is shutting down")
        try:
            await self.start()
        except PoolError as exc:
            raise Busy(str(exc)) from None
        assert self._slots is not None and self._threads is not None
        deadline = self.timeout if wait is None else wait
        try:
            await asyncio.wait_for(self._slots.acquire(), deadline)
        except TimeoutError:
            raise Busy("no lint worker became free in time") from None
        worker = self._idle.pop()
        loop = asyncio.get_running_loop()
        future = loop.run_in_executor(self._threads, worker.call, job, self.timeout)
        try:
            answer = await asyncio.shield(future)
        except asyncio.CancelledError:
            # The request was cancelled: the job finishes in its worker, then the slot frees.
            self._later(self._after(future, worker))
            raise
        except BaseException:
            self._later(self._replace(worker))
            raise
        self._give_back(worker)
        return answer

    def _give_back(self, worker: Worker) -> None:
        assert self._slots is not None
        if worker.jobs >= self.max_tasks:
            self._later(self._replace(worker, graceful=True))
        else:
            self._idle.append(worker)
            self._slots.release()

    def _later(self, coroutine: Any) -> None:
        task = asyncio.get_running_loop().create_task(coroutine)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def _after(self, future: asyncio.Future[Any], worker: Worker) -> None:
        try:
            await future
        except BaseException:
            await self._replace(worker)
            return
        self._give_back(worker)

    async def _replace(self, worker: Worker, graceful: bool = False) -> None:
        """A new worker takes the place of ``worker``, then the slot is free again."""
        loop = asyncio.get_running_loop()
        assert self._threads is not None and self._slots is not None
        await loop.run_in_executor(self._threads, worker.stop if graceful else worker.kill)
        with self._lock:
            self._all.discard(worker.process.pid)
        if self._closed:
            return
        for attempt in range(3):
            try:
                fresh = await loop.run_in_executor(self._threads, self.spawn)
                break
            except Exception:  # pragma: no cover - cannot start a process
                log.exception("cannot start a lint worker (attempt %d)", attempt + 1)
                await asyncio.sleep(1)
        else:  # pragma: no cover
            return
        self._idle.append(fresh)
        self._slots.release()

    def pids(self) -> set[int]:
        with self._lock:
            return set(self._all)

    async def close(self) -> None:
        self._closed = True
        for task in list(self._tasks):
            task.cancel()
        workers, self._idle = self._idle, []
        if self._threads is None:
            return
        loop = asyncio.get_running_loop()
        await asyncio.gather(
            *(loop.run_in_executor(self._threads, w.stop) for w in workers),
            return_exceptions=True,
        )
        self._threads.shutdown(wait=False, cancel_futures=True)

    def stats(self) -> dict[str, Any]:
        return {
            "size": self.size,
            "idle": len(self._idle),
            "started": self.ready,
        }
