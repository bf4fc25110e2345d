"""The file is not well-formed XML.

## What it does
Reports the XML syntax error lxml found, with its line and column. It also
reports files over 64 MiB, which urdflint refuses to parse.

## Why is this bad?
No URDF consumer can read the file at all. Note that yourdfpy silently
retries such files in recover mode and may load half of the robot.

## How to fix
Fix the syntax at the reported position: an unclosed tag, a stray `<` or `&`
(write `&lt;`/`&amp;`), mismatched quotes or a second root element.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule("X001", "invalid-xml", Severity.ERROR, requires_robot=False)
def check(doc: Document) -> Iterator[Hit]:
    problem = doc.problem
    if problem is not None and problem.code == "X001":
        line, column = problem.line, problem.column
        yield Hit(None, problem.message, line=line, column=column, path=problem.path)
