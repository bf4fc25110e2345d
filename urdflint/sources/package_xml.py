"""ROS package manifests (``package.xml``) and where a description's elements are written.

Serves the portability rules C014, C015 and C017: which package a file lies in
(:func:`enclosing`), its name and the dependencies a binary install pulls in
(:func:`read`), the ``package://`` form of a path inside a package (:func:`package_uri`),
and the file and line that write an element of a document, also through xacro
(:func:`written`), every mesh and texture reference of a document
(:func:`file_references`), and every package name it uses (:func:`package_uses`).

A manifest is parsed with the hardened parser (no entities, no DTD, no network) and
never over 1 MiB; a malformed one is a :class:`Manifest` with ``problem`` set.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING

from lxml import etree

from urdflint.model.document import make_parser
from urdflint.model.structure import q
from urdflint.sources.meshes import FileRef, package_of, references, textures
from urdflint.sources.resolve import MAX_PACKAGE_XML_BYTES, holder

if TYPE_CHECKING:
    from urdflint.model.document import Document

FIND_USE_RE = re.compile(rb"\$\((?:find|find-pkg-share)\s+([^)\s$]+)\)")
COMMENT_RE = re.compile(rb"<!--.*?-->", re.S)

# What a binary install of the package brings along (bloom's Debian "Depends:" is
# package.run_depends + buildtool_export_depends, and catkin_pkg's run_depends is
# exec_depend + build_export_depend; <depend> is all three; format 1 says <run_depend>).
RUNTIME_TAGS = frozenset(
    {"depend", "exec_depend", "run_depend", "build_export_depend", "buildtool_export_depend"}
)


@dataclass(frozen=True, slots=True)
class Manifest:
    """One ``package.xml``: ``problem`` is set when it cannot be read or parsed."""

    folder: Path
    name: str | None
    runtime: frozenset[str]  # packages declared with a tag in RUNTIME_TAGS
    problem: str | None = None

    def provides(self, package: str) -> bool:
        """Whether ``package://package/...`` is fine from this package (itself or a dependency)."""
        return package == self.name or package in self.runtime


@lru_cache(maxsize=1024)
def read(folder: Path) -> Manifest:
    """The manifest in ``folder/package.xml``."""
    path = folder / "package.xml"
    try:
        if path.stat().st_size > MAX_PACKAGE_XML_BYTES:
            return Manifest(folder, None, frozenset(), "package.xml is over 1 MiB")
        data = path.read_bytes()
    except OSError as exc:
        return Manifest(folder, None, frozenset(), f"package.xml cannot be read ({exc.strerror})")
    try:
        root = etree.fromstring(data, make_parser())
    except etree.XMLSyntaxError as exc:
        return Manifest(folder, None, frozenset(), f"package.xml is not well-formed XML ({exc})")
    if root is None or root.tag != "package":
        return Manifest(folder, None, frozenset(), "package.xml has no <package> root")
    name = (root.findtext("name") or "").strip() or None
    runtime = frozenset(
        (child.text or "").strip()
        for child in root
        if isinstance(child.tag, str) and child.tag in RUNTIME_TAGS and (child.text or "").strip()
    )
    return Manifest(folder, name, runtime)


def enclosing(path: Path, stop: Path | None = None) -> Path | None:
    """The nearest folder above ``path`` (a file) holding a ``package.xml``, not above
    ``stop`` when given (the service's root)."""
    return holder(path.parent, stop)


def package_uri(path: Path, stop: Path | None = None) -> str | None:
    """``package://NAME/rel/path`` for a file inside a package with a readable manifest."""
    folder = enclosing(path, stop)
    if folder is None:
        return None
    manifest = read(folder)
    if manifest.name is None:
        return None
    inside = PurePosixPath(*path.relative_to(folder).parts)
    return f"package://{manifest.name}/{inside}"


def installed_package_uri(path: PurePosixPath) -> str | None:
    """``package://NAME/rest`` guessed from an install layout ``.../share/NAME/rest``."""
    parts = path.parts
    for index in range(len(parts) - 2, 0, -1):
        if parts[index] == "share" and index + 2 < len(parts):
            return f"package://{parts[index + 1]}/{'/'.join(parts[index + 2 :])}"
    return None


@dataclass(frozen=True, slots=True)
class Written:
    """Where an attribute of an element is written: the file (when known) and its line."""

    file: Path | None
    text: str  # the source line ('' when unknown)
    expanded: bool  # the document was expanded from xacro


def written(doc: Document, el: etree._Element, attribute: str) -> Written:
    """The file and line that write ``attribute`` of ``el`` (through the xacro source map)."""
    if doc.origin is None:
        file = doc.base_dir / Path(doc.path).name if doc.base_dir is not None else None
        line = el.sourceline or 0
        text = doc.lines[line - 1].decode("utf-8", "replace") if 0 < line <= len(doc.lines) else ""
        return Written(file, text, False)
    origin = doc.origin(el, attribute)
    if origin is None or not origin.exact:
        return Written(None, "", True)
    for source in getattr(doc.origin, "files", ()):
        if source.shown == origin.path:
            lines = source.data.splitlines()
            raw = lines[origin.line - 1] if 0 < origin.line <= len(lines) else b""
            return Written(Path(source.path), raw.decode("utf-8", "replace"), True)
    return Written(None, "", True)


def file_references(doc: Document) -> list[FileRef]:
    """Every mesh (visual and collision) and texture reference, meshes first (listed once per
    document; the list is shared: do not change it)."""
    found = doc.memo.get("package_xml.file_references")
    if found is None:
        found = doc.memo["package_xml.file_references"] = _file_references(doc)
    return found  # type: ignore[no-any-return]


def _file_references(doc: Document) -> list[FileRef]:
    meshes = [
        FileRef(ref.element, ref.uri, f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}")
        for ref in references(doc)
    ]
    return meshes + textures(doc)


@dataclass(frozen=True, slots=True)
class Use:
    """A package name a document uses: in a ``package://`` mesh or texture (``element``),
    or in a xacro ``$(find NAME)`` written at ``line``, ``column`` of ``path`` (``None``:
    the main file)."""

    name: str
    element: etree._Element | None = None
    path: str | None = None
    line: int | None = None
    column: int | None = None


def package_uses(doc: Document) -> list[Use]:
    """Every package name ``doc`` uses, in the order written: the ``$(find NAME)`` of the
    files xacro read (comments left out), then the ``package://`` references."""
    found: list[Use] = []
    for source in getattr(doc.origin, "files", ()):
        data = COMMENT_RE.sub(lambda m: re.sub(rb"[^\n]", b" ", m.group()), source.data)
        path = None if source.shown == doc.path else source.shown
        for match in FIND_USE_RE.finditer(data):
            line = data.count(b"\n", 0, match.start()) + 1
            column = match.start() - (data.rfind(b"\n", 0, match.start()) + 1) + 1
            found.append(Use(match.group(1).decode("utf-8", "replace"), None, path, line, column))
    for ref in file_references(doc):
        name = package_of(ref.uri)
        if name is not None:
            found.append(Use(name, ref.element))
    return found
