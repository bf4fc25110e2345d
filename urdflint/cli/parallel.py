"""Checking many files at once: ``--jobs N`` over the standard library's process pool.

Each file is one task; the workers lint it exactly as a serial run would (meshes and
Pinocchio stay per process) and send back only what the report needs, in the order the
files were given, so the output of ``--jobs 4`` is byte for byte the output of ``--jobs 1``.
On a terminal, a run that lasts more than a second shows its progress on stderr.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import IO, Any

AUTO_MIN_FILES = 8  # fewer files than this: one process (a pool costs more than it saves)


@dataclass(frozen=True)
class Task:
    """One file to check: its path (``-`` for stdin, then ``data``), shown name, settings."""

    name: str
    shown: str
    settings: Any
    data: bytes | None = None


@dataclass(frozen=True)
class Flags:
    """What every task of the run also computes."""

    matrix: bool = False
    emit_expanded: Path | None = None
    record: bool = False  # dataset records: each file's digest and inputs too


@dataclass
class Outcome:
    """What the report needs of one checked file (picklable: no parsed document)."""

    shown: str
    findings: list[Any] = field(default_factory=list)
    ran: tuple[str, ...] = ()
    skipped: dict[str, tuple[str, ...]] = field(default_factory=dict)
    crashed: bool = False
    model: Any = None
    matrix: list[dict[str, Any]] = field(default_factory=list)
    error: str | None = None
    targets: dict[str, Any] | None = None  # the targets the findings are for, and how chosen
    links: int | None = None  # the model's size (None: no model was read)
    joints: int | None = None
    engines: tuple[str, ...] = ()  # the --confirm engines
    inputs: list[Any] | None = None  # Flags.record: what the check read ([kind, name, value])
    digest: str | None = None  # Flags.record: the file's content digest


def cpu_count() -> int:
    """The CPUs this process may run on (the affinity mask where the OS has one)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def jobs_for(requested: int | None, files: int) -> int:
    """The number of processes: ``--jobs`` if given, else every CPU for more than a few
    files; never more than there are files."""
    jobs = requested if requested is not None else (cpu_count() if files >= AUTO_MIN_FILES else 1)
    return max(1, min(jobs, files))


def lint_one(task: Task, context: Any, flags: Flags) -> Outcome:
    """Lint one file as a serial run does; replayed from the analysis cache when nothing it
    read changed (not with ``--emit-expanded``, which must write the expansion, nor with
    ``--confirm``, whose engines are not part of the key)."""
    cache = getattr(context, "cache", None)
    parts = _cache_parts(task, context, flags)
    if cache is None or parts is None:
        return _lint_one(task, context, flags)
    return cache.result(  # type: ignore[no-any-return]
        "check",
        parts,
        lambda: _lint_one(task, context, flags),
        overlay=context.overlay,
        environ=context.environ,
        keep=lambda outcome: not outcome.crashed and outcome.error is None,
    )


def lint_recorded(task: Task, context: Any, flags: Flags) -> Outcome:
    """:func:`lint_one`, with the file's digest and the inputs the check read (dataset
    records: ``--format jsonl``, ``--resume``)."""
    from urdflint.cache import code_folders, deps

    ignore = context.cache.ignore if getattr(context, "cache", None) else code_folders()
    with deps.recording(ignore) as recorder:
        outcome = lint_one(task, context, flags)
        inputs = recorder.deps()
    if task.data is not None:
        digest: str | None = deps.digest_bytes(task.data)
    else:
        digest = deps.file_digest(os.path.abspath(task.name))
    return replace(outcome, inputs=_json_inputs(inputs), digest=digest)


def _json_inputs(inputs: Sequence[Any]) -> list[Any] | None:
    """The inputs as JSON-able ``[kind, name, value]`` (None: one is not: never reused)."""
    import json

    found = [[d.kind, d.name, d.value] for d in inputs]
    try:
        json.dumps(found)
    except (TypeError, ValueError):
        return None
    return found


def _cache_parts(task: Task, context: Any, flags: Flags) -> tuple[Any, ...] | None:
    """The key of a task's result in the analysis cache (None: not cached)."""
    if getattr(context, "cache", None) is None or flags.emit_expanded or task.settings.confirm:
        return None
    from urdflint.cache import keys

    data = keys.canonical(task.data) if task.data is not None else None
    return (
        os.path.abspath(task.name) if task.data is None else "-",
        task.shown,
        data,
        keys.settings_key(task.settings),
        flags.matrix,
        keys.context_key(context),
    )


def _replayed(tasks: Sequence[Task], context: Any, flags: Flags) -> list[Outcome | None]:
    """Each task's outcome replayed from the cache, or None where it must be computed."""
    found: list[Outcome | None] = []
    for task in tasks:
        parts = _cache_parts(task, context, flags)
        hit, value = (False, None)
        if parts is not None:
            hit, value = context.cache.replayed(
                "check", parts, overlay=context.overlay, environ=context.environ
            )
        found.append(value if hit else None)
    return found


def _lint_one(task: Task, context: Any, flags: Flags) -> Outcome:
    from urdflint.engine import linter, matrix
    from urdflint.outputs import report

    try:
        if task.data is not None:
            result = linter.lint_bytes(task.data, task.shown, task.settings, context, Path.cwd())
        else:
            result = linter.lint_path(Path(task.name), task.shown, task.settings, context)
    except OSError as exc:
        return Outcome(task.shown, error=f"{task.shown}: cannot read: {exc.strerror or exc}")
    doc = result.document
    rows: list[dict[str, Any]] = []
    if flags.matrix and doc is not None and doc.root is not None:

        def relint(wider: Any) -> list[Any]:
            if task.data is not None:
                return linter.lint_bytes(task.data, task.shown, wider, context, Path.cwd()).findings
            return linter.lint_path(Path(task.name), task.shown, wider, context).findings

        chosen = result.targets.names if result.targets else task.settings.targets
        found = matrix.every_target(result.findings, replace(task.settings, targets=chosen), relint)
        rows = [{"path": task.shown, **row} for row in found]
    elif flags.record and doc is not None and doc.root is not None:  # the selected targets'
        chosen = result.targets.names if result.targets else task.settings.targets
        found = matrix.rows(result.findings, chosen, task.settings.confirm)
        rows = [{"path": task.shown, **row, "selected": True} for row in found]
    if flags.emit_expanded:
        _emit(flags.emit_expanded, doc)
    return Outcome(
        task.shown,
        result.findings,
        result.ran,
        result.skipped,
        result.crashed,
        report.model_summary(result),
        rows,
        targets=result.targets.to_dict() if result.targets and rows_possible(doc) else None,
        links=len(doc.links) if rows_possible(doc) else None,
        joints=len(doc.joints) if rows_possible(doc) else None,
        engines=tuple(task.settings.confirm),
    )


def _emit(path: Path, doc: Any) -> None:
    """``--emit-expanded``: the expanded URDF, or no file at all when xacro failed (a stale
    file from an earlier run would pass for this one's output)."""
    if doc is not None and doc.source and not (doc.problem and doc.problem.code == "X010"):
        path.write_bytes(doc.source)
    else:
        path.unlink(missing_ok=True)


def rows_possible(doc: Any) -> bool:
    """Whether a model was read (a matrix and the targets line are about one)."""
    return doc is not None and doc.root is not None


Work = Callable[[Task, Any, Flags], Outcome]
_WORKER: tuple[Any, Flags, Work] | None = None  # the run's context, flags, work: each worker


def _start(context: Any, flags: Flags, work: Work) -> None:
    global _WORKER
    _WORKER = (context, flags, work)


def _work(task: Task) -> Outcome:
    assert _WORKER is not None
    context, flags, work = _WORKER
    return work(task, context, flags)


def run(
    tasks: Sequence[Task], context: Any, flags: Flags, jobs: int, work: Work = lint_one
) -> Iterator[Outcome]:
    """Each task's ``work`` (:func:`lint_one`, or a variant that also records what it
    read), in the order of ``tasks``, from ``jobs`` processes."""
    progress = Progress(len(tasks), sys.stderr)
    try:
        if jobs <= 1 or len(tasks) <= 1:
            for task in tasks:
                yield work(task, context, flags)
                progress.step()
            return
        if getattr(context, "cache", None) is None or work is not lint_one:
            yield from _pooled(tasks, context, flags, jobs, progress, work)
            return
        # what the cache replays needs no pool: only the other files go to the processes
        done = _replayed(tasks, context, flags)
        todo = [task for task, outcome in zip(tasks, done, strict=True) if outcome is None]
        jobs = min(jobs, len(todo))
        fresh = iter(
            (lint_one(t, context, flags) for t in todo)
            if jobs <= 1
            else _pooled(todo, context, flags, jobs, progress, work)
        )
        for outcome in done:
            if outcome is None:
                outcome = next(fresh)
                if jobs <= 1:
                    progress.step()
            else:
                progress.step()
            yield outcome
    finally:
        progress.close()


def _pooled(
    tasks: Sequence[Task], context: Any, flags: Flags, jobs: int, progress: Progress, work: Work
) -> Iterator[Outcome]:
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # fork: the workers start with the rules already imported (spawn elsewhere: they import)
    method = "fork" if "fork" in multiprocessing.get_all_start_methods() else None
    if method == "fork":
        _preload(tasks)
    with ProcessPoolExecutor(
        jobs,
        mp_context=multiprocessing.get_context(method),
        initializer=_start,
        initargs=(context, flags, work),
    ) as pool:
        for outcome in pool.map(_work, tasks, chunksize=1):
            yield outcome
            progress.step()


def _preload(tasks: Sequence[Task]) -> None:
    """Import once, before forking, the optional modules the run's rules import lazily
    (Pinocchio, trimesh, numpy: ~0.5 s each worker would otherwise pay again)."""
    import importlib

    from urdflint.engine import registry
    from urdflint.model import optional

    needs: set[str] = set()
    for settings in {id(t.settings): t.settings for t in tasks}.values():
        for code in settings.enabled():
            needs.update(registry.RULES[code].needs)
    for module in sorted(needs):
        if optional.available(module):
            try:
                importlib.import_module(module)
            except Exception:  # a broken install: the worker reports it as the rule's U004/U001
                continue


class Progress:
    """``checked 37/200 files, 1:05 left`` on a terminal's stderr, once a run has lasted a
    second."""

    DELAY = 1.0

    def __init__(self, total: int, stream: IO[str]) -> None:
        self.total = total
        self.done = 0
        self.stream = stream
        self.started = time.monotonic()
        self.shown = False
        isatty = getattr(stream, "isatty", None)
        self.enabled = total > 1 and bool(isatty and isatty())

    def step(self) -> None:
        self.done += 1
        if not self.enabled or time.monotonic() - self.started < self.DELAY:
            return
        width = 24
        filled = width * self.done // self.total
        bar = "#" * filled + "." * (width - filled)
        self.stream.write(
            f"\rurdflint: [{bar}] checked {self.done}/{self.total} files{self.eta()}\x1b[K"
        )
        self.stream.flush()
        self.shown = True

    def eta(self) -> str:
        """``, 2:05 left`` from the pace so far (nothing until a few files are done)."""
        left = self.total - self.done
        if self.done < 3 or left <= 0:
            return ""
        seconds = int((time.monotonic() - self.started) / self.done * left + 0.5)
        hours, rest = divmod(seconds, 3600)
        clock = (
            f"{hours}:{rest // 60:02d}:{rest % 60:02d}"
            if hours
            else f"{rest // 60}:{rest % 60:02d}"
        )
        return f", {clock} left"

    def close(self) -> None:
        if self.shown:
            self.stream.write("\r\x1b[K")  # leave the terminal as it was
            self.stream.flush()
            self.shown = False
