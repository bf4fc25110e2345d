"""The options about the rest of the description package: the SRDF and the conventions."""

from __future__ import annotations

import argparse

from urdflint.engine import config


def add_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--srdf",
        metavar="FILE",
        help="the robot's MoveIt SRDF (M rules); default: <stem>.srdf beside the file, or the "
        "package's config/*.srdf for the same robot name",
    )
    parser.add_argument(
        "--profile",
        choices=config.PROFILES,
        help="also check the naming conventions (REP 103/105/120/199) of this kind of robot",
    )
