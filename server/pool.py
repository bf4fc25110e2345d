"""Warm lint worker processes with a hard per-job time limit.

Why processes and not threads: a runaway job (xacro evaluating ``${10**10**8}``, Pinocchio
on a pathological tree) cannot be stopped in a thread, and xacro keeps its state in
module globals. Each worker runs one job at a time (``worker.main``); the pool

- starts ``size`` workers from a fork server that has already imported urdflint and the
  heavy libraries (``_preload``), falling back to ``spawn`` where there is no fork server;
- hands a job to an idle worker from a thread, so the event loop only awaits: ``/healthz``
  and the other requests are answered while models are linted;
- kills the worker (SIGKILL, with its process group: the engine processes of a ``confirm``
  job) when a job overruns its time limit and raises
  :class:`JobTimeout`; a worker that dies on its own raises :class:`WorkerDied`. Either way a
  fresh worker takes the place, in the background, before the slot is given out again;
- replaces a worker after ``max_tasks`` jobs, to bound slow leaks;
- raises :class:`Busy` when no worker frees up within the wait limit;
- notices workers that die while starting: it counts consecutive start failures and keeps
  the last one's reason (``error``, the worker's own exception line when it could send it),
  which ``/readyz`` reports. :meth:`Pool.keep_starting` retries the start a few times with
  a back-off; when no worker ever started (or every slot was lost), it gives up: ``failed``
  holds the reason and ``on_failed`` is called (the app then stops the server, non-zero).

How a worker starts, away from the folder the server was started in, and how it tells
why it could not, is in ``starting.py``.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import signal
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from .starting import greeting, launch, signal_name

log = logging.getLogger("urdflint.server.pool")
START_ATTEMPTS = 4  # pool starts tried (0.5, 1, 2 s apart) before the server gives up
START_BACKOFF = 0.5  # seconds before the second start attempt; doubles after each


class PoolError(Exception):
    pass


class JobTimeout(PoolError):
    pass


class WorkerDied(PoolError):
    def __init__(self, exitcode: int | None) -> None:
        self.exitcode = exitcode
        name = signal_name(exitcode)
        super().__init__(f"the lint worker ended ({name}) while checking this input")


class Busy(PoolError):
    pass


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
        """SIGKILL the worker and its process group: the engines it started (``confirm``)
        die with it (``worker.main`` makes each worker the leader of its own group)."""
        first, self.alive = self.alive, False
        if first:  # once, while its pid (the group's id) is still known to be this worker's
            with contextlib.suppress(OSError):
                os.killpg(self.process.pid, signal.SIGKILL)
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
    failures: int = 0  # consecutive worker starts that failed
    error: str | None = None  # why the last worker start failed (None once one succeeds)
    failed: str | None = None  # why the pool gave up: no worker can start
    on_failed: Callable[[str], None] | None = None  # told once, when the pool gives up
    _lost: int = 0  # slots whose worker could not be replaced

    @property
    def ready(self) -> bool:
        started = self._started is not None and self._started.is_set()
        return started and not self._closed and self.failed is None

    @property
    def problem(self) -> str | None:
        """Why no job can run now (``None`` when workers are up or still starting fine)."""
        if self.failed is not None:
            return self.failed
        if self.error is not None and (not self.ready or self._lost >= self.size):
            return f"the lint workers cannot start: {self.error}"
        return None

    def spawn(self) -> Worker:
        """Start one worker process (blocking: call it from a thread); counts the start."""
        try:
            process, conn = launch(self.memory, self.timeout)
        except Exception as exc:  # no process at all (out of processes or memory, say)
            self._starts(f"cannot start a process: {exc!r}")
            raise PoolError(self.error) from exc
        worker = Worker(process, conn)
        with self._lock:
            self._all.add(process.pid)
        failure = greeting(process, conn)
        if failure is None:
            self._starts(None)
            return worker
        worker.kill()
        reason, details = failure
        if reason != self.error:  # the details once, not for every worker and attempt
            log.error("a lint worker could not start: %s\n%s", reason, details.rstrip())
        self._starts(reason)
        with self._lock:
            self._all.discard(process.pid)
        raise PoolError(reason)

    def _starts(self, reason: str | None) -> None:
        """Count a worker start: a success resets the count, a failure keeps its reason."""
        with self._lock:
            self.failures = 0 if reason is None else self.failures + 1
            self.error = reason

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
        started: list[Worker | BaseException] = []
        try:  # the first start also starts the fork server, the others share it
            started.append(await loop.run_in_executor(self._threads, self.spawn))
        except Exception as exc:
            started.append(exc)
        else:
            started += await asyncio.gather(
                *(loop.run_in_executor(self._threads, self.spawn) for _ in range(self.size - 1)),
                return_exceptions=True,
            )
        workers = [w for w in started if isinstance(w, Worker)]
        if len(workers) < len(started):
            for worker in workers:
                await loop.run_in_executor(self._threads, worker.kill)
            reason = self.error or next(e for e in started if not isinstance(e, Worker))
            raise PoolError(f"the lint workers could not start: {reason}")
        self._idle.extend(workers)
        self._started = self._started or asyncio.Event()
        self._started.set()

    async def keep_starting(
        self, attempts: int = START_ATTEMPTS, backoff: float = START_BACKOFF
    ) -> bool:
        """Start the workers, trying ``attempts`` times with a doubling back-off.

        False when no attempt worked: the pool gives up (:meth:`give_up`).
        """
        for attempt in range(attempts):
            try:
                await self.start()
                return True
            except PoolError as exc:
                log.error("start attempt %d of %d failed: %s", attempt + 1, attempts, exc)
                if self._closed:
                    return False
            if attempt + 1 < attempts:
                await asyncio.sleep(backoff * 2**attempt)
        self.give_up(f"no lint worker could start ({attempts} attempts): {self.error}")
        return False

    def give_up(self, reason: str) -> None:
        """No job can ever run: remember why and tell ``on_failed`` (once)."""
        if self.failed is not None or self._closed:
            return
        self.failed = reason
        log.critical("%s", reason)
        if self.on_failed is not None:
            self.on_failed(reason)

    async def run(self, job: Any, wait: float | None = None) -> dict[str, Any]:
        """Run ``job`` in a worker; :class:`Busy`, :class:`JobTimeout`, :class:`WorkerDied`."""
        if self._closed:
            raise Busy("the server is shutting down")
        if self.failed is not None:
            raise Busy(self.failed)
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
        except BaseException as exc:
            if isinstance(exc, WorkerDied):
                log.warning("lint worker %d died: %s; starting another", worker.process.pid, exc)
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
        for attempt in range(START_ATTEMPTS):
            try:
                fresh = await loop.run_in_executor(self._threads, self.spawn)
                break
            except Exception as exc:
                log.error("cannot replace a lint worker (attempt %d): %s", attempt + 1, exc)
                await asyncio.sleep(START_BACKOFF * 2**attempt)
        else:  # the slot is lost; with every slot lost, no job can ever run
            self._lost += 1
            if self._lost >= self.size:
                self.give_up(f"every lint worker died and none could be restarted: {self.error}")
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
            "start_failures": self.failures,
            "lost": self._lost,
        }
