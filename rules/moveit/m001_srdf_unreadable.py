"""The robot's SRDF cannot be read: missing, not well-formed XML, or not a `<robot>`.

## What it does
Finds the MoveIt SRDF of the checked URDF (`--srdf FILE`, `srdf = "path"` in the
configuration, `<stem>.srdf` or `<stem>.srdf.xacro` beside the file, a
`config/*.srdf` of the same ROS package for the same robot name, or the SRDF a MoveIt
config package's `.setup_assistant` pairs with this URDF) and reports when that file
does not exist, is not well-formed XML, has a DOCTYPE or entities, or whose root is
not `<robot>`. A `.srdf.xacro` that urdflint cannot expand is a warning: the
expansion may need arguments or packages urdflint does not have.

## Why is this bad?
srdfdom (`srdf::Model::initString` in `src/model.cpp`) parses the SRDF with
TinyXML2 and gives up on the first syntax error ("Could not parse the SRDF XML
File"); `initXml` refuses a file without a `<robot>` root ("Could not find the
'robot' element in the xml file"). MoveIt's `RDFLoader` then has no semantic model
and `move_group` does not start. None of the other M rules can check the file.

## How to fix
Fix the XML error at the reported line, or point `--srdf` at the right file.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.sources import srdf as srdf_source


@rule(
    "M001",
    "srdf-unreadable",
    Severity.ERROR,
    fix="Fix the SRDF at the reported line, or pass the right file with --srdf.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_source.load(doc)
    if srdf is None or srdf.doc.ok:
        return
    problem = srdf.doc.problem
    if problem is None:  # a recovered tree: the file is still not well-formed
        return
    message = problem.message
    if problem.code in ("X001", "X002"):
        message = f"the SRDF is not usable: {message}"
    severity = Severity.WARNING if srdf.soft else None
    if srdf.soft:
        message = f"cannot expand the SRDF {srdf.shown} with xacro: {message}"
    yield Hit(
        None,
        message,
        severity=severity,
        line=problem.line,
        column=problem.column,
        path=problem.path or srdf.shown,
    )
