"""A baseline entry whose finding no longer occurs.

## What it does
With `--baseline FILE`, reports each recorded finding (file, rule code, element)
that did not occur in this run, once per entry, with how many of its recorded
occurrences are gone. Only entries for files that were checked, and for rules
that ran on them, are considered, so linting a subset of the files (or of the
rules) never makes the rest of the baseline look stale.

## Why is this bad?
The problem was fixed, but the baseline still accepts it: if it comes back on
that element it would pass unnoticed. A baseline should only ever shrink.

## How to fix
Rewrite the baseline with `urdflint check --write-baseline FILE PATH...` and
commit it. The finding is informational, so it fails the run only with
`--fail-on info`, which is how a CI job can insist that baselines shrink.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.finding import Severity


@rule(
    "U005",
    "stale-baseline-entry",
    Severity.INFO,
    requires_robot=False,
    fix="Rewrite the baseline with --write-baseline FILE so it only keeps what still occurs.",
)
def check(doc: object) -> Iterator[Hit]:
    """Produced by the command line when it applies a baseline."""
    yield from ()
