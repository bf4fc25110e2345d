"""Two packages of one name are equally near the file, so which one it uses is arbitrary.

## What it does
Looks up every package the file uses (`package://NAME/...` meshes and textures,
xacro `$(find NAME)`) as urdflint resolves it: the package that holds the file
wins, then the package of that name nearest to the file among the workspace's
packages (every `package.xml` below the checked paths and their git root) or,
without a workspace, among the folders above the file. When another package of
the same name is just as near (the deepest folder they share is the same),
reports the name once per file, at its first use, naming every folder.

A same-named package farther away (the ROS 1 `ur_description` beside the ROS 2
one, while the file is in one of them) is not reported: the nearer one is
meant, and urdflint uses it wherever the repository sits.

## Why is this bad?
colcon ("Duplicate package names not supported") and catkin ("Multiple packages
found with the same name") refuse to build such a workspace, and tools that
search a path (`ROS_PACKAGE_PATH`, `rospack`, `ament_index`) take the first one
they meet, so the meshes and includes the file gets depend on the order of
folders on one machine. urdflint picks the first one found by its walk, so its
findings (C004 for a mesh the other copy lacks, X010 for an include) may be about
the wrong package.

## How to fix
Keep one of the packages in the workspace: delete or move the other, or put an
empty `COLCON_IGNORE` file in its folder (colcon, catkin and urdflint skip it).
To lint against a chosen one, pass `--package-path NAME=DIR` (or set
`package-paths` in the configuration). `urdflint check --show-packages` lists
which folder every package name resolves to, and why.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.sources import package_xml


@rule("C017", "duplicate-package", Severity.WARNING)
def check(doc: Document) -> Iterator[Hit]:
    done: set[str] = set()
    for use in package_xml.package_uses(doc):
        if use.name in done:
            continue
        done.add(use.name)
        found = doc.resolver.lookup(use.name)
        if found.folder is None or not found.ties:
            continue
        others = ", ".join(_shown(f) for f in found.ties)
        yield Hit(
            use.element,
            f"package {use.name!r} is at {len(found.ties) + 1} places as near to this file: "
            f"{_shown(found.folder)} (used) and {others}; colcon and catkin refuse a "
            "workspace with two packages of one name",
            fix=f"Keep one package {use.name!r} (a COLCON_IGNORE file hides the other), or "
            f"choose one with --package-path {use.name}=DIR.",
            line=use.line,
            column=use.column,
            path=use.path,
            attribute="filename" if use.element is not None else None,
        )


def _shown(folder: Path) -> str:
    """``folder`` relative to the working folder when it is below it."""
    full = os.path.abspath(folder)
    here = os.getcwd()
    return os.path.relpath(full, here) if full.startswith(here + os.sep) else full
