"""Checking datasets: records written as files finish, ``--resume``, ``--executor ray``.

A run writes dataset records (:mod:`urdflint.outputs.records`) when its main output is
``--format jsonl``, a ``--report jsonl:PATH`` asks for them, or ``--resume FILE`` names a
results file. Then each task also records the file's digest and every input the check read,
and its matrix rows: those of the targets its findings are for, and with ``--matrix`` every
target's (the report's "loads in" columns); the text and JSON outputs show them only with
``--matrix``.

``--resume FILE`` reads the records FILE holds, reuses each one whose file, settings and
inputs are unchanged (nothing is checked again), checks the other files and appends their
records to FILE: the same command, run again after a stop, continues where it stopped, and
its outputs cover every file.

When every output is records (no text, JSON, SARIF... to render at the end), the run keeps
only counts of the findings it has written: memory stays flat over 100,000 files.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from urdflint.cli import parallel
from urdflint.cli.common import UsageError
from urdflint.outputs import records

STREAMED = ("jsonl",)  # formats written file by file, as results come


@dataclass
class Plan:
    """Where this run's records go, and what it may reuse."""

    sinks: list[IO[str]] = field(default_factory=list)
    owned: list[IO[str]] = field(default_factory=list)  # the files this run opened
    recorded: dict[str, dict[str, Any]] = field(default_factory=dict)  # --resume: by path
    resume: IO[str] | None = None  # --resume's file: only new records go there
    lean: bool = False  # every output is records: keep counts, not findings
    settings: dict[int, str] = field(default_factory=dict)  # id(settings) -> digest
    context: str | None = None  # the digest of urdflint's code and the run's context
    reused: int = 0
    stale: int = 0

    @property
    def active(self) -> bool:
        return bool(self.sinks) or self.resume is not None

    def close(self) -> None:
        for handle in self.owned:
            handle.close()
        for handle in self.sinks:
            if handle not in self.owned:
                handle.flush()


def wanted(args: argparse.Namespace, reports: Sequence[tuple[str, Path]]) -> bool:
    """Whether this run writes records at all."""
    resume = getattr(args, "resume", None)
    return (
        getattr(args, "format", None) in STREAMED
        or any(n in STREAMED for n, _ in reports)
        or bool(resume)
    )


def plan(args: argparse.Namespace, reports: Sequence[tuple[str, Path]]) -> Plan:
    """Open the record outputs (validated before any file is checked)."""
    found = Plan()
    if not wanted(args, reports):
        return found
    resume = Path(args.resume).resolve() if args.resume else None
    if resume is not None:
        if resume.is_dir():
            raise UsageError(f"--resume {args.resume}: is a directory")
        try:
            kept, _ = records.read(resume) if resume.exists() else ([], 0)
        except records.Unreadable as exc:
            raise UsageError(f"--resume: {exc}") from None
        for item in kept:
            found.recorded[item["path"]] = item
        try:
            found.resume = records.append_to(resume)
        except OSError as exc:
            raise UsageError(f"--resume {args.resume}: cannot write: {exc.strerror}") from None
        found.owned.append(found.resume)
    targets: list[Path | None] = []
    if args.format in STREAMED:
        targets.append(args.output)
    targets += [path for name, path in reports if name in STREAMED]
    for target in targets:
        if target is None:
            found.sinks.append(sys.stdout)
            continue
        if resume is not None and target.resolve() == resume:
            continue  # the resumed file: written once, through found.resume
        try:
            handle = open(target, "w", encoding="utf-8")  # noqa: SIM115 (closed by close())
        except OSError as exc:
            raise UsageError(f"{target}: cannot write: {exc.strerror or exc}") from None
        found.sinks.append(handle)
        found.owned.append(handle)
    others = [n for n, _ in reports if n not in STREAMED]
    found.lean = args.format in STREAMED and not others and args.baseline is None
    found.lean = found.lean and not args.write_baseline
    return found


# -- resuming --------------------------------------------------------------------------------


def _as_deps(inputs: list[Any]) -> tuple[Any, ...]:
    from urdflint.cache.deps import Dep

    return tuple(Dep(kind, name, _tupled(value)) for kind, name, value in inputs)


def _tupled(value: Any) -> Any:
    if isinstance(value, list):
        return tuple(_tupled(v) for v in value)
    return value


def settings_digest(found: Plan, task: parallel.Task, context: Any) -> str:
    """The digest of what besides the file shapes its record (its settings, the run's
    context, urdflint's code)."""
    known = found.settings.get(id(task.settings))
    if known is None:
        from urdflint.cache import keys

        if found.context is None:  # once per run: it names every path given (thousands)
            found.context = keys.digest(keys.code_version(), keys.context_key(context))
        known = keys.digest(found.context, keys.settings_key(task.settings))
        found.settings[id(task.settings)] = known
    return known


def reusable(found: Plan, task: parallel.Task, context: Any) -> parallel.Outcome | None:
    """The recorded outcome of ``task`` when nothing it depends on changed."""
    item = found.recorded.get(task.shown)
    if item is None or task.data is not None:
        return None
    from urdflint.cache import deps

    fresh = (
        item.get("settings") == settings_digest(found, task, context)
        and item.get("hash") is not None
        and item["hash"] == deps.file_digest(os.path.abspath(task.name))
        and not item.get("crashed")
        and item.get("inputs") is not None
        and deps.unchanged(_as_deps(item["inputs"]), context.overlay, context.environ)
    )
    if not fresh:
        found.stale += 1
        return None
    found.reused += 1
    return outcome_of(item)


def outcome_of(item: dict[str, Any]) -> parallel.Outcome:
    """The :class:`parallel.Outcome` a record was written from."""
    return parallel.Outcome(
        item["path"],
        [records.finding(f) for f in item["findings"]],
        tuple(item["ran"]),
        {code: tuple(m) for code, m in item["skipped"].items()},
        bool(item["crashed"]),
        item["model"],
        list(item["matrix"]),
        item["error"],
        item["targets"],
        links=item.get("links"),
        joints=item.get("joints"),
        engines=tuple(item.get("engines") or ()),
        inputs=item.get("inputs"),
    )


# -- writing -------------------------------------------------------------------------------


def write(found: Plan, task: parallel.Task, outcome: parallel.Outcome, context: Any) -> None:
    """Write the record of one finished (or reused) file to the run's record outputs."""
    from urdflint import __version__

    item = records.record(
        outcome, hash=outcome.digest, settings=settings_digest(found, task, context),
        tool=__version__,
    )  # fmt: skip
    line = records.dumps(item)
    for handle in found.sinks:
        handle.write(line)
        handle.flush()
    if found.resume is not None:  # a file not recorded, or recorded and changed since
        found.resume.write(line)
        found.resume.flush()


# -- running ---------------------------------------------------------------------------------


def execute(
    args: argparse.Namespace,
    tasks: Sequence[parallel.Task],
    context: Any,
    flags: parallel.Flags,
    found: Plan,
) -> Iterator[tuple[int, parallel.Outcome]]:
    """Each task's ``(index, outcome)`` as it finishes: reused records first, then the
    files checked by the chosen executor (``--jobs`` processes keep the input order; Ray
    gives them in the order they finish). Records are written as they come."""
    todo: list[int] = []
    for index, task in enumerate(tasks):
        reused = reusable(found, task, context) if found.recorded else None
        if reused is None:
            todo.append(index)
            continue
        for handle in found.sinks:
            handle.write(records.dumps(_recorded(found, task)))
        yield index, reused
    if found.recorded:
        _say_resumed(args, found, len(todo))
    pending = [tasks[i] for i in todo]
    if getattr(args, "executor", "local") == "ray":
        from urdflint.cli import ray_run

        stream = ray_run.run(pending, context, flags, args)
    else:
        jobs = parallel.jobs_for(args.jobs, len(pending))
        stream = enumerate(parallel.run(pending, context, flags, jobs, parallel.lint_recorded))
    for position, outcome in stream:
        index = todo[position]
        write(found, tasks[index], outcome, context)
        yield index, outcome


def _recorded(found: Plan, task: parallel.Task) -> dict[str, Any]:
    return found.recorded[task.shown]


def _say_resumed(args: argparse.Namespace, found: Plan, todo: int) -> None:
    changed = f", {found.stale} changed since" if found.stale else ""
    print(
        f"urdflint: resuming {args.resume}: {found.reused} file(s) already recorded{changed}; "
        f"{todo} to check",
        file=sys.stderr,
    )


def lean(outcome: parallel.Outcome, counts: dict[str, int]) -> parallel.Outcome:
    """What a lean run keeps of a written file: its findings counted, not kept; only what
    the exit code needs (its path, whether it crashed or could not be read)."""
    for finding in outcome.findings:
        counts[str(finding.severity)] += 1
    return parallel.Outcome(outcome.shown, crashed=outcome.crashed, error=outcome.error)
