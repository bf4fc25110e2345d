"""What a ``check`` would do, and helping a package adopt urdflint: the options
``--show-files``, ``--show-settings``, ``--add-noqa`` and ``--watch`` (one at a time).

``--show-files`` prints the files the run would check (after the discovery of folders, the
choice of entry xacro files and ``--changed-since``), one per line; ``--show-settings`` the
settings of each (:mod:`urdflint.cli.show_settings`). Neither lints anything; both exit 0
(2 when a path cannot be used). ``--add-noqa`` is :mod:`urdflint.cli.noqa`, ``--watch``
:mod:`urdflint.cli.watch`.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from urdflint.cli.common import EXIT_ERROR, EXIT_OK


def add_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--show-files",
        action="store_true",
        help="print the files that would be checked, one per line, and exit without linting",
    )
    group.add_argument(
        "--show-settings",
        action="store_true",
        help="print the settings each file would be checked with (configuration file, "
        "targets and why, rules, xacro arguments, statics and stability, the folder of each "
        "package it uses and why) and exit without linting; --format json for JSON",
    )
    group.add_argument(
        "--add-noqa",
        action="store_true",
        help="write a suppression comment (<!-- urdflint: ignore[CODE] -->) before the "
        "element of every error and warning reported now, and list what a comment cannot "
        "suppress",
    )
    group.add_argument(
        "--watch",
        action="store_true",
        help="check, then check again whenever a checked file or a file it reads (xacro "
        "includes, meshes, package.xml, the configuration) changes; Ctrl-C stops",
    )


def requested(args: argparse.Namespace) -> bool:
    """Whether the run is one of the modes here that replace linting."""
    return any(getattr(args, name, False) for name in ("show_files", "show_settings", "add_noqa"))


def run(
    args: argparse.Namespace, files: list[str], errors: list[str], context: Any, finder: Any
) -> int:
    """The mode asked for, on the files a ``check`` would lint."""
    try:
        if args.add_noqa:
            from urdflint.cli import noqa

            return noqa.run(args, files, errors, finder, context)
        if args.show_settings:
            from urdflint.cli import show_settings

            show_settings.write(args, files, context, finder, sys.stdout)
        else:
            sys.stdout.writelines(f"{name}\n" for name in files)
            sys.stdout.flush()
    finally:
        if context.cache is not None:
            context.cache.finish()
    for message in errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    if not files and not errors:
        since = f" changed since {args.changed_since}" if args.changed_since else " found"
        print(f"urdflint: no *.urdf or *.xacro files{since}", file=sys.stderr)
    return EXIT_ERROR if errors else EXIT_OK
