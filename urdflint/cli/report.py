"""``urdflint report RESULTS...``: a dataset run's ``--format jsonl`` records summarised.

Several RESULTS are the shards of one run (the last record of a path wins). The summary
goes to stdout (text, or ``--format json``); ``--html FILE`` writes one self-contained
page, ``--parquet FOLDER`` the tables ``files.parquet`` and ``findings.parquet`` (pyarrow).
``--against OLD...`` compares with an earlier run's records. Exit 0, or 2 with one line on
stderr when a RESULTS file is not records or an output cannot be written.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from urdflint.cli.common import EXIT_OK, UsageError

__all__ = ["add_parser", "run"]


def _top(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError("must be 0 or more")
    return value


def add_parser(sub: Any) -> None:
    parser = sub.add_parser(
        "report",
        help="summarise the records of check --format jsonl (text, JSON, HTML, Parquet)",
        description="Summarise a dataset run: the records `urdflint check --format jsonl` "
        "wrote (several files: the shards of one run). Counts per status, severity and rule, "
        "the load matrix per target, the worst assets and the distributions of mass, link "
        "count and findings per file; with --against, what changed since an earlier run.",
    )
    parser.add_argument(
        "results",
        nargs="+",
        type=Path,
        metavar="RESULTS",
        help="JSONL files written by check --format jsonl",
    )
    parser.add_argument(
        "--against",
        nargs="+",
        action="extend",
        type=Path,
        default=[],
        metavar="OLD",
        help="an earlier run's JSONL files: report what changed",
    )
    parser.add_argument(
        "--format",
        choices=("text", "json"),
        default="text",
        help="the summary on stdout (default: text)",
    )
    parser.add_argument(
        "--html",
        type=Path,
        metavar="FILE",
        help="also write the report as one self-contained HTML page",
    )
    parser.add_argument(
        "--parquet",
        type=Path,
        metavar="FOLDER",
        help="also write files.parquet and findings.parquet into FOLDER (needs pyarrow)",
    )
    parser.add_argument(
        "--top",
        type=_top,
        default=20,
        metavar="N",
        help="how many of the worst assets to list (default: 20)",
    )


def _needs_pyarrow() -> None:
    from urdflint.model import optional

    if not optional.available("pyarrow"):
        raise UsageError(f"--parquet needs pyarrow: {optional.install_command('cluster')}")


def run(args: argparse.Namespace) -> int:
    from urdflint.outputs import records
    from urdflint.outputs.dataset import compare, load, summarize

    if args.parquet is not None:
        _needs_pyarrow()  # before the reading: a missing library fails fast
    try:
        found = load(args.results)
        old = load(args.against) if args.against else None
    except records.Unreadable as exc:
        raise UsageError(str(exc)) from None
    summary = summarize(found, top=args.top)
    summary["results"] = [str(p) for p in args.results]
    if old is not None:
        summary["against"] = [str(p) for p in args.against]
        summary["diff"] = compare(old, found)
    if args.html is not None:
        from urdflint.outputs.dataset import html

        _write(args.html, html.render(summary))
    if args.parquet is not None:
        _parquet(found, args.parquet)
    if args.format == "json":
        sys.stdout.write(json.dumps(summary, indent=2, ensure_ascii=False) + "\n")
    else:
        from urdflint.outputs.dataset import text

        sys.stdout.write(text.render(summary))
    return EXIT_OK


def _write(path: Path, content: str) -> None:
    try:
        path.write_text(content, encoding="utf-8")
    except OSError as exc:
        raise UsageError(f"{path}: cannot write: {exc.strerror or exc}") from None


def _parquet(found: list[dict[str, Any]], folder: Path) -> None:
    from urdflint.model import optional
    from urdflint.outputs.dataset import parquet

    try:
        parquet.write(found, folder)
    except ImportError:  # an install that find_spec sees but that does not import
        raise UsageError(
            f"--parquet needs pyarrow: {optional.install_command('cluster')}"
        ) from None
    except OSError as exc:
        raise UsageError(f"{folder}: cannot write: {exc.strerror or exc}") from None
