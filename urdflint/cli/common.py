"""What the commands share: exit codes, the usage error, option groups, the run context."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from urdflint.engine import options, statics_settings
from urdflint.engine.options import UsageError

EXIT_OK, EXIT_FINDINGS, EXIT_ERROR = 0, 1, 2

__all__ = [
    "EXIT_ERROR",
    "EXIT_FINDINGS",
    "EXIT_OK",
    "UsageError",
    "cache_options",
    "gate_options",
    "model_options",
    "open_cache",
    "run_context",
    "settings_here",
]  # fmt: skip


def cache_options(parser: argparse.ArgumentParser) -> None:
    """``--no-cache`` and ``--cache-dir`` (urdflint.cache)."""
    parser.add_argument(
        "--no-cache",
        action="store_true",
        help="neither read nor write the analysis cache",
    )
    parser.add_argument(
        "--cache-dir",
        type=Path,
        metavar="DIR",
        help="the analysis cache folder (default: cache-dir in the configuration, "
        "$URDFLINT_CACHE_DIR, else $XDG_CACHE_HOME/urdflint or ~/.cache/urdflint)",
    )


def settings_here(args: argparse.Namespace | None = None) -> Any:
    """The configuration of the current folder (``--config``, ``--isolated`` honoured), or
    ``None`` when there is none or it is invalid: what ``cache`` and ``lsp`` read of it is
    where the cache lives."""
    from urdflint.engine import config

    if args is not None and getattr(args, "isolated", False):
        return None
    try:
        if args is not None and getattr(args, "config", None):
            return config.load(args.config)
        found = config.discover(Path.cwd())
        return config.load(found) if found else None
    except config.ConfigError:
        return None


def open_cache(args: argparse.Namespace, settings: Any = None) -> Any:
    """The run's :class:`urdflint.cache.Cache`, or ``None`` with ``--no-cache`` (or
    ``URDFLINT_NO_CACHE=1``)."""
    import os

    if getattr(args, "no_cache", False) or os.environ.get("URDFLINT_NO_CACHE", "") not in (
        "",
        "0",
    ):
        return None
    from urdflint.cache import DEFAULT_MAX_BYTES, Cache

    folder = getattr(args, "cache_dir", None) or getattr(settings, "cache_dir", None)
    size = getattr(settings, "cache_max_size", None) or DEFAULT_MAX_BYTES
    found = Cache(folder, size)
    return found if found.usable else None


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
    statics_settings.add_options(parser)  # --payload, --gravity: the D rules, info --statics


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


def run_context(args: argparse.Namespace, cache: Any = None) -> Any:
    from urdflint.engine.context import Context
    from urdflint.sources import workspace

    paths = [Path(p) for p in getattr(args, "paths", [getattr(args, "path", ".")]) if p != "-"]
    return Context(
        package_paths={name: Path(folder) for name, folder in args.package_path},
        workspace=workspace.Packages(paths or [Path.cwd()], cache),
        cache=cache,
    )
