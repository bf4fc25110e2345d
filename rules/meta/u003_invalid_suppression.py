"""A `urdflint:` comment that is not a valid suppression.

## What it does
Reports `<!-- urdflint: ... -->` comments without rule codes, with unknown
codes, with an unknown directive, or with nothing after them to suppress.

## Why is this bad?
The author meant to silence a finding and the comment does nothing, or would
silence everything. urdflint requires explicit codes so a suppression never
hides more than intended.

## How to fix
Write `<!-- urdflint: ignore[CODE,...] reason -->` directly before the element,
or `<!-- urdflint: ignore-file[CODE] -->` anywhere for the whole file.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.finding import Severity


@rule("U003", "invalid-suppression", Severity.WARNING)
def check(doc: object) -> Iterator[Hit]:
    """Produced by the engine while it reads the suppressions."""
    yield from ()
