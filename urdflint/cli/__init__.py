"""Command line: ``urdflint check|info|rules|explain|serve``. Owns I/O and exit codes, no lint
logic; each command is its own module (``add_parser`` and ``run``).

Exit codes: 0 nothing at or above ``--fail-on``; 1 findings at or above it;
2 usage error, unreadable path, invalid configuration or an internal error.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from urdflint import __version__
from urdflint.cli import cache, check, info, lsp, mcp, report, rules, serve
from urdflint.cli.common import EXIT_ERROR, EXIT_FINDINGS, EXIT_OK, UsageError
from urdflint.engine.options import SettingsFinder
from urdflint.sources.discovery import collect

__all__ = ["EXIT_ERROR", "EXIT_FINDINGS", "EXIT_OK", "SettingsFinder", "UsageError",
           "build_parser", "collect", "main"]  # fmt: skip

COMMANDS = {
    "check": check.run,
    "fix": check.run,
    "info": info.run,
    "rules": rules.run_rules,
    "explain": rules.run_explain,
    "serve": serve.run,
    "lsp": lsp.run,
    "mcp": mcp.run,
    "cache": cache.run,
    "report": report.run,
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="urdflint",
        description="Lint robot descriptions (URDF): every problem, with line, rule code and fix.",
    )
    parser.add_argument("--version", action="version", version=f"urdflint {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    check.add_parser(sub)
    info.add_parser(sub)
    rules.add_parsers(sub)
    serve.add_parser(sub)
    lsp.add_parser(sub)
    mcp.add_parser(sub)
    cache.add_parser(sub)
    report.add_parser(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return COMMANDS[args.command](args)
    except UsageError as exc:
        print(f"urdflint: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except BrokenPipeError:
        return EXIT_ERROR
