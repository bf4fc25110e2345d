"""A rule crashed while checking this file.

## What it does
Reports a rule that raised an exception. The engine catches it, reports it as
this finding and carries on with the other rules and files.

## Why is this bad?
The file was not fully checked: the crashed rule's findings are missing. This
is a bug in urdflint, not in your robot, and the run exits with code 2 so a CI
gate does not pass on an incomplete check.

## How to fix
Report it with the file that triggers it. Meanwhile `--ignore` the crashed rule.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.finding import Severity


@rule("U001", "internal-error", Severity.ERROR, requires_robot=False)
def check(doc: object) -> Iterator[Hit]:
    """Produced by the engine (``linter._run``) when a rule raises."""
    yield from ()
