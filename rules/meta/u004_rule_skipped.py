"""Rules were skipped because an optional dependency is not installed.

## What it does
Notes, once per run, which rules did not run and which extra provides them
(for example Pinocchio from `urdflint[dynamics]`).

## Why is this bad?
It is not: the light install is deliberate (Pinocchio alone is about 480 MB and
has no Windows wheels). The note makes sure a clean result is not mistaken for a
full one.

## How to fix
Install the named extra, e.g. `pip install "urdflint[full]"`, or use the
`urdflint-full` pre-commit hook.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.finding import Severity


@rule("U004", "rule-skipped", Severity.INFO, requires_robot=False)
def check(doc: object) -> Iterator[Hit]:
    """Produced by the command line after the run."""
    yield from ()
