"""The document is not a URDF `<robot>`, or it declares a DOCTYPE or entities.

## What it does
Reports a root element other than `<robot>`, and any `<!DOCTYPE>` or entity
reference. urdflint refuses such documents instead of expanding them, and checks
nothing else in them.

A `<robot xmlns="...">` that only declares a default namespace is a `<robot>`: it
is checked like any other, and this rule reports the declaration as a warning.

## Why is this bad?
Every URDF parser looks for `<robot>` as the root and finds nothing otherwise
(`check_urdf`: "Could not find the 'robot' element in the xml file").
URDF never needs a DTD (`check_urdf` 3.0.1 does not even find the `<robot>`
after an internal DTD subset); entity declarations are how XML bombs and external
file reads (XXE) are smuggled into parsers, so they are never expanded.

A default namespace is harmless for the TinyXML-based consumers, which compare
tag names as written: urdfdom (`check_urdf` 3.0.1), Pinocchio, sdformat 12
(Gazebo), PyBullet, MuJoCo and Drake all load such a robot completely. The
namespace-aware Python parsers do not: yourdfpy and urdf_parser_py load a robot
with no links and no joints ("Unknown tag "{http://www.ros.org}link"" is
urdf_parser_py's only hint), so every Python tool built on them sees an empty
model.

## How to fix
Make `<robot name="...">` the root element. Remove the DOCTYPE and replace
entities by their values (or use xacro properties, which are expanded first).
Remove `xmlns="..."` from `<robot>`: URDF has no namespace.
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
    elif doc.root is not None and doc.default_namespace is not None:
        yield Hit(
            doc.robot,
            f"<robot> declares the default namespace {doc.default_namespace!r}; urdfdom, "
            "sdformat, PyBullet, MuJoCo and Drake ignore it, but yourdfpy and urdf_parser_py "
            "then find no <link> and no <joint>",
            fix='Remove xmlns="..." from <robot>: URDF has no namespace.',
            severity=Severity.WARNING,
            attribute="xmlns",
        )
