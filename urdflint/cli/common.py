"""What the commands share: exit codes, the usage error, option groups, the run context."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from urdflint.engine import options
from urdflint.engine.options import UsageError

EXIT_OK, EXIT_FINDINGS, EXIT_ERROR = 0, 1, 2

__all__ = [
    "EXIT_ERROR",
    "EXIT_FINDINGS",
    "EXIT_OK",
    "UsageError",
    "gate_options",
    "model_options",
    "run_context",
]  # fmt: skip


def model_options(parser: argparse.ArgumentParser) -> None:
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


def gate_options(parser: argparse.ArgumentParser) -> None:
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


def run_context(args: argparse.Namespace) -> Any:
    from urdflint.engine.context import Context
    from urdflint.sources import workspace

    paths = [Path(p) for p in getattr(args, "paths", [getattr(args, "path", ".")]) if p != "-"]
    return Context(
        package_paths={name: Path(folder) for name, folder in args.package_path},
        workspace=workspace.Packages(paths or [Path.cwd()]),
    )
