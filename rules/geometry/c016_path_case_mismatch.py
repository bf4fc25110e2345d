"""A mesh or texture path matches a file only when letter case is ignored.

## What it does
Resolves every `<mesh filename>` (visual and collision) and `<texture
filename>` like C004 and compares each folder and file name of the path with
the names on disk. When a name differs from the one on disk only in letter
case (`meshes/Base_Link.STL` for `meshes/base_link.stl`, `Meshes/` for
`meshes/`), the reference is reported with the name it should have. This
works on every system: on Linux the file is "missing" (C004's finding, which
then names the near miss), on macOS and Windows the file opens and only this
rule notices.

## Why is this bad?
The default file systems of Windows (NTFS) and macOS (APFS) ignore case, Linux
file systems do not. A model exported from SolidWorks or Onshape on Windows, or
edited on a Mac, loads there and loses those meshes on every Linux machine,
which is where ROS, Gazebo and most CI run: RViz and MoveIt leave the link
undrawn, Gazebo logs "Unable to find file", PyBullet and MuJoCo refuse the
whole model, Drake refuses it ("resolved to '...' which does not exist").
Git on a case-insensitive system cannot even show that a renamed file differs
only in case, so such mistakes survive reviews.

## How to fix
Write the names exactly as they are on disk (`urdflint fix` does it), or rename
the files. On a case-insensitive system, rename in two steps
(`git mv Box.STL tmp && git mv tmp box.stl`) so that git records it.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.sources import package_xml
from urdflint.sources.case import case_variant
from urdflint.sources.meshes import FileRef, resolved


def target(doc: Document, ref: FileRef) -> Path | None:
    """The absolute path ``ref`` leads to, found or not (``None`` when it cannot be said)."""
    answer = resolved(doc, ref.uri)
    if answer.found and answer.path is not None:
        path = answer.path
        twin = path.with_name(path.name.swapcase())
        if twin.name == path.name or not twin.exists():
            return None  # a case-sensitive file system found it: the names match
    elif (answer.problem or "").startswith("no file at") and answer.tried:
        path = Path(answer.tried[-1])
    else:
        return None
    return Path(os.path.abspath(path))


@rule("C016", "path-case-mismatch", Severity.ERROR, fixable="safe")
def check(doc: Document) -> Iterator[Hit]:
    listings: dict[Path, frozenset[str] | None] = {}
    for ref in package_xml.file_references(doc):
        path = target(doc, ref)
        actual = case_variant(path, listings) if path is not None else None
        if path is None or actual is None:
            continue
        pairs = zip(path.parts, actual.parts, strict=True)
        first = next(i for i, (a, b) in enumerate(pairs) if a != b)
        wrong = "/".join(path.parts[first:])
        right = "/".join(actual.parts[first:])
        yield Hit(
            ref.element,
            f"{ref.what} matches {str(actual)!r} only when case is ignored ({wrong!r} is "
            f"{right!r} on disk): it loads on Windows and macOS, not on Linux",
            fix=f"Write {right!r} as it is on disk.",
            attribute="filename",
            repair=_repair(doc, ref, wrong, right),
        )


def _repair(doc: Document, ref: FileRef, wrong: str, right: str) -> Repair | None:
    where = package_xml.written(doc, ref.element, "filename")
    if where.expanded and ref.uri not in where.text:
        return None  # the name is built by xacro: fix it where it is written
    uri = ref.uri.strip()
    if not uri.endswith(wrong):
        return None
    fixed = uri[: len(uri) - len(wrong)] + right
    return Repair("safe", f"write {fixed}", (SetAttribute(ref.element, "filename", fixed),))
