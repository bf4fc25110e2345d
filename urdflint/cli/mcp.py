"""``urdflint mcp``: serve the linter to AI coding agents (Model Context Protocol, stdio)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from urdflint.cli.common import UsageError

SDK_MAJOR = 2  # urdflint.mcp.server uses the SDK's 2.x API


def add_parser(sub: Any) -> None:
    parser = sub.add_parser(
        "mcp",
        help="run the MCP server over stdio (check, fix, explain, info, matrix for AI agents)",
        description="Speak the Model Context Protocol on stdin/stdout: the tools check, fix, "
        "explain, info and matrix, and the rule pages as resources, for AI coding agents. "
        "Files are read and written only inside the client's roots (without roots: the "
        "current folder). Agents start it; see README (Claude, VS Code, Cursor).",
    )
    parser.add_argument(
        "--root",
        action="append",
        type=Path,
        default=[],
        metavar="DIR",
        help="confine files to DIR when the client lists no roots (repeatable; default: the "
        "current folder)",
    )


def run(args: argparse.Namespace) -> int:
    from urdflint.model.optional import install_command

    try:
        import mcp  # noqa: F401
    except ImportError:
        raise UsageError(f"urdflint mcp needs the mcp package: {install_command('mcp')}") from None
    from importlib.metadata import PackageNotFoundError, version

    try:
        found = version("mcp")
    except PackageNotFoundError:
        found = "0"
    if not found.split(".")[0].isdigit() or int(found.split(".")[0]) < SDK_MAJOR:
        raise UsageError(
            f"urdflint mcp needs mcp {SDK_MAJOR}.x, not {found}: {install_command('mcp')}"
        )
    missing = [str(folder) for folder in args.root if not folder.is_dir()]
    if missing:
        raise UsageError(f"--root {missing[0]}: no such folder")
    from urdflint.mcp.server import serve

    return serve(args.root)
