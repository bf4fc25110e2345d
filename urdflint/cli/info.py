"""``urdflint info``: the model's tree, per-link masses, total mass, COM and DOF."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from urdflint.cli.common import EXIT_FINDINGS, EXIT_OK, UsageError, model_options, run_context
from urdflint.engine import config
from urdflint.engine.options import SettingsFinder


def add_parser(sub: Any) -> None:
    info = sub.add_parser("info", help="the model: tree, per-link masses, total mass, COM, DOF")
    info.add_argument("path", metavar="PATH", help="a URDF or xacro file")
    info.add_argument("--format", choices=("text", "json"), default="text")
    info.add_argument("--config", type=Path, metavar="FILE")
    info.add_argument("--isolated", action="store_true")
    info.add_argument(
        "--statics",
        action="store_true",
        help="also each joint's largest gravity torque, its effort limit and margin, the "
        "weakest joint and the payload it allows (Pinocchio; --payload, --gravity)",
    )
    model_options(info)


def run(args: argparse.Namespace) -> int:
    from urdflint.engine import linter
    from urdflint.outputs import info

    try:
        settings = SettingsFinder(args).for_folder(Path(args.path).parent)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    path = Path(args.path)
    if not path.is_file():
        raise UsageError(f"{args.path}: no such file")
    try:
        doc = linter.load(path, args.path, settings, run_context(args))
    except OSError as exc:
        raise UsageError(f"{args.path}: cannot read: {exc.strerror or exc}") from None
    text, ok = info.render(doc, args.format, statics=args.statics)
    sys.stdout.write(text)
    return EXIT_OK if ok else EXIT_FINDINGS
