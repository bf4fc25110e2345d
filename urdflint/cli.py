"""Command line: ``urdflint check|rules|explain``. Owns I/O and exit codes, no lint logic.

Exit codes: 0 nothing at or above ``--fail-on``; 1 findings at or above it;
2 usage error, unreadable path, invalid configuration or an internal error.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from urdflint import __version__, config, formatters, options, registry, report, targets
from urdflint.finding import Finding

EXIT_OK, EXIT_FINDINGS, EXIT_ERROR = 0, 1, 2
SKIP_DIRS = {"node_modules", "__pycache__", "build", "install", "log"}
FAIL_LEVEL = report.FAIL_LEVEL


class UsageError(Exception):
    pass


def _codes(value: str) -> list[str]:
    return [part.strip() for part in value.split(",") if part.strip()]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="urdflint",
        description="Lint robot descriptions (URDF): every problem, with line, rule code and fix.",
    )
    parser.add_argument("--version", action="version", version=f"urdflint {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    check = sub.add_parser("check", help="lint files and folders (folders: every *.urdf below)")
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
        "--target",
        action="append",
        choices=tuple(targets.TARGETS),
        default=[],
        help="consumer the model is meant for (repeatable; default gazebo-classic)",
    )
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
    _model_options(check)
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
    _gate_options(check)

    info = sub.add_parser("info", help="the model: tree, per-link masses, total mass, COM, DOF")
    info.add_argument("path", metavar="PATH", help="a URDF or xacro file")
    info.add_argument("--format", choices=("text", "json"), default="text")
    info.add_argument("--config", type=Path, metavar="FILE")
    info.add_argument("--isolated", action="store_true")
    _model_options(info)

    rules = sub.add_parser("rules", help="list the rules")
    rules.add_argument("--format", choices=("text", "json"), default="text")

    explain = sub.add_parser("explain", help="show a rule's page: what, why, how to fix, examples")
    explain.add_argument("rule", metavar="CODE|NAME")

    serve = sub.add_parser(
        "serve",
        help="run the HTTP validation service (needs urdflint[server])",
        description="Run the HTTP service (urdflint.server.app:app) with uvicorn. Limits come "
        "from URDFLINT_* environment variables: MAX_URDF_BYTES, MAX_ZIP_BYTES, TIMEOUT, "
        "JOBS, QUEUE (see the README).",
    )
    serve.add_argument("--host", default="127.0.0.1", help="address to listen on")
    serve.add_argument("--port", type=int, default=8000, help="port to listen on")
    serve.add_argument(
        "--workers",
        type=int,
        default=1,
        help="server processes (each with its own URDFLINT_JOBS lint workers)",
    )
    serve.add_argument("--log-level", default="info", choices=("debug", "info", "warning", "error"))
    return parser


def _model_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--package-path",
        action="append",
        type=options.pair("="),
        default=[],
        metavar="NAME=DIR",
        help="where package NAME is (package:// and $(find NAME))",
    )
    parser.add_argument(
        "--q",
        action="append",
        type=options.joint_value,
        default=[],
        metavar="JOINT=VALUE",
        help="joint position for the mass and COM computation (repeatable)",
    )
    parser.add_argument(
        "--xacro-arg",
        action="append",
        type=options.pair(":="),
        default=[],
        metavar="NAME:=VALUE",
        help="argument for xacro files (repeatable)",
    )


def _gate_options(parser: argparse.ArgumentParser) -> None:
    """Baselines and --changed-since (urdflint.baseline, urdflint.changed)."""
    baseline = parser.add_mutually_exclusive_group()
    baseline.add_argument(
        "--write-baseline",
        type=Path,
        metavar="FILE",
        help="record the current findings in FILE (JSON) and exit 0",
    )
    baseline.add_argument(
        "--baseline",
        type=Path,
        metavar="FILE",
        help="report and fail only on findings not recorded in FILE; "
        "recorded ones that no longer occur are reported as U005",
    )
    parser.add_argument(
        "--changed-since",
        "--diff-only",
        dest="changed_since",
        metavar="REF",
        help="lint only the *.urdf/*.xacro files among PATHs changed since git REF (or untracked)",
    )


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "check":
            return run_check(args)
        if args.command == "rules":
            return run_rules(args)
        if args.command == "info":
            return run_info(args)
        if args.command == "serve":
            return run_serve(args)
        return run_explain(args)
    except UsageError as exc:
        print(f"urdflint: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except BrokenPipeError:
        return EXIT_ERROR


# -- check ---------------------------------------------------------------------------


def _overrides(args: argparse.Namespace) -> dict[str, object]:
    flat = {key: [c for group in getattr(args, key) for c in group] for key in ("select", "ignore")}
    for key, selectors in flat.items():
        try:
            registry.expand(selectors)
        except ValueError as exc:
            raise UsageError(f"--{key}: {exc}") from None
    found: dict[str, object] = {}
    if args.select:
        found["select"] = tuple(flat["select"])
    if flat["ignore"]:
        found["ignore"] = tuple(flat["ignore"])
    if args.exit_zero:
        found["fail_on"] = "never"
    elif args.fail_on:
        found["fail_on"] = args.fail_on
    if args.target:
        found["targets"] = tuple(dict.fromkeys(args.target))
    if args.xacro_arg:
        found["xacro_args"] = dict(args.xacro_arg)
    return found


class SettingsFinder:
    """Effective settings per file: discovered (or given) config plus CLI overrides."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.overrides = _overrides(args) if args.command == "check" else {}
        if args.command == "info" and args.xacro_arg:
            self.overrides["xacro_args"] = dict(args.xacro_arg)
        self.expect_mass = getattr(args, "expect_mass", None)
        self.expect_com = getattr(args, "expect_com", None)
        self.q = dict(args.q)
        self.isolated = args.isolated
        self.explicit = config.load(args.config) if args.config else None
        self.cache: dict[Path, config.Settings] = {}

    def for_folder(self, folder: Path) -> config.Settings:
        if self.explicit is not None:
            return self._apply(self.explicit)
        if self.isolated:
            return self._apply(config.Settings())
        folder = folder.resolve()
        if folder not in self.cache:
            found = config.discover(folder)
            self.cache[folder] = config.load(found) if found else config.Settings()
        return self._apply(self.cache[folder])

    def _apply(self, settings: config.Settings) -> config.Settings:
        extra: dict[str, Any] = dict(self.overrides)
        if "ignore" in extra:
            extra["ignore"] = settings.ignore + tuple(extra["ignore"])
        if "xacro_args" in extra:
            extra["xacro_args"] = {**settings.xacro_args, **extra["xacro_args"]}
        expect = settings.expect
        if self.expect_mass is not None:
            mass, absolute, fraction = self.expect_mass
            expect = replace(expect, mass=mass, mass_abs_tolerance=absolute)
            if fraction is not None:
                expect = replace(expect, mass_tolerance=fraction)
        if self.expect_com is not None:
            com, tolerance = self.expect_com
            expect = replace(expect, com=com)
            if tolerance is not None:
                expect = replace(expect, com_tolerance=tolerance)
        if self.q:
            expect = replace(expect, q={**expect.q, **self.q})
        return replace(settings, expect=expect, **extra)


def collect(paths: Sequence[str]) -> tuple[list[str], list[str]]:
    """Files to lint (``-`` kept as is) and one error message per unusable path."""
    files: list[str] = []
    errors: list[str] = []
    for raw in paths:
        if raw == "-":
            files.append(raw)
            continue
        path = Path(raw)
        if path.is_dir():
            found = sorted(
                p
                for p in path.rglob("*.urdf")
                if p.is_file()
                and not any(
                    part.startswith(".") or part in SKIP_DIRS
                    for part in p.relative_to(path).parts[:-1]
                )
            )
            files.extend(str(p) for p in found)
        elif path.is_file():
            files.append(raw)
        elif path.exists():
            errors.append(f"{raw}: not a regular file")
        else:
            errors.append(f"{raw}: no such file or directory")
    return list(dict.fromkeys(files)), errors


def run_check(args: argparse.Namespace) -> int:
    from urdflint import linter

    try:
        finder = SettingsFinder(args)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    files, errors = collect(args.paths)
    files = _changed_only(args, files)
    accepted = _load_baseline(args)
    context = _context(args)
    findings: list[Finding] = []
    checked: list[str] = []
    models: dict[str, Any] = {}
    skipped: dict[str, tuple[str, ...]] = {}
    fail_on = "error"
    crashed = False
    expects = False
    if args.emit_expanded and not (len(files) == 1 and linter.is_xacro(files[0])):
        raise UsageError("--emit-expanded needs exactly one xacro file")
    reports = _reports(args)
    ran: dict[str, tuple[str, ...]] = {}
    for name in files:
        is_stdin = name == "-"
        shown = args.stdin_filename if is_stdin else name
        try:
            settings = finder.for_folder(Path.cwd() if is_stdin else Path(name).parent)
        except config.ConfigError as exc:
            raise UsageError(str(exc)) from None
        try:
            if is_stdin:
                result = linter.lint_bytes(
                    sys.stdin.buffer.read(), shown, settings, context, Path.cwd()
                )
            else:
                result = linter.lint_path(Path(name), shown, settings, context)
        except OSError as exc:
            errors.append(f"{shown}: cannot read: {exc.strerror or exc}")
            continue
        checked.append(shown)
        ran[shown] = result.ran
        findings.extend(result.findings)
        skipped.update(result.skipped)
        crashed = crashed or result.crashed
        fail_on = settings.fail_on
        expects = expects or settings.expect.mass is not None or settings.expect.com is not None
        models[shown] = report.model_summary(result)
        if args.emit_expanded and result.document is not None:
            args.emit_expanded.write_bytes(result.document.source)
    gate = expects and bool({"P003", "P004"} & set(skipped))
    if skipped and checked and (gate or "U004" in finder.for_folder(Path.cwd()).enabled()):
        findings.append(report.skipped_note(checked[0], skipped, expects))
    findings.sort(key=Finding.sort_key)
    findings = _baseline_step(args, accepted, findings, ran)

    for message in errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    fmt = args.format
    if fmt == "auto":
        fmt = "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    run = formatters.RunInfo(__version__, tuple(checked), models, fail_on, ran)
    _write_outputs([(fmt, args.output), *reports], findings, run)

    if not files and not errors and args.changed_since:
        print(
            f"urdflint: no *.urdf or *.xacro files changed since {args.changed_since}",
            file=sys.stderr,
        )
        return EXIT_OK
    if errors or crashed or not files:
        if not files and not errors:
            print("urdflint: error: no *.urdf or *.xacro files found", file=sys.stderr)
        return EXIT_ERROR
    threshold = FAIL_LEVEL.get(fail_on)
    if threshold is not None and any(f.severity >= threshold for f in findings):
        return EXIT_FINDINGS
    return EXIT_OK


def _changed_only(args: argparse.Namespace, files: list[str]) -> list[str]:
    """``--changed-since``: the files among ``files`` (and folder PATHs) git reports as changed."""
    if not args.changed_since:
        return files
    from urdflint import changed

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
    from urdflint import baseline

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
    from urdflint import baseline

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


def _context(args: argparse.Namespace) -> Any:
    from urdflint.context import Context

    return Context(package_paths={name: Path(folder) for name, folder in args.package_path})


def run_info(args: argparse.Namespace) -> int:
    from urdflint import info, linter

    try:
        settings = SettingsFinder(args).for_folder(Path(args.path).parent)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    path = Path(args.path)
    if not path.is_file():
        raise UsageError(f"{args.path}: no such file")
    try:
        doc = linter.load(path, args.path, settings, _context(args))
    except OSError as exc:
        raise UsageError(f"{args.path}: cannot read: {exc.strerror or exc}") from None
    text, ok = info.render(doc, args.format)
    sys.stdout.write(text)
    return EXIT_OK if ok else EXIT_FINDINGS


# -- serve ------------------------------------------------------------------------------


def run_serve(args: argparse.Namespace) -> int:
    """Run uvicorn with the service; its imports happen here, never at CLI start."""
    try:
        import uvicorn
    except ImportError:
        raise UsageError("serve needs the server extra: pip install 'urdflint[server]'") from None
    if args.workers < 1 or not 0 <= args.port < 65536:
        raise UsageError("--workers must be at least 1 and --port between 0 and 65535")
    from urdflint.server.limits import LimitError, Limits

    try:
        Limits.from_env()
    except LimitError as exc:
        raise UsageError(str(exc)) from None
    uvicorn.run(
        "urdflint.server.app:app",
        host=args.host,
        port=args.port,
        workers=args.workers,
        log_level=args.log_level,
        timeout_keep_alive=5,
        timeout_graceful_shutdown=10,
    )
    return EXIT_OK


# -- rules and explain ---------------------------------------------------------------


def run_rules(args: argparse.Namespace) -> int:
    rules = registry.load_rules()
    if args.format == "json":
        data = [
            {
                "code": r.code,
                "name": r.name,
                "severity": str(r.severity),
                "family": registry.FAMILIES[r.family],
                "summary": r.summary,
                "needs": list(r.needs),
                "options": dict(r.options),
            }
            for r in sorted(rules.values(), key=lambda r: r.code)
        ]
        print(json.dumps({"version": 1, "rules": data}, indent=2))
        return EXIT_OK
    for r in sorted(rules.values(), key=lambda r: r.code):
        print(f"{r.code}  {r.name:<36} {r.severity!s:<8} {r.summary}")
    return EXIT_OK


def run_explain(args: argparse.Namespace) -> int:
    from urdflint import docs

    found = registry.lookup(args.rule)
    if found is None:
        raise UsageError(f"unknown rule {args.rule!r} (see 'urdflint rules')")
    sys.stdout.write(docs.page(found))
    return EXIT_OK
