"""A mesh or texture is named by an absolute path or a `file://` URI: it exists on one machine.

## What it does
Reports every `<mesh filename>` of a `<visual>` or `<collision>` and every
`<texture filename>` that is an absolute path (`/home/me/ws/meshes/arm.stl`,
`C:\\robots\\arm.stl`) or a `file://` URI (`file:///home/me/...`, and the
broken relative form `file://meshes/arm.stl`). It does not matter whether the
file exists where urdflint runs (C004 says that): the path is tied to one
folder layout.

When the path lies inside a ROS package (a folder with a `package.xml` above
the file), the fix names the `package://NAME/...` equivalent; when it follows
an install layout (`.../share/NAME/...`), the fix names the package guessed
from it. In a document expanded from xacro only paths written literally are
reported: `file://$(find pkg)/meshes/...` is resolved on the machine that
expands the xacro, which is the pattern several ROS 2 packages use for Gazebo.

## Why is this bad?
The model works on the author's machine and nowhere else: on a colleague's
computer, in CI, in a Docker image or after `apt install`, the folder does not
exist. ROS's resource_retriever (RViz, MoveIt) hands `file://` URIs to libcurl,
which reads the local disk of the machine that renders, so a robot description
published by a robot and shown in RViz on a laptop loses its meshes (the reason
Universal_Robots_ROS2_Description and create3_sim moved from `file://` to
`package://`). Gazebo, Drake and Pinocchio open the path as written. MuJoCo
(4.0) does not understand `file://` at all: it fails with "Error opening file
'file:/home/...'" even on the author's machine. The relative form
`file://meshes/x.stl` is not a valid file URI (`meshes` is read as a host
name): MuJoCo refuses it and the others read it relative to a folder of their
choosing.

## How to fix
Ship the meshes in a package and write `package://NAME/meshes/arm.stl`, or
write a path relative to the URDF (`meshes/arm.stl`) when the file is not used
through ROS. `urdflint fix --unsafe-fixes` rewrites a path that lies inside a
package found by this run into its `package://` form.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path, PurePosixPath

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.sources import package_xml
from urdflint.sources.meshes import FileRef, resolved
from urdflint.sources.resolve import SCHEME_RE

WINDOWS_RE = re.compile(r"^(?:[A-Za-z]:[\\/]|\\\\)")
FIX = "Write package://PACKAGE/path for a file a ROS package ships, or a path relative to the URDF."


def local_path(uri: str) -> tuple[str, str] | None:
    """``(kind, path)`` for a ``file://`` URI or an absolute path, else ``None``.

    ``kind`` is ``"file"`` (a ``file://`` URI with an absolute path), ``"file-relative"``
    (``file://meshes/a.stl``) or ``"absolute"`` (no scheme)."""
    text = uri.strip()
    scheme = SCHEME_RE.match(text)
    if scheme and len(scheme.group(1)) > 1:  # one letter: a Windows drive
        if scheme.group(1).lower() != "file":
            return None
        rest = text[scheme.end() :]
        path = rest[2:] if rest.startswith("//") else rest
        return ("file" if path.startswith("/") else "file-relative", path)
    if text.startswith("/") or WINDOWS_RE.match(text):
        return ("absolute", text)
    return None


@rule(
    "C014",
    "non-portable-mesh-path",
    Severity.WARNING,
    fix=FIX,
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
    for ref in package_xml.file_references(doc):
        found = local_path(ref.uri)
        if found is None:
            continue
        where = package_xml.written(doc, ref.element, "filename")
        if where.expanded and ref.uri not in where.text:
            continue  # built by $(find ...) or an argument: resolved where xacro runs
        kind, path = found
        yield _hit(doc, ref, kind, path, repairable=not where.expanded)


def _hit(doc: Document, ref: FileRef, kind: str, path: str, *, repairable: bool) -> Hit:
    if kind == "file-relative":
        message = (
            f"{ref.what} is a file:// URI with a relative path: MuJoCo cannot open it, and "
            "other consumers read it relative to a folder of their choosing"
        )
    elif kind == "file":
        message = (
            f"{ref.what} is a file:// URI: it exists on one machine only, and MuJoCo "
            "cannot open file:// URIs"
        )
    else:
        message = f"{ref.what} is an absolute path: it exists on one machine only"
    suggestion, repair = _suggestion(doc, ref.element, path, kind, repairable)
    return Hit(ref.element, message, fix=suggestion, attribute="filename", repair=repair)


def _suggestion(
    doc: Document, el: etree._Element, path: str, kind: str, repairable: bool
) -> tuple[str | None, Repair | None]:
    """The fix naming the ``package://`` form, and the repair when it leads to the same file."""
    if kind == "file-relative" or WINDOWS_RE.match(path):
        return None, None
    uri = package_xml.package_uri(Path(path), doc.resolver.root) if Path(path).is_file() else None
    if uri is None:
        guess = package_xml.installed_package_uri(PurePosixPath(path))
        if guess is None:
            return None, None
        return f"Write {guess!r} (the path is inside that package's install folder).", None
    repair = None
    answer = resolved(doc, uri)
    same = (
        answer.found and answer.path is not None and answer.path.resolve() == Path(path).resolve()
    )
    if repairable and same:
        repair = Repair("unsafe", f"write {uri}", (SetAttribute(el, "filename", uri),))
    return f"Write {uri!r}: the file is inside that package.", repair
