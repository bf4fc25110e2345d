"""Which files a run lints: the paths given, and in folders the robot descriptions.

A folder yields the *entry* files: the ``*.urdf`` and ``*.xacro`` files (``*.urdf.xacro``
included) that no xacro file of the folder includes, and, for xacro, that are robots
themselves: links, joints or macro calls under ``<robot>``, not only definitions.
Macro libraries and fragments, the files only included by others, are checked as part of
the entry files that include them, so a file is never reported twice. An include names
its file literally, through ``$(find pkg)``, or through the default of ``$(optenv VAR
default)`` and of a ``<xacro:arg>`` of the same file (husky's ``$(arg urdf_extras)``,
whose default is ``$(optenv HUSKY_URDF_EXTRAS empty.urdf)``).

A ``*.urdf`` that nobody includes and that is no robot (:func:`fragment`: another root than
``<robot>``, or xacro markup in a nameless ``<robot>``) is a fragment: the run reports it
once (X011) instead of linting it as a broken robot.
"""

from __future__ import annotations

import fnmatch
import functools
import os
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from lxml import etree

from urdflint.model.document import XACRO_NS, make_parser
from urdflint.model.parsing import UNDECLARED_NS, local_tag, parse
from urdflint.model.schema import SPECS
from urdflint.sources.resolve import candidates, nearest

SKIP_DIRS = {"node_modules", "__pycache__", "build", "install", "log"}
MAX_SCAN_BYTES = 2 * 2**20  # a bigger xacro file is linted, not scanned for includes
INCLUDE_RE = re.compile(rb"<[\w.-]*:?include\b[^>]*?\bfilename\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
FIND_RE = re.compile(r"^\$\((?:find|find-pkg-share)\s+([^)\s]+)\)(.*)$")
ARG_RE = re.compile(r"\$\(arg\s+([^)\s]+)\)")
OPTENV_RE = re.compile(r"\$\(optenv\s+[^)\s]+\s+([^)$]*)\)")
XACRO_ARG_RE = re.compile(rb"<[\w.-]*:?arg\b([^>]*)>")
ATTR_RE = re.compile(rb"\b(name|default)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
EXPR_RE = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
DEFINITIONS = frozenset({"macro", "property", "arg", "include"})
SRDF_SUFFIXES = (".srdf.xacro", ".srdf.xml.xacro")
SRDF_TAGS = frozenset(
    {"group", "group_state", "end_effector", "virtual_joint", "passive_joint", "disable_collisions"}
)
CONDITIONS = frozenset({"if", "unless"})
ROOT_TAG_RE = re.compile(r"root element is <([^>]+)>")
NAMED_ROBOT_RE = re.compile(rb"<robot\b[^>]*\bname\s*=\s*[\"'][^\"']")


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
            found = entries(xacros, packages if packages is not None else {}, urdfs)
            files.extend(str(p) for p in sorted(found))
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


def entries(
    xacros: Sequence[Path], packages: Mapping[str, Path], urdfs: Sequence[Path] = ()
) -> list[Path]:
    """The files among ``xacros`` and ``urdfs`` that are robots of their own, or fragments
    nobody includes (see the module doc)."""
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
        if included(os.path.normpath(os.path.abspath(path))):
            continue  # included by another file: checked there
        data = texts[path]
        if data is None or is_robot(data, path.name.lower().endswith(".urdf.xacro")):
            found.append(path)
    return found + [p for p in urdfs if not included(os.path.normpath(os.path.abspath(p)))]


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
    args: dict[str, str] | None = None
    for match in INCLUDE_RE.finditer(data):
        spec = (match.group(1) or match.group(2) or b"").decode("utf-8", "replace").strip()
        if "$(arg" in spec:
            args = _arg_defaults(data) if args is None else args
        spec = _defaults(spec, args or {})
        if not spec:
            continue
        found = FIND_RE.match(spec)
        if found is not None:
            package, rest = found.group(1), found.group(2)
            folders = candidates(packages, package)
            folder = nearest(folders, path.parent)[0] if folders else None
            base = os.path.abspath(folder) if folder is not None else "*" + os.sep + package
            pattern = base + EXPR_RE.sub("*", rest)
        elif spec.startswith("$(") or spec.startswith("${"):
            pattern = "*" + EXPR_RE.sub("*", spec)
        else:
            pattern = os.path.join(os.path.abspath(path.parent), EXPR_RE.sub("*", spec))
        if _specific(pattern):
            patterns.append(os.path.normpath(pattern) if "*" not in pattern[:1] else pattern)
    return patterns


def _defaults(spec: str, args: Mapping[str, str]) -> str:
    """``spec`` as xacro reads it when nothing is set: each ``$(arg NAME)`` replaced by
    the default the file gives it, then each ``$(optenv VAR default)`` by its default."""
    for _ in range(3):  # a default may name another argument
        spec = ARG_RE.sub(lambda m: args.get(m.group(1), m.group(0)), spec)
    return OPTENV_RE.sub(lambda m: m.group(1).strip(), spec).strip()


def _arg_defaults(data: bytes) -> dict[str, str]:
    """``NAME -> default`` of the file's ``<xacro:arg>`` declarations."""
    found: dict[str, str] = {}
    for match in XACRO_ARG_RE.finditer(data):
        attrs = {m.group(1): m.group(2) or m.group(3) or b"" for m in ATTR_RE.finditer(match[1])}
        if b"name" in attrs and b"default" in attrs:
            name = attrs[b"name"].decode("utf-8", "replace")
            found.setdefault(name, attrs[b"default"].decode("utf-8", "replace"))
    return found


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
    """``files`` with each xacro library or fragment, and each ``*.urdf`` fragment, replaced by
    the entry files that include it (directly or through other libraries), found among the
    workspace's packages and the file's own folder tree. A library nobody includes stays as
    given (it gets its X011 note), and so does every robot file."""
    out: list[str] = []
    graph: _IncludeGraph | None = None
    for name in files:
        path = Path(name)
        if name == "-" or not _library(path):
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


def _library(path: Path) -> bool:
    """A xacro file that is not a robot, or a ``*.urdf`` fragment."""
    lower = path.name.lower()
    if lower.endswith(".urdf"):
        return fragment(path) is not None
    data = _read(path) if lower.endswith(".xacro") else None
    return data is not None and not is_robot(data, lower.endswith(".urdf.xacro"))


def fragment(path: Path) -> str | None:
    """Why the ``*.urdf`` file ``path`` is a fragment, not a robot, or ``None`` (a robot, or
    a file that is not well-formed or not URDF at all, whose error is reported): its root
    element is one a ``<robot>`` holds (``<gazebo>``, ``<link>``...) or a xacro element; its
    ``<robot>`` has no name and holds xacro markup or no ``<link>``; or it only defines xacro
    macros and properties. A named robot with xacro markup stays a robot (X008 says it needs
    expanding): real ``.urdf`` exports often keep some (14 of the 36 corpus robots)."""
    if not path.name.lower().endswith(".urdf"):
        return None
    try:
        stat = path.stat()
    except OSError:
        return None
    return _fragment(os.path.abspath(path), stat.st_size, stat.st_mtime_ns)


@functools.lru_cache(maxsize=1 << 16)  # a run asks twice per file (entries, then fragments)
def _fragment(full: str, size: int, mtime: int) -> str | None:
    data = _read(Path(full))
    if data is None or (b"xacro" not in data and NAMED_ROBOT_RE.search(data)):
        return None
    parsed = parse(data)
    root, problem = parsed.root, parsed.problem
    if root is None or parsed.recovered:
        message = problem.message if problem is not None and problem.code == "X002" else ""
        tag = ROOT_TAG_RE.match(message)
        if tag is None or not (tag[1] in SPECS["robot"].children or tag[1].startswith("xacro:")):
            return None  # not a robot's piece (an SDF file): X002 says what it is
        return f"its root element is <{tag[1]}>, a part of a <robot>"
    markup = _xacro_markup(root, data)
    if not root.get("name"):
        if markup is not None:
            return f"its <robot> has no name and uses xacro (<{markup}>)"
        if root.find("link") is None:
            return "its <robot> has no name and no <link>"
    elif markup is not None and not _has_content(root, True):
        return "it only defines xacro macros and properties"
    return None


XACRO_PREFIX_RE = re.compile(rb"""xmlns:xacro\s*=\s*["']([^"']*)["']""")


def _xacro_markup(root: etree._Element, data: bytes) -> str | None:
    """The local name of the first xacro element (by namespace or prefix) below ``root``, in
    document order: lxml's own loop over xacro's namespace, those the ``xacro`` prefix is
    bound to in ``data`` and the parser's for an undeclared ``xacro:`` (a Python loop over
    every element of thousands of files was most of what finding fragments cost)."""
    bound = (m.decode("utf-8", "replace") for m in XACRO_PREFIX_RE.findall(data))
    spaces = {XACRO_NS, f"{UNDECLARED_NS}xacro", *bound}
    found = next(root.iter(*(f"{{{space}}}*" for space in sorted(spaces))), None)
    return local_tag(found) if found is not None else None


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
