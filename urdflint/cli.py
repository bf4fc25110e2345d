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

from urdflint import __version__, config, formatters, registry, targets
from urdflint.finding import Finding, Severity

EXIT_OK, EXIT_FINDINGS, EXIT_ERROR = 0, 1, 2
SKIP_DIRS = {"node_modules", "__pycache__", "build", "install", "log"}
FAIL_LEVEL = {"error": Severity.ERROR, "warning": Severity.WARNING, "info": Severity.INFO}


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

    rules = sub.add_parser("rules", help="list the rules")
    rules.add_argument("--format", choices=("text", "json"), default="text")

    explain = sub.add_parser("explain", help="show a rule's page: what, why, how to fix, examples")
    explain.add_argument("rule", metavar="CODE|NAME")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "check":
            return run_check(args)
        if args.command == "rules":
            return run_rules(args)
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
    return found


class SettingsFinder:
    """Effective settings per file: discovered (or given) config plus CLI overrides."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.overrides = _overrides(args)
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
        return replace(settings, **extra)


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
    findings: list[Finding] = []
    checked: list[str] = []
    skipped: dict[str, tuple[str, ...]] = {}
    fail_on = "error"
    crashed = False
    for name in files:
        is_stdin = name == "-"
        shown = args.stdin_filename if is_stdin else name
        try:
            settings = finder.for_folder(Path.cwd() if is_stdin else Path(name).parent)
        except config.ConfigError as exc:
            raise UsageError(str(exc)) from None
        try:
            data = sys.stdin.buffer.read() if is_stdin else Path(name).read_bytes()
        except OSError as exc:
            errors.append(f"{shown}: cannot read: {exc.strerror or exc}")
            continue
        result = linter.lint_bytes(data, shown, settings)
        checked.append(shown)
        findings.extend(result.findings)
        skipped.update(result.skipped)
        crashed = crashed or result.crashed
        fail_on = settings.fail_on
    if skipped and checked and "U004" in finder.for_folder(Path.cwd()).enabled():
        findings.append(_skipped_note(checked[0], skipped))
    findings.sort(key=Finding.sort_key)

    for message in errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    fmt = args.format
    if fmt == "auto":
        fmt = "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    run = formatters.RunInfo(__version__, tuple(checked))
    sys.stdout.write(formatters.get(fmt)(findings, run))
    sys.stdout.flush()

    if errors or crashed or not files:
        if not files and not errors:
            print("urdflint: error: no *.urdf files found", file=sys.stderr)
        return EXIT_ERROR
    threshold = FAIL_LEVEL.get(fail_on)
    if threshold is not None and any(f.severity >= threshold for f in findings):
        return EXIT_FINDINGS
    return EXIT_OK


def _skipped_note(path: str, skipped: dict[str, tuple[str, ...]]) -> Finding:
    from urdflint.linter import EXTRAS

    rule = registry.RULES["U004"]
    modules = sorted({m for missing in skipped.values() for m in missing})
    extras = sorted({EXTRAS.get(m, m) for m in modules})
    message = (
        f"{len(skipped)} rule(s) skipped ({', '.join(sorted(skipped))}): "
        f"{', '.join(modules)} not installed; install urdflint[{','.join(extras)}]"
    )
    return Finding(
        path,
        1,
        1,
        rule.code,
        rule.name,
        rule.severity,
        message,
        "/robot",
        f"pip install 'urdflint[{','.join(extras)}]'",
    )


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
