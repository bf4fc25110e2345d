"""Run a probe over several files in one process, and survive its crashes.

The probe (:mod:`urdflint.engines.probe`, or any command that reads the same way) loads
the files in turn and writes one JSON report per file to stdout, and before each file a
marker line (:data:`~urdflint.engines.probe.MARK`) to stderr, so what the engine printed
is split per file here. Each file has ``timeout`` seconds, counted from the previous
report (for the first, from the start of the process, the engine's import included). When
the process dies (a signal, an ``abort()``, an exit before the last report) or times out,
the file it was on (the last marker it printed) is that file's crash, and a new process
takes the files after it. A command without markers (sdformat's probe, one file per
process) has all its output on its one file.
"""

from __future__ import annotations

import json
import queue
import re
import subprocess
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

from urdflint.engines.probe import MARK, MUJOCO_LOG

MARKER = re.compile(rf"^{re.escape(MARK)} (\d+)\r?\n", re.M)

Command = Callable[[Sequence[Path]], list[str]]


@dataclass
class Loaded:
    """What the probe said about one file.

    ``report`` is its JSON report (``None``: none came), ``printed`` what the engine printed
    while loading it (and, for the first file of a process, while starting); ``status`` the
    exit status of a process that ended on this file without reporting on every file, or
    that died on it (negative: the signal); ``hung`` that it timed out on this file;
    ``failed`` why the process could not be started.
    """

    path: Path
    report: dict[str, Any] | None = None
    printed: str = ""
    status: int | None = None
    hung: bool = False
    failed: str | None = None


def load(
    command: Command,
    paths: Sequence[Path],
    timeout: float,
    cwd: Path,
    env: dict[str, str] | None = None,
) -> list[Loaded]:
    """One :class:`Loaded` per path, in order: ``command(paths)`` run from ``cwd``, again
    with the files after the one it crashed or hung on until every file has its answer."""
    done: list[Loaded] = []
    while len(done) < len(paths):
        done.extend(_process(command, paths[len(done) :], timeout, cwd, env))
    return done


def _process(
    command: Command,
    paths: Sequence[Path],
    timeout: float,
    cwd: Path,
    env: dict[str, str] | None,
) -> list[Loaded]:
    """Run one process over ``paths``: the files it answered, up to the one it ended on."""
    try:
        proc = subprocess.Popen(command(paths), cwd=cwd, env=env, stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)  # fmt: skip
    except OSError as exc:  # the probe could not be started (missing, not allowed)
        return [Loaded(p, failed=str(exc.strerror or exc)) for p in paths]
    out, err = proc.stdout, proc.stderr
    assert out is not None and err is not None
    lines: queue.Queue[bytes | None] = queue.Queue()
    printed: list[bytes] = []
    readers = [
        threading.Thread(target=_lines, args=(out, lines), daemon=True),
        threading.Thread(target=lambda: printed.append(err.read()), daemon=True),
    ]
    for reader in readers:
        reader.start()
    reports, hung = _reports(proc, lines, len(paths), timeout)
    for reader in readers:
        reader.join()
    out.close()
    err.close()
    text = b"".join(printed).decode("utf-8", "replace")
    return _answers(paths, reports, _split(text, len(paths)), proc.returncode, hung, cwd)


def _lines(stream: IO[bytes], into: queue.Queue[bytes | None]) -> None:
    for line in stream:
        into.put(line)
    into.put(None)


def _reports(
    proc: subprocess.Popen[bytes], lines: queue.Queue[bytes | None], count: int, timeout: float
) -> tuple[list[dict[str, Any]], bool]:
    """The reports, as they come (each within ``timeout``), and whether it hung; the
    process has ended (or was killed) on return."""
    reports: list[dict[str, Any]] = []
    while len(reports) < count:
        try:
            line = lines.get(timeout=timeout)
        except queue.Empty:
            return reports, _kill(proc)
        if line is None:  # stdout closed: the process is ending
            break
        report = report_of(line.decode("utf-8", "replace"))
        if report is not None:
            reports.append(report)
    try:
        proc.wait(timeout=timeout)
        return reports, False
    except subprocess.TimeoutExpired:
        return reports, _kill(proc)


def _kill(proc: subprocess.Popen[bytes]) -> bool:
    proc.kill()
    proc.wait()
    return True


def report_of(text: str) -> dict[str, Any] | None:
    """The last JSON report among the lines of ``text``."""
    for line in reversed(text.splitlines()):
        try:
            found = json.loads(line)
        except ValueError:
            continue
        if isinstance(found, dict) and "ok" in found:
            return found
    return None


def _split(printed: str, count: int) -> tuple[list[str], int]:
    """What was printed, per file (by the markers; before the first: on the first file),
    and the index of the last marker (-1: none)."""
    parts = MARKER.split(printed)
    chunks = [""] * count
    chunks[0] = parts[0]
    last = -1
    for index, text in zip(parts[1::2], parts[2::2], strict=True):
        last = int(index)
        if last < count:
            chunks[last] += text
    return chunks, last


def _answers(
    paths: Sequence[Path],
    reports: list[dict[str, Any]],
    printed: tuple[list[str], int],
    status: int,
    hung: bool,
    cwd: Path,
) -> list[Loaded]:
    """The files answered; when the process did not report on every file and end cleanly,
    the file it was on (its last marker, else the first unanswered) gets the crash."""
    chunks, last = printed
    answers = [Loaded(paths[i], report, chunks[i]) for i, report in enumerate(reports)]
    if len(reports) == len(paths) and status == 0 and not hung:
        return answers
    current = min(last if last >= 0 else len(reports), len(paths) - 1)
    crashed = Loaded(paths[current], None, chunks[current] + left_log(cwd), status, hung)
    return [*answers[:current], crashed]


def left_log(cwd: Path) -> str:
    """MuJoCo's log of a file it died on (the probe echoes it only after a load)."""
    log = cwd / MUJOCO_LOG
    if not log.is_file():
        return ""
    text = "\n" + log.read_text(encoding="utf-8", errors="replace")
    log.unlink()
    return text
