"""An inline suppression that suppressed nothing.

## What it does
Reports `<!-- urdflint: ignore[...] -->` and `ignore-file[...]` comments whose
codes matched no finding in the element (or file) they cover.

## Why is this bad?
A stale suppression hides the next real problem of that kind on that element,
and it tells readers that a defect exists when it was fixed long ago.

## How to fix
Delete the comment, or remove the codes that no longer apply from it.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.finding import Severity


@rule("U002", "unused-suppression", Severity.INFO, fix="Remove the stale suppression comment.")
def check(doc: object) -> Iterator[Hit]:
    """Produced by the engine after suppressions were applied."""
    yield from ()
