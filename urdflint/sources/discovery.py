"""Which files a run lints: the paths given, and in folders the robot descriptions.

A folder yields every ``*.urdf`` and the *entry* xacro files: the ``*.xacro`` files
(``*.urdf.xacro`` included) that no other xacro file of the folder includes, and that are
robots themselves: links, joints or macro calls under ``<robot>``, not only definitions.
Macro libraries and fragments, the files only included by others, are checked as part of
the entry files that include them, so a file is never reported twice.
"""

from __future__ import annotations

import fnmatch
import os
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from lxml import etree

from urdflint.model.document import XACRO_NS, make_parser

SKIP_DIRS = {"node_modules", "__pycache__", "build", "install", "log"}
MAX_SCAN_BYTES = 2 * 2**20  # a bigger xacro file is linted, not scanned for includes
INCLUDE_RE = re.compile(rb"<[\w.-]*:?include\b[^>]*?\bfilename\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
FIND_RE = re.compile(r"^\$\((?:find|find-pkg-share)\s+([^)\s]+)\)(.*)$")
EXPR_RE = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
DEFINITIONS = frozenset({"macro", "property", "arg", "include"})
SRDF_SUFFIXES = (".srdf.xacro", ".srdf.xml.xacro")
SRDF_TAGS = frozenset(
    {"group", "group_state", "end_effector", "virtual_joint", "passive_joint", "disable_collisions"}
)
CONDITIONS = frozenset({"if", "unless"})


def collect(
    paths: Sequence[str], packages: Mapping[str, Path] | None = None
) -> tuple[list[str], list[str]]:
    """Files to lint (``-`` kept as is) and one error message per unusable path."""
    files: list[str] = []
    errors: list[str] = []
    for raw in paths:
        if raw == "-":
            files.append(raw)
            continue
        path = Path(raw)
        if path.is_dir():
            urdfs, xacros = _below(path)
            found = entries(xacros, packages if packages is not None else {}) if xacros else []
            files.extend(str(p) for p in sorted(urdfs + found))
        elif path.is_file():
            files.append(raw)
        elif path.exists():
            errors.append(f"{raw}: not a regular file")
        else:
            errors.append(f"{raw}: no such file or directory")
    return list(dict.fromkeys(files)), errors


def _below(folder: Path) -> tuple[list[Path], list[Path]]:
    urdfs: list[Path] = []
    xacros: list[Path] = []
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d not in SKIP_DIRS)
        for name in filenames:
            lower = name.lower()
            if lower.endswith(".urdf"):
                urdfs.append(Path(dirpath) / name)
            elif lower.endswith(".xacro") and not lower.endswith(SRDF_SUFFIXES):
                xacros.append(Path(dirpath) / name)  # an SRDF is read beside its URDF
    return urdfs, xacros


def entries(xacros: Sequence[Path], packages: Mapping[str, Path]) -> list[Path]:
    """The xacro files among ``xacros`` that are robots of their own (see the module doc)."""
    patterns: list[str] = []
    texts: dict[Path, bytes | None] = {}
    for path in xacros:
        data = _read(path)
        texts[path] = data
        if data is not None:
            patterns.extend(_include_patterns(path, data, packages))
    included = _matcher(patterns)
    found: list[Path] = []
    for path in xacros:
        full = os.path.normpath(os.path.abspath(path))
        if included(full):
            continue  # included by another file: checked there
        data = texts[path]
        if data is None or is_robot(data, path.name.lower().endswith(".urdf.xacro")):
            found.append(path)
    return found


def _matcher(patterns: list[str]) -> Callable[[str], bool]:
    """Whether a path matches one of the glob ``patterns`` (as ``fnmatchcase``): literal
    names by a set, the others by one regular expression (one ``fnmatch`` per file and
    pattern cost 0.2 s on a workspace of 200 files)."""
    literal = {p for p in patterns if not any(c in p for c in "*?[")}
    globs = sorted({p for p in patterns if p not in literal})
    regex = re.compile("|".join(f"(?:{fnmatch.translate(p)})" for p in globs)) if globs else None
    return lambda full: full in literal or (regex is not None and regex.match(full) is not None)


def _read(path: Path) -> bytes | None:
    try:
        if path.stat().st_size > MAX_SCAN_BYTES:
            return None
        return path.read_bytes()
    except OSError:
        return None


def _include_patterns(path: Path, data: bytes, packages: Mapping[str, Path]) -> list[str]:
    """What the file's ``<xacro:include>`` tags can name, as absolute glob patterns."""
    patterns: list[str] = []
    for match in INCLUDE_RE.finditer(data):
        spec = (match.group(1) or match.group(2) or b"").decode("utf-8", "replace").strip()
        if not spec:
            continue
        found = FIND_RE.match(spec)
        if found is not None:
            package, rest = found.group(1), found.group(2)
            folder = packages.get(package)
            base = os.path.abspath(folder) if folder is not None else "*" + os.sep + package
            pattern = base + EXPR_RE.sub("*", rest)
        elif spec.startswith("$(") or spec.startswith("${"):
            pattern = "*" + EXPR_RE.sub("*", spec)
        else:
            pattern = os.path.join(os.path.abspath(path.parent), EXPR_RE.sub("*", spec))
        if _specific(pattern):
            patterns.append(os.path.normpath(pattern) if "*" not in pattern[:1] else pattern)
    return patterns


def _specific(pattern: str) -> bool:
    """The pattern names a file, not any file: its base name keeps a literal stem
    (``${prefix}_arm.xacro`` does, ``${file}`` and ``${name}.urdf.xacro`` do not)."""
    stem = os.path.basename(pattern).replace("*", "")
    for suffix in (".xacro", ".urdf", ".gazebo", ".trans", ".xml"):
        stem = stem.removesuffix(suffix)
    return len(stem.strip("._-")) >= 2


def is_robot(data: bytes, includes: bool = False) -> bool:
    """Whether a xacro text writes robot content: links, joints or macro calls, not only
    definitions; with ``includes`` (a ``*.urdf.xacro`` file that defines no macro), includes
    count as content, since a robot file may be nothing but includes. Unreadable XML counts
    as a robot, so that its error is reported."""
    try:
        root = etree.fromstring(data, make_parser())
    except (etree.XMLSyntaxError, ValueError):
        return True
    if includes and any(etree.QName(el).localname == "macro" for el in root.iter("{*}macro")):
        includes = False
    if any(isinstance(el.tag, str) and etree.QName(el).localname in SRDF_TAGS for el in root):
        return False  # a MoveIt SRDF written in xacro: the M rules read it with its URDF
    return _has_content(root, includes)


def _has_content(element: etree._Element, includes: bool) -> bool:
    for child in element:
        if not isinstance(child.tag, str):
            continue
        namespace, _, local = (
            child.tag[1:].partition("}") if child.tag[:1] == "{" else ("", "", child.tag)
        )
        if namespace == XACRO_NS or (child.prefix == "xacro"):
            if local == "include" and includes:
                return True
            if local in DEFINITIONS:
                continue
            if local in CONDITIONS:
                if _has_content(child, includes):
                    return True
                continue
            return True  # a macro call, xacro:element, xacro:insert_block
        if local in ("link", "joint"):
            return True
    return False


MAX_GRAPH_FILES = 5000  # xacro files scanned to find who includes a library


def as_entries(files: Sequence[str], packages: Mapping[str, Path]) -> list[str]:
    """``files`` with each xacro library or fragment replaced by the entry files that include
    it (directly or through other libraries), found among the workspace's packages and the
    file's own folder tree. A library nobody includes stays as given (it gets its X011 note),
    and so does every robot file."""
    out: list[str] = []
    graph: _IncludeGraph | None = None
    for name in files:
        path = Path(name)
        data = _read(path) if name != "-" and name.lower().endswith(".xacro") else None
        if data is None or is_robot(data, name.lower().endswith(".urdf.xacro")):
            out.append(name)
            continue
        graph = graph or _IncludeGraph(packages, [path.parent])
        graph.add_tree(path.parent)
        found = graph.entries_of(path)
        if found:
            out.extend(_shown(p) for p in found)
        else:
            out.append(name)
    return list(dict.fromkeys(out))


def _shown(path: Path) -> str:
    try:
        return os.path.relpath(path)
    except ValueError:  # another drive
        return str(path)


class _IncludeGraph:
    """Who includes whom among the xacro files of the workspace (bounded scan)."""

    def __init__(self, packages: Mapping[str, Path], extra: Sequence[Path]) -> None:
        self.packages = packages
        self.files: dict[Path, list[str]] = {}
        self.scanned: set[Path] = set()
        for folder in [*packages.values(), *extra]:
            self.add_tree(folder)

    def add_tree(self, folder: Path) -> None:
        folder = folder.resolve()
        if folder in self.scanned:
            return
        self.scanned.add(folder)
        for path in _below(folder)[1]:
            if len(self.files) >= MAX_GRAPH_FILES:
                return
            full = path.resolve()
            if full not in self.files:
                data = _read(full)
                self.files[full] = _include_patterns(full, data, self.packages) if data else []

    def includers(self, target: Path) -> list[Path]:
        full = os.path.normpath(str(target.resolve()))
        return [
            path
            for path, patterns in self.files.items()
            if path != target.resolve() and any(fnmatch.fnmatchcase(full, p) for p in patterns)
        ]

    def entries_of(self, target: Path) -> list[Path]:
        """The files at the top of the include chains that reach ``target``."""
        found: list[Path] = []
        seen = {target.resolve()}
        queue = [target.resolve()]
        while queue:
            current = queue.pop(0)
            parents = [p for p in self.includers(current) if p not in seen]
            if not parents and current != target.resolve():
                found.append(current)
            for parent in parents:
                seen.add(parent)
                queue.append(parent)
        return sorted(found)
