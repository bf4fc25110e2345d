"""``urdflint check``: lint files and folders, write the reports, decide the exit code."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from urdflint import __version__
from urdflint.cli import fix, fragments, show, show_packages, watch
from urdflint.cli.check_options import add_parser
from urdflint.cli.common import (
    EXIT_ERROR,
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    open_cache,
    run_context,
)
from urdflint.engine import config, instances
from urdflint.engine.options import SettingsFinder
from urdflint.model.finding import Finding
from urdflint.outputs import formatters, report
from urdflint.sources.discovery import SKIP_DIRS, as_entries, collect

FAIL_LEVEL = report.FAIL_LEVEL
__all__ = ["add_parser", "run"]


@dataclass
class Run:
    """What linting the files of one ``check`` produced."""

    findings: list[Finding] = field(default_factory=list)
    checked: list[str] = field(default_factory=list)
    models: dict[str, Any] = field(default_factory=dict)
    skipped: dict[str, tuple[str, ...]] = field(default_factory=dict)
    ran: dict[str, tuple[str, ...]] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)
    fail_on: str = "error"
    crashed: bool = False
    expects: bool = False
    matrix: list[dict[str, Any]] = field(default_factory=list)
    targets: dict[str, Any] = field(default_factory=dict)  # path -> its targets, how chosen
    baselined: int = 0  # findings the baseline accepted (or --write-baseline recorded)
    counts: dict[str, int] | None = None  # a lean dataset run: findings counted, not kept


def run(args: argparse.Namespace) -> int:
    if getattr(args, "watch", False):
        return watch.run(args, run)  # this run, again on each change
    try:
        finder = SettingsFinder(args)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    try:
        here = finder.for_folder(Path.cwd())
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    context = run_context(args, open_cache(args, here))
    files, errors = collect(args.paths, context.workspace)
    files = as_entries(_changed_only(args, files), context.workspace)
    robots, pieces = fragments.split(files)  # a *.urdf fragment nobody includes: one note
    if args.show_packages:
        show_packages.write(files, context, finder, sys.stderr)
    if show.requested(args):  # --show-files, --show-settings, --add-noqa: no lint report
        return show.run(args, files, errors, context, finder)
    accepted = _load_baseline(args)
    if args.emit_expanded and not (len(files) == 1 and files[0].lower().endswith(".xacro")):
        raise UsageError("--emit-expanded needs exactly one xacro file")
    reports = _reports(args)
    from urdflint.cli import dataset

    plan = dataset.plan(args, reports)  # --format jsonl, --resume: records as files finish

    def lint() -> Run:
        found = Run(errors=list(errors))
        _lint_files(args, robots, finder, found, context, plan)
        fragments.add(pieces, finder, found, context)
        return found

    try:
        outcome, done = fix.drive(args, files, lint)
    finally:
        plan.close()
        if context.cache is not None:
            context.cache.finish()
    if done is not None:
        return done
    if outcome.counts is not None:  # every output is records, written file by file
        return _lean_end(args, files, outcome)
    findings = _finish(args, finder, outcome, accepted)
    fix.report(args, findings)
    for message in outcome.errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    _write_report(args, files, outcome, findings, reports)
    return _exit_code(args, files, outcome, findings)


def _write_report(
    args: argparse.Namespace,
    files: list[str],
    outcome: Run,
    findings: list[Finding],
    reports: list[tuple[str, Path]],
) -> None:
    """The main output and the --report files."""
    fmt = args.format
    if fmt == "auto":
        fmt = "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    show_info = args.show_info or outcome.fail_on == "info"
    info = formatters.RunInfo(
        __version__,
        tuple(outcome.checked),
        outcome.models,
        outcome.fail_on,
        outcome.ran,
        show_info,
        tuple(outcome.matrix),
        outcome.targets,
        outcome.baselined,
        docs_url=args.docs_url or os.environ.get("URDFLINT_DOCS_URL") or None,
    )
    _write_outputs([(fmt, args.output), *reports], findings, info, _display(args, info, files))


def _lint_files(
    args: argparse.Namespace,
    files: list[str],
    finder: SettingsFinder,
    outcome: Run,
    context: Any,
    plan: Any,
) -> None:
    from urdflint.cli import dataset, parallel

    tasks = [_task(args, name, finder) for name in files]
    if not plan.active and getattr(args, "executor", "local") == "local":
        flags = parallel.Flags(args.matrix, args.emit_expanded)
        jobs = parallel.jobs_for(args.jobs, len(tasks))
        _collect(args, tasks, parallel.run(tasks, context, flags, jobs), outcome)
        return
    # records (every target's matrix row, what each file read), or Ray: as files finish
    flags = parallel.Flags(args.matrix, args.emit_expanded, record=plan.active)
    done: list[Any] = [None] * len(tasks)
    counts = {"error": 0, "warning": 0, "info": 0}
    for index, result in dataset.execute(args, tasks, context, flags, plan):
        done[index] = dataset.lean(result, counts) if plan.lean else result
    if plan.lean:
        outcome.counts = counts
    _collect(args, tasks, done, outcome)


def _collect(args: argparse.Namespace, tasks: list[Any], outcomes: Any, outcome: Run) -> None:
    """Fold each file's outcome, in input order, into the run."""
    for task, done in zip(tasks, outcomes, strict=True):
        if not args.matrix:
            done.matrix = []  # computed for the records only
        if done.error is not None:
            outcome.errors.append(done.error)
            continue
        outcome.checked.append(done.shown)
        outcome.ran[done.shown] = done.ran
        outcome.findings.extend(done.findings)
        outcome.skipped.update(done.skipped)
        outcome.crashed = outcome.crashed or done.crashed
        outcome.fail_on = task.settings.fail_on
        expect = task.settings.expect
        outcome.expects = outcome.expects or expect.mass is not None or expect.com is not None
        outcome.models[done.shown] = done.model
        outcome.matrix.extend(done.matrix)
        if done.targets is not None:
            outcome.targets[done.shown] = done.targets


def _task(args: argparse.Namespace, name: str, finder: SettingsFinder) -> Any:
    """One file's task: its settings (from the configuration nearest to it), stdin's bytes."""
    from urdflint.cli import parallel

    is_stdin = name == "-"
    try:
        settings = finder.for_folder(Path.cwd() if is_stdin else Path(name).parent)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    if not is_stdin:
        return parallel.Task(name, name, settings)
    return parallel.Task(name, args.stdin_filename, settings, sys.stdin.buffer.read())


def _finish(
    args: argparse.Namespace, finder: SettingsFinder, outcome: Run, accepted: Any
) -> list[Finding]:
    """The findings to report: a note on skipped rules, then the baseline step."""
    findings = (
        instances.across_files(outcome.findings) if len(outcome.checked) > 1 else outcome.findings
    )
    skipped, checked = outcome.skipped, outcome.checked
    gate = outcome.expects and bool({"P003", "P004"} & set(skipped))
    if skipped and checked and (gate or "U004" in finder.for_folder(Path.cwd()).enabled()):
        findings.append(report.skipped_note(checked[0], skipped, outcome.expects))
    findings.sort(key=Finding.sort_key)
    kept = _baseline_step(args, accepted, findings, outcome.ran)
    stale = sum(f.code == "U005" for f in kept)
    outcome.baselined = len(findings) - (len(kept) - stale)
    return kept


def _exit_code(
    args: argparse.Namespace, files: list[str], outcome: Run, findings: list[Finding]
) -> int:
    if not files and not outcome.errors and args.changed_since:
        print(
            f"urdflint: no *.urdf or *.xacro files changed since {args.changed_since}",
            file=sys.stderr,
        )
        return EXIT_OK
    if outcome.errors or outcome.crashed or not files:
        if not files and not outcome.errors:
            print("urdflint: error: no *.urdf or *.xacro files found", file=sys.stderr)
        return EXIT_ERROR
    threshold = FAIL_LEVEL.get(outcome.fail_on)
    if threshold is not None and any(f.severity >= threshold for f in findings):
        return EXIT_FINDINGS
    return EXIT_OK


def _lean_end(args: argparse.Namespace, files: list[str], outcome: Run) -> int:
    """The end of a run whose every output is records: a summary line, the exit code."""
    for message in outcome.errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    counts = outcome.counts or {}
    parts = [
        f"{counts[s]} {s}{'' if counts[s] == 1 else 's'}" for s in ("error", "warning", "info")
    ]
    where = f" (records in {args.output})" if args.output else ""
    if outcome.checked and not args.quiet:
        checked = len(outcome.checked)
        print(f"urdflint: {', '.join(parts)} in {checked} file(s){where}", file=sys.stderr)
    if outcome.errors or outcome.crashed or not files:
        return EXIT_ERROR
    threshold = FAIL_LEVEL.get(outcome.fail_on)
    if threshold is not None and any(counts[str(s)] for s in FAIL_LEVEL.values() if s >= threshold):
        return EXIT_FINDINGS
    return EXIT_OK


def _changed_only(args: argparse.Namespace, files: list[str]) -> list[str]:
    """``--changed-since``: the files among ``files`` (and folder PATHs) git reports as changed."""
    if not args.changed_since:
        return files
    from urdflint.sources import changed

    if args.write_baseline:
        raise UsageError(
            "--write-baseline records every finding; do not combine it with --changed-since"
        )
    existing = [Path(p) for p in args.paths if p != "-" and Path(p).exists()]
    try:
        found = changed.changed_files(args.changed_since, existing[0] if existing else Path.cwd())
    except changed.ChangedError as exc:
        raise UsageError(str(exc)) from None
    return changed.select(files, args.paths, found, SKIP_DIRS)


def _load_baseline(args: argparse.Namespace) -> Any:
    if args.baseline is None:
        return None
    from urdflint.engine import baseline

    try:
        return baseline.load(args.baseline)
    except baseline.BaselineError as exc:
        raise UsageError(str(exc)) from None


def _baseline_step(
    args: argparse.Namespace,
    accepted: Any,
    findings: list[Finding],
    ran: dict[str, tuple[str, ...]],
) -> list[Finding]:
    """``--write-baseline``: record and accept everything; ``--baseline``: keep only new
    findings, plus a U005 note per stale entry."""
    if not args.write_baseline and accepted is None:
        return findings
    from urdflint.engine import baseline

    if args.write_baseline:
        try:
            count = baseline.write(args.write_baseline, findings)
        except baseline.BaselineError as exc:
            raise UsageError(str(exc)) from None
        print(f"urdflint: recorded {count} finding(s) in {args.write_baseline}", file=sys.stderr)
        return [f for f in findings if f.code in baseline.UNRECORDED]
    new, stale = baseline.apply(accepted, findings, ran)
    return sorted(new + stale, key=Finding.sort_key)


def _writable(path: Path, option: str) -> Path:
    """``path`` if a file can be written there (checked before linting), else a usage error."""
    if path.is_dir():
        raise UsageError(f"{option} {path}: is a directory")
    folder = path.parent
    if not folder.is_dir():
        raise UsageError(f"{option} {path}: no such directory {str(folder)!r}")
    if not os.access(folder, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise UsageError(f"{option} {path}: not writable")
    return path


def _reports(args: argparse.Namespace) -> list[tuple[str, Path]]:
    """``--report FORMAT:PATH`` values (and ``--output``), validated before any linting."""
    reports: list[tuple[str, Path]] = []
    seen = {_writable(args.output, "--output").resolve()} if args.output else set()
    for value in args.report:
        name, found, target = value.partition(":")
        if not found or not target or not name:
            raise UsageError(f"--report {value!r}: expected FORMAT:PATH, e.g. sarif:urdflint.sarif")
        if name not in formatters.NAMES and name != "jsonl":
            known = ", ".join((*formatters.NAMES, "jsonl"))
            raise UsageError(f"--report {value!r}: unknown format {name!r} (use {known})")
        path = _writable(Path(target), "--report")
        if path.resolve() in seen:
            raise UsageError(f"--report {value!r}: {target} is written twice")
        seen.add(path.resolve())
        reports.append((name, path))
    return reports


def _display(
    args: argparse.Namespace, run: formatters.RunInfo, files: list[str]
) -> formatters.RunInfo:
    """The main output's display options (--output-format, --statistics, --quiet)."""
    return replace(
        run,
        output_format=args.output_format,
        statistics=args.statistics,
        quiet=args.quiet,
        unread=(args.stdin_filename,) if "-" in files else (),  # not the text on disk
    )


def _write_outputs(
    outputs: Sequence[tuple[str, Path | None]],
    findings: list[Finding],
    run: formatters.RunInfo,
    main: formatters.RunInfo | None = None,
) -> None:
    """Render each (format, file) of the run; ``None`` = stdout. The first, the main output,
    with the display options of ``main``; the --report files carry everything. With
    --statistics, the main output is the statistics table unless its format is json."""
    for index, (name, path) in enumerate(outputs):
        if name == "jsonl":
            continue  # records: written as each file finished (urdflint.cli.dataset)
        shown = main if index == 0 and main is not None else run
        if shown.statistics and name != "json":
            name = "text"
        shown = shown if name == "json" else replace(shown, models={})
        text = formatters.get(name)(findings, shown)
        if path is None:
            sys.stdout.write(text)
            sys.stdout.flush()
            continue
        try:
            path.write_text(text, encoding="utf-8")
        except OSError as exc:
            raise UsageError(f"{path}: cannot write: {exc.strerror or exc}") from None
