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
from urdflint.cli import fix, package
from urdflint.cli.common import (
    EXIT_ERROR,
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    gate_options,
    model_options,
    run_context,
)
from urdflint.engine import config, instances, matrix, options
from urdflint.engine.options import SettingsFinder
from urdflint.model import targets
from urdflint.model.finding import Finding
from urdflint.outputs import formatters, report
from urdflint.sources.discovery import SKIP_DIRS, as_entries, collect

FAIL_LEVEL = report.FAIL_LEVEL


def _codes(value: str) -> list[str]:
    return [part.strip() for part in value.split(",") if part.strip()]


HELP = {
    "check": "lint files and folders (folders: every *.urdf below)",
    "fix": "apply the automatic fixes, then report what is left (check --fix)",
}


def add_parser(sub: Any) -> None:
    for name, text in HELP.items():
        _options(sub.add_parser(name, help=text))


def _options(check: argparse.ArgumentParser) -> None:
    check.add_argument("paths", nargs="+", metavar="PATH", help="file, folder, or - for stdin")
    check.add_argument(
        "--format",
        default="auto",
        choices=("auto", *formatters.NAMES),
        help="output format; auto = github when GITHUB_ACTIONS is set, else text",
    )
    check.add_argument(
        "--select",
        action="append",
        type=_codes,
        default=[],
        metavar="CODES",
        help="run only these rules (codes, names or family letters, comma-separated)",
    )
    check.add_argument(
        "--ignore",
        action="append",
        type=_codes,
        default=[],
        metavar="CODES",
        help="do not run these rules (added to the configured ignores)",
    )
    check.add_argument(
        "--fail-on",
        choices=config.FAIL_ON,
        default=None,
        help="lowest severity that makes the exit code 1 (default: error)",
    )
    check.add_argument("--exit-zero", action="store_true", help="same as --fail-on never")
    check.add_argument(
        "--show-info",
        action="store_true",
        help="list info findings in the text output (default: one summary line; "
        "--fail-on info and the machine formats always list them)",
    )
    check.add_argument(
        "--target",
        action="append",
        type=options.target_list,
        default=[],
        metavar="TARGETS",
        help="consumers the model is meant for: "
        + ", ".join((*targets.TARGETS, targets.ALL))
        + " (comma-separated or repeated; default gazebo-classic; all: every one)",
    )
    package.add_options(check)
    check.add_argument(
        "--matrix",
        action="store_true",
        help="show what each target will do with the model: loads, loads with changes, "
        "refused or crashes, and the findings that decide it (with --confirm: what the "
        "engines did)",
    )
    _more_options(check)
    fix.add_options(check)


def _more_options(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "--config",
        type=Path,
        metavar="FILE",
        help="use this configuration file instead of discovering one",
    )
    check.add_argument("--isolated", action="store_true", help="ignore every configuration file")
    check.add_argument(
        "--stdin-filename",
        default="<stdin>",
        metavar="NAME",
        help="path to show (and to match per-file ignores) for input read from -",
    )
    model_options(check)
    check.add_argument(
        "--expect-mass",
        metavar="KG[±TOL]",
        type=options.expect_mass,
        help="fail (P003) unless the total mass is KG within ±TOL kg or ±N%% "
        "(default tolerance: expect.mass-tolerance, 2%%)",
    )
    check.add_argument(
        "--expect-com",
        metavar="X,Y,Z[±TOL]",
        type=options.expect_com,
        help="fail (P004) unless the centre of mass, in the root link frame, is X,Y,Z "
        "within TOL metres (default: expect.com-tolerance, 0.01)",
    )
    check.add_argument(
        "--confirm",
        action="append",
        type=options.engine_list,
        default=[],
        metavar="ENGINES",
        help="also load the model in these engines (mujoco, pybullet, drake, pinocchio, "
        "sdformat or all; "
        "comma-separated) and report what they refuse, drop, warn about or crash on (E rules)",
    )
    check.add_argument(
        "--emit-expanded",
        type=Path,
        metavar="FILE",
        help="write the expanded URDF of a single xacro input to FILE",
    )
    check.add_argument(
        "--output",
        type=Path,
        metavar="FILE",
        help="write the --format output to FILE instead of stdout",
    )
    check.add_argument(
        "--report",
        action="append",
        default=[],
        metavar="FORMAT:PATH",
        help="also write FORMAT (" + ", ".join(formatters.NAMES) + ") to PATH (repeatable), "
        "e.g. --report sarif:urdflint.sarif --report junit:urdflint.xml",
    )
    gate_options(check)


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


def run(args: argparse.Namespace) -> int:
    from urdflint.engine import linter

    try:
        finder = SettingsFinder(args)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    context = run_context(args)
    files, errors = collect(args.paths, context.workspace)
    files = as_entries(_changed_only(args, files), context.workspace)
    accepted = _load_baseline(args)
    if args.emit_expanded and not (len(files) == 1 and linter.is_xacro(files[0])):
        raise UsageError("--emit-expanded needs exactly one xacro file")
    reports = _reports(args)

    def lint() -> Run:
        found = Run(errors=list(errors))
        _lint_files(args, files, finder, found, context)
        return found

    outcome, done = fix.drive(args, files, lint)
    if done is not None:
        return done
    findings = _finish(args, finder, outcome, accepted)
    fix.report(args, findings)
    for message in outcome.errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
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
    )
    _write_outputs([(fmt, args.output), *reports], findings, info)
    return _exit_code(args, files, outcome, findings)


def _lint_files(
    args: argparse.Namespace, files: list[str], finder: SettingsFinder, outcome: Run, context: Any
) -> None:
    from urdflint.engine import linter

    for name in files:
        is_stdin = name == "-"
        shown = args.stdin_filename if is_stdin else name
        try:
            settings = finder.for_folder(Path.cwd() if is_stdin else Path(name).parent)
        except config.ConfigError as exc:
            raise UsageError(str(exc)) from None
        if args.matrix and not args.target and settings.targets == targets.DEFAULT_TARGETS:
            settings = replace(settings, targets=tuple(targets.TARGETS))  # every row
        try:
            if is_stdin:
                data = sys.stdin.buffer.read()
                result = linter.lint_bytes(data, shown, settings, context, Path.cwd())
            else:
                result = linter.lint_path(Path(name), shown, settings, context)
        except OSError as exc:
            outcome.errors.append(f"{shown}: cannot read: {exc.strerror or exc}")
            continue
        outcome.checked.append(shown)
        outcome.ran[shown] = result.ran
        outcome.findings.extend(result.findings)
        outcome.skipped.update(result.skipped)
        outcome.crashed = outcome.crashed or result.crashed
        outcome.fail_on = settings.fail_on
        expect = settings.expect
        outcome.expects = outcome.expects or expect.mass is not None or expect.com is not None
        outcome.models[shown] = report.model_summary(result)
        if args.matrix and result.document is not None and result.document.root is not None:
            rows = matrix.rows(result.findings, settings.targets, settings.confirm)
            outcome.matrix.extend({"path": shown, **row} for row in rows)
        if args.emit_expanded and result.document is not None:
            args.emit_expanded.write_bytes(result.document.source)


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
    return _baseline_step(args, accepted, findings, outcome.ran)


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
        if name not in formatters.NAMES:
            known = ", ".join(formatters.NAMES)
            raise UsageError(f"--report {value!r}: unknown format {name!r} (use {known})")
        path = _writable(Path(target), "--report")
        if path.resolve() in seen:
            raise UsageError(f"--report {value!r}: {target} is written twice")
        seen.add(path.resolve())
        reports.append((name, path))
    return reports


def _write_outputs(
    outputs: Sequence[tuple[str, Path | None]], findings: list[Finding], run: formatters.RunInfo
) -> None:
    """Render each (format, file) of the run; ``None`` = stdout."""
    for name, path in outputs:
        text = formatters.get(name)(findings, run if name == "json" else replace(run, models={}))
        if path is None:
            sys.stdout.write(text)
            sys.stdout.flush()
            continue
        try:
            path.write_text(text, encoding="utf-8")
        except OSError as exc:
            raise UsageError(f"{path}: cannot write: {exc.strerror or exc}") from None
