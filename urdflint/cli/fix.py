"""``urdflint fix`` / ``check --fix``: apply the automatic fixes, round after round.

A round lints every file, applies the fixes of the findings (safe ones; unsafe ones too with
``--unsafe-fixes``) as text edits, and writes the files; the next round lints the result, so
a fix that only becomes possible after another (or that overlapped another) is applied then.
Rounds stop when nothing changes. ``--diff`` prints what the first round would change, as a
unified diff, and writes nothing.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Callable
from typing import Any

from urdflint.cli.common import EXIT_FINDINGS, EXIT_OK, UsageError


def add_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--fix",
        action="store_true",
        help="apply the automatic fixes (safe ones; see --unsafe-fixes) and report what is left",
    )
    parser.add_argument(
        "--unsafe-fixes",
        action="store_true",
        help="also apply fixes that change the model's physics (inertias, limits)",
    )
    parser.add_argument(
        "--density",
        type=density,
        metavar="KG_PER_M3",
        help="density of the <inertial> that the unsafe fix of I001 computes from a link's "
        "collision geometry (default 1000, MuJoCo's; rules.I001.density in the configuration)",
    )
    parser.add_argument(
        "--write-meshes",
        action="store_true",
        help="let the unsafe fix of C001 give a mesh visual a collision: its convex hull, "
        "written as <stem>_hull.obj beside the mesh (never over an existing file)",
    )
    parser.add_argument(
        "--diff",
        action="store_true",
        help="print the fixes as a unified diff and change nothing (exit 1 if there is one)",
    )


def density(text: str) -> float:
    """``--density``: a positive number of kg/m³."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (value > 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"expected a positive density in kg/m³, got {text!r}")
    return value


def rounds(args: argparse.Namespace, lint: Callable[[], Any]) -> tuple[Any, dict[str, bytes], int]:
    """Lint and fix until nothing changes (:func:`urdflint.engine.fixes.rounds`); the last
    lint's outcome, each changed file's original bytes, and how many fixes were applied."""
    from urdflint.engine import fixes

    return fixes.rounds(lint, args.unsafe_fixes, _write)


def _write(path: str, data: bytes) -> None:
    with open(path, "wb") as out:
        out.write(data)


def diff(args: argparse.Namespace, outcome: Any) -> int:
    """Print the first round's fixes as a unified diff; the number of files it changes."""
    import difflib

    from urdflint.engine import fixes

    found = [f.autofix for f in outcome.findings if f.autofix is not None]
    changed = fixes.apply_all(found, unsafe=args.unsafe_fixes)
    for path, (old, new, _) in sorted(changed.items()):
        sys.stdout.writelines(
            difflib.unified_diff(
                old.decode("utf-8", "replace").splitlines(keepends=True),
                new.decode("utf-8", "replace").splitlines(keepends=True),
                fromfile=path if os.path.lexists(path) else "/dev/null",
                tofile=path,
            )
        )
    return len(changed)


def drive(
    args: argparse.Namespace, files: list[str], lint: Callable[[], Any]
) -> tuple[Any, int | None]:
    """The run's outcome: linted, or fixed then linted; with ``--diff``, the exit code."""
    fixing = args.command == "fix" or args.fix
    if (fixing or args.diff) and "-" in files:
        raise UsageError("--fix and --diff need files, not standard input")
    if args.diff:
        return None, EXIT_FINDINGS if diff(args, lint()) else EXIT_OK
    if not fixing:
        return lint(), None
    outcome, originals, applied = rounds(args, lint)
    created = sorted(path for path, old in originals.items() if not old)
    args.fixed = (len(originals) - len(created), applied, created)
    return outcome, None


def report(args: argparse.Namespace, findings: list[Any]) -> None:
    """One line on stderr: what was fixed, and what more ``--unsafe-fixes`` would fix."""
    if not hasattr(args, "fixed"):
        return
    files, applied, created = args.fixed
    left = [f for f in findings if f.autofix is not None and not f.autofix.unavailable]
    unsafe = args.unsafe_fixes
    more = sum(1 for f in left if f.autofix.applicability == "unsafe") if not unsafe else 0
    text = f"urdflint: fixed {applied} finding{'s' if applied != 1 else ''}"
    text += f" in {files} file{'s' if files != 1 else ''}"
    if created:
        text += f"; wrote {', '.join(created)}"
    if more:
        text += f"; {more} more with --unsafe-fixes"
    print(text, file=sys.stderr)
