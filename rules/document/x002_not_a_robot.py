"""The document is not a URDF `<robot>`, or it declares a DOCTYPE or entities.

## What it does
Reports a root element other than `<robot>`, and any `<!DOCTYPE>` or entity
reference. urdflint refuses such documents instead of expanding them.

## Why is this bad?
Every URDF parser looks for `<robot>` as the root and finds nothing otherwise.
URDF never needs a DTD; entity declarations are how XML bombs and external
file reads (XXE) are smuggled into parsers, so they are never expanded.

## How to fix
Make `<robot name="...">` the root element. Remove the DOCTYPE and replace
entities by their values (or use xacro properties, which are expanded first).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule("X002", "not-a-robot", Severity.ERROR, requires_robot=False)
def check(doc: Document) -> Iterator[Hit]:
    problem = doc.problem
    if problem is not None and problem.code == "X002":
        line, column = problem.line, problem.column
        yield Hit(None, problem.message, line=line, column=column, path=problem.path)
