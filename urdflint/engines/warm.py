"""Warm probes: one engine process kept from one model to the next.

Starting a probe costs more than most loads: Python and the engine's import take 0.5 s of
CPU for MuJoCo and 0.3 s for PyBullet, against 0.05 to 0.2 s to load a corpus robot. So a
process that confirms many models (``--confirm`` over a dataset, each ``--jobs`` or Ray
worker, a language server confirming on save) keeps a probe per engine, started on first
use and fed one model at a time on its stdin (``python -m urdflint.engines.probe --serve
ENGINE MEMORY``). Its answer is what :func:`urdflint.engines.batch.load` gives for one
file: the report, and what the engine printed while loading the model (the first model
of a process also gets what the engine printed while starting). When the probe dies or
hangs on a model, that model gets the crash and the next model a new process.

A probe is retired after :data:`RECYCLE` models (an engine's leak stays bounded) or
:data:`IDLE` seconds unused (a long-lived server does not keep the engines' memory). Each
probe runs from its own temporary folder, where MuJoCo writes its log; the probe removes
it when its stdin closes (its parent exited, even killed), the parent when it kills it.
A forked child does not use its parent's probes.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path

from urdflint.engines.batch import MARKER, Loaded, left_log, report_of
from urdflint.engines.probe import END

RECYCLE = 200  # models per probe process
IDLE = 60.0  # seconds a probe waits unused before it is stopped
KEEP = 4  # idle probes kept per engine (threads confirming at once start more)
SETTLE = 5.0  # seconds to wait for the engine's output of a model after its report


class Probe:
    """One engine's probe process, serving one model at a time (not thread-safe: see
    :func:`borrowed`)."""

    def __init__(self, engine: str, memory: int) -> None:
        self.engine, self.memory = engine, memory
        self.proc: subprocess.Popen[bytes] | None = None
        self.folder: Path | None = None  # the current process's working folder
        self.served = 0  # models sent to the current process
        self.used = time.monotonic()

    def load(self, path: Path, timeout: float) -> Loaded:
        """Load ``path`` (within ``timeout`` seconds; for a new process, its start too)."""
        self.used = time.monotonic()
        if self.proc is None or self.proc.poll() is not None or self.served >= RECYCLE:
            failed = self._start()
            if failed is not None:
                return Loaded(path, failed=failed)
        assert self.proc is not None and self.proc.stdin is not None
        index = self.served
        self.served += 1
        try:
            self.proc.stdin.write(json.dumps(str(path)).encode() + b"\n")
            self.proc.stdin.flush()
        except OSError:  # it died between two models: its exit is this model's answer
            pass
        try:
            line = self._reports.get(timeout=timeout)
        except queue.Empty:
            return self._ended(path, hung=True)
        report = report_of(line.decode("utf-8", "replace")) if line is not None else None
        if report is None:  # stdout closed: the process died on this model
            return self._ended(path, hung=False)
        return Loaded(path, report, self._printed(index))

    def _start(self) -> str | None:
        self.close()
        self.folder = Path(tempfile.mkdtemp(prefix="urdflint-probe-"))
        command = [sys.executable, "-m", "urdflint.engines.probe", "--serve", self.engine,
                   str(self.memory)]  # fmt: skip
        try:
            pipe = subprocess.PIPE
            self.proc = subprocess.Popen(
                command, cwd=self.folder, stdin=pipe, stdout=pipe, stderr=pipe
            )
        except OSError as exc:  # the probe could not be started (missing, not allowed)
            shutil.rmtree(self.folder, ignore_errors=True)
            self.proc, self.folder = None, None
            return str(exc.strerror or exc)
        self.served = 0
        self._reports: queue.Queue[bytes | None] = queue.Queue()
        self._printed_bytes = bytearray()
        self._changed = threading.Condition()
        self._err_done = False
        self._readers = [
            threading.Thread(target=self._read_out, args=(self.proc.stdout,), daemon=True),
            threading.Thread(target=self._read_err, args=(self.proc.stderr,), daemon=True),
        ]
        for reader in self._readers:
            reader.start()
        return None

    def _read_out(self, stream: object) -> None:
        for line in stream:  # type: ignore[attr-defined]
            self._reports.put(line)
        self._reports.put(None)

    def _read_err(self, stream: object) -> None:
        while True:
            chunk = stream.read1(1 << 16)  # type: ignore[attr-defined]
            with self._changed:
                if not chunk:
                    self._err_done = True
                    self._changed.notify_all()
                    return
                self._printed_bytes += chunk
                self._changed.notify_all()

    def _printed(self, index: int) -> str:
        """What the engine printed up to the end of model ``index`` (markers removed),
        taken out of the buffer."""
        end = f"\n{END} {index}\n".encode()
        deadline = time.monotonic() + SETTLE
        with self._changed:
            while end not in self._printed_bytes and not self._err_done:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                self._changed.wait(left)
            cut = self._printed_bytes.find(end)
            cut = len(self._printed_bytes) if cut < 0 else cut + len(end)
            taken = bytes(self._printed_bytes[:cut])
            del self._printed_bytes[:cut]
        return _unmarked(taken[: -len(end)] if taken.endswith(end) else taken)

    def _ended(self, path: Path, hung: bool) -> Loaded:
        """The process died, or hung (killed here): everything it printed is this model's."""
        assert self.proc is not None
        if hung:
            self.proc.kill()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout=SETTLE)
        if self.proc.returncode is None:  # stdout closed but alive: done with it
            self.proc.kill()
            self.proc.wait()
        for reader in self._readers:
            reader.join(timeout=SETTLE)
        with self._changed:
            text = _unmarked(bytes(self._printed_bytes))
            self._printed_bytes.clear()
        if self.folder is not None:  # MuJoCo's log of the model it died on
            text += left_log(self.folder)
        status = self.proc.returncode
        self.close()
        return Loaded(path, None, text, status, hung)

    def close(self) -> None:
        """Stop the process (stdin closed: it exits; killed if it does not) and remove its
        folder."""
        proc, self.proc = self.proc, None
        if proc is not None:
            with contextlib.suppress(OSError):
                if proc.stdin is not None:
                    proc.stdin.close()
            try:
                proc.wait(timeout=SETTLE)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            for stream in (proc.stdout, proc.stderr):
                with contextlib.suppress(OSError):
                    if stream is not None:
                        stream.close()
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None

    def forget(self) -> None:
        """In a forked child: drop the parent's process without touching it (the pipes'
        copies are closed, so the probe still sees its stdin close when the parent exits)."""
        proc, self.proc = self.proc, None
        if proc is not None:
            for stream in (proc.stdin, proc.stdout, proc.stderr):
                with contextlib.suppress(OSError, ValueError):
                    if stream is not None:
                        os.close(stream.fileno())
            proc.returncode = 0  # not ours to wait for
        self.folder = None


def _unmarked(data: bytes) -> str:
    """The engine's output without the probe's start markers."""
    return MARKER.sub("", data.decode("utf-8", "replace"))


_LOCK = threading.Lock()
_IDLE: dict[str, list[Probe]] = {}
_REAPER: threading.Thread | None = None


@contextlib.contextmanager
def borrowed(engine: str, memory: int) -> Iterator[Probe]:
    """A probe of ``engine`` for this thread's use: an idle one, else a new one; back to
    the idle ones after."""
    with _LOCK:
        _reap()
        free = _IDLE.get(engine)
        probe = free.pop() if free else Probe(engine, memory)
    try:
        yield probe
    except BaseException:
        probe.close()
        raise
    with _LOCK:
        kept = _IDLE.setdefault(engine, [])
        if probe.proc is not None and len(kept) < KEEP:
            kept.append(probe)
            _watch()
            return
    probe.close()


def _reap() -> None:
    """Stop the probes idle for longer than :data:`IDLE` (with the lock held)."""
    now = time.monotonic()
    for engine, probes in _IDLE.items():
        stale = [p for p in probes if now - p.used > IDLE]
        _IDLE[engine] = [p for p in probes if now - p.used <= IDLE]
        for probe in stale:
            probe.close()


def _watch() -> None:
    """Start the thread that stops idle probes, if it is not running (lock held)."""
    global _REAPER
    if _REAPER is None or not _REAPER.is_alive():
        _REAPER = threading.Thread(target=_reaper, name="urdflint-probes", daemon=True)
        _REAPER.start()


def _reaper() -> None:
    while True:
        time.sleep(IDLE / 4)
        with _LOCK:
            _reap()
            if not any(_IDLE.values()):
                return


def close_all() -> None:
    """Stop every idle probe of this process (at exit)."""
    with _LOCK:
        probes = [p for found in _IDLE.values() for p in found]
        _IDLE.clear()
    for probe in probes:
        probe.close()


def _forked() -> None:
    global _LOCK, _REAPER
    _LOCK = threading.Lock()  # another thread may have held it at the fork
    _REAPER = None
    for found in _IDLE.values():
        for probe in found:
            probe.forget()
    _IDLE.clear()


atexit.register(close_all)
if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forked)
