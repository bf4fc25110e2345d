"""A xacro file is a library of macros or a fragment, not a robot: only document rules ran.

## What it does
Reports, as information, a xacro file that has no `<link>` after expansion (a
file of `xacro:macro` definitions, of `<material>` definitions, of `<gazebo>`
blocks) and a file that cannot be expanded on its own only because it uses
properties, macros or arguments that the file including it defines (urdflint
looks for a file of the same package that includes it). Such files get only
the document-level checks (X); the robot rules (structure, inertia, joints,
Gazebo references) run on the file that includes them, where they are complete.

A `.urdf` file is treated alike when a folder is checked: one that a xacro file of the
folder includes (husky's `empty.urdf` placeholder) is checked through that file, and one
that is not a robot and that nothing includes (a `<gazebo>` snippet, a nameless `<robot>`
with xacro markup, as jackal's `custom_example.urdf`) gets this one note instead of the
robot rules' errors.

## Why is this bad?
It is not a defect: it tells you that this file was not checked as a robot, so
that a clean result is not mistaken for a checked robot. Pre-commit hooks and
`urdflint check folder/` hand every `.xacro` file to urdflint, libraries included.

## How to fix
Nothing to fix. Make sure the robot file that includes the library is checked
too. If the file is meant to be a robot, add its links. To silence the note,
ignore X011 for library files in the configuration (`per-file-ignores`).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity


@rule(
    "X011",
    "xacro-library",
    Severity.INFO,
    requires_robot=False,
    fix="Check the robot file that includes this one; libraries are checked there.",
)
def check(doc: Document) -> Iterator[Hit]:
    problem = doc.problem
    if problem is not None and problem.code == "X011":
        line, column = problem.line, problem.column
        yield Hit(None, problem.message, line=line, column=column, path=problem.path)
    elif doc.library and doc.ok:
        contents = _contents(doc)
        yield Hit(
            doc.robot,
            f"no <link> after expansion{contents}: a xacro library, so only"
            " document-level rules ran on it",
        )


def _contents(doc: Document) -> str:
    counts: dict[str, int] = {}
    for el in children(doc.robot):
        counts[el.tag] = counts.get(el.tag, 0) + 1
    if not counts:
        return " (it only defines macros or properties)"
    listed = ", ".join(f"{n} <{tag}>" for tag, n in sorted(counts.items()))
    return f" (it defines {listed})"
