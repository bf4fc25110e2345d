"""The options of ``urdflint check`` and ``urdflint fix``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from urdflint.cli import fix, package, show
from urdflint.cli.common import cache_options, gate_options, model_options
from urdflint.engine import config, options
from urdflint.model import targets
from urdflint.outputs import formatters


def _codes(value: str) -> list[str]:
    return [part.strip() for part in value.split(",") if part.strip()]


def _jobs(value: str) -> int:
    try:
        jobs = int(value)
    except ValueError:
        jobs = 0
    if jobs < 1:
        raise argparse.ArgumentTypeError(f"expected 1 or more processes, got {value!r}")
    return jobs


HELP = {
    "check": "lint files and folders (folders: every *.urdf and entry *.xacro below)",
    "fix": "apply the automatic fixes, then report what is left (check --fix)",
}


def add_parser(sub: Any) -> None:
    for name, text in HELP.items():
        _options(sub.add_parser(name, help=text))


def _options(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "paths",
        nargs="+",
        metavar="PATH",
        help="file, folder (every *.urdf and entry *.xacro below), or - for stdin",
    )
    check.add_argument(
        "--format",
        default="auto",
        choices=("auto", *formatters.NAMES, "jsonl"),
        help="output format; auto = github when GITHUB_ACTIONS is set, else text; jsonl = "
        "one record per file, written as each file finishes",
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
    _display_options(check)
    _target_options(check)
    _more_options(check)
    cache_options(check)
    fix.add_options(check)
    _jobs_option(check)
    _dataset_options(check)
    _show_packages_option(check)


def _target_options(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "--target",
        action="append",
        type=options.target_list,
        default=[],
        metavar="TARGETS",
        help="consumers the model is meant for: "
        + ", ".join((*targets.TARGETS, targets.ALL))
        + " (comma-separated or repeated; default: inferred from the model and its package,"
        " else gz-sim and ros; all: every one)",
    )
    package.add_options(check)
    check.add_argument(
        "--matrix",
        action="store_true",
        help="show what each target will do with the model: loads, loads with changes, "
        "refused or crashes, and the findings that decide it (with --confirm: what the "
        "engines did)",
    )


def _jobs_option(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "--jobs",
        "-j",
        type=_jobs,
        default=None,
        metavar="N",
        help="check files in N processes (default: one per CPU for 8 files or more, else 1); "
        "the output is the same as with --jobs 1",
    )


def _dataset_options(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "--executor",
        choices=("local", "ray"),
        default="local",
        help="where files are checked: local (--jobs processes here) or ray (tasks on a Ray "
        "cluster, each file and each --confirm engine its own; needs the cluster extra)",
    )
    check.add_argument(
        "--ray-address",
        metavar="ADDRESS",
        default=None,
        help="the Ray cluster --executor ray joins (host:port or ray://host:port); default: "
        "$RAY_ADDRESS, else a Ray running here, else a new local one",
    )
    check.add_argument(
        "--resume",
        metavar="FILE",
        default=None,
        help="records of an earlier run (--format jsonl): files whose content, settings and "
        "inputs are unchanged are not checked again; new records are appended to FILE",
    )


def _show_packages_option(check: argparse.ArgumentParser) -> None:
    check.add_argument(
        "--show-packages",
        action="store_true",
        help="list on stderr which folder each package name (package://, $(find)) resolves "
        "to for the files checked, and why; findings and exit code stay the same",
    )
    show.add_options(check)  # --show-files, --show-settings, --add-noqa, --watch


def _more_options(check: argparse.ArgumentParser) -> None:
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
    model_options(check)
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
        "--confirm",
        action="append",
        type=options.engine_list,
        default=[],
        metavar="ENGINES",
        help="also load the model in these engines (mujoco, pybullet, drake, pinocchio, "
        "sdformat or all; "
        "comma-separated) and report what they refuse, drop, warn about or crash on (E rules)",
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
        help="also write FORMAT (" + ", ".join((*formatters.NAMES, "jsonl")) + ") to PATH, "
        "repeatable, e.g. --report sarif:urdflint.sarif --report junit:urdflint.xml",
    )
    gate_options(check)


def _display_options(check: argparse.ArgumentParser) -> None:
    """How the main output shows the findings; never which findings or the exit code."""
    check.add_argument(
        "--show-info",
        action="store_true",
        help="list info findings in the text output (default: one summary line; "
        "--fail-on info and the machine formats always list them)",
    )
    check.add_argument(
        "--output-format",
        choices=("concise", "full"),
        default="concise",
        help="text format: concise (default) writes the findings of one rule at one source "
        "line (a macro called N times) as one line, ×N; full writes each finding with its "
        "macro calls, its effects and the source line it points to",
    )
    check.add_argument(
        "--statistics",
        action="store_true",
        help="instead of the findings, one row per rule: count, code, name, severity, "
        "fixable, most frequent first (a JSON list with --format json)",
    )
    check.add_argument(
        "--quiet",
        "-q",
        action="store_true",
        help="write only the findings: no info, fixable, targets or summary line",
    )
    check.add_argument(
        "--docs-url",
        metavar="URL",
        default=None,
        help="SARIF: each rule's helpUri, a URL with {code}, {name} or {path} (the rule's "
        "source in this repository), or a base URL the code is appended to (default: "
        "$URDFLINT_DOCS_URL)",
    )
