"""The options about the rest of the description package: the SRDF and the conventions."""

from __future__ import annotations

import argparse

from urdflint.engine import config


def add_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--srdf",
        metavar="FILE",
        help="the robot's MoveIt SRDF or .srdf.xacro (M rules); default: <stem>.srdf beside "
        "the file, the package's config/*.srdf of the same robot, or the SRDF a MoveIt config "
        "package's .setup_assistant pairs with it",
    )
    parser.add_argument(
        "--profile",
        choices=config.PROFILES,
        help="also check the naming conventions (REP 103/105/120/199) of this kind of robot",
    )
