"""The MoveIt SRDF of a robot: where it is, parsed once per document, where its elements are.

:func:`load` finds the SRDF of a linted URDF or xacro document, in this order:

1. ``doc.settings.srdf`` (``--srdf FILE``, ``srdf = "path"`` in the configuration);
2. ``<stem>.srdf`` or ``<stem>.srdf.xacro`` beside the file (the stem without ``.urdf``,
   ``.xacro`` or ``.urdf.xacro``);
3. a ``config/`` or ``srdf/`` ``*.srdf`` (or ``*.srdf.xacro``) of the file's ROS package
   (the nearest folder above it with a ``package.xml``) whose ``<robot name>`` is the
   URDF's;
4. a MoveIt config package (its ``.setup_assistant`` names this file as its URDF, by
   package and relative path): the SRDF it names.

The SRDF is parsed as hardened as a URDF (no DTD, no entities, no network) into a
:class:`~urdflint.model.document.Document`, which keeps its source positions; a
``.srdf.xacro`` is expanded with the project's xacro machinery first and its source map
gives the positions. :func:`disabled_pairs` is the SRDF's ``disable_collisions`` pairs.
"""

from __future__ import annotations

import contextlib
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any
from weakref import WeakKeyDictionary

from lxml import etree

from urdflint.cache import deps
from urdflint.model.document import MAX_BYTES, Document, XmlProblem, children

if TYPE_CHECKING:
    from urdflint.engine.config import Settings
    from urdflint.engine.context import Context

__all__ = ["Srdf", "disabled_pairs", "find", "load", "name_of"]

URDF_SUFFIXES = (".urdf.xacro", ".xacro", ".urdf")
SRDF_SUFFIXES = (".srdf", ".srdf.xacro")
SRDF_FOLDERS = ("config", "srdf")
SETUP_ASSISTANT = ".setup_assistant"
XACRO_ARG_RE = re.compile(r"<xacro:arg\b[^>]*>")
ATTR_RE = re.compile(r"""(\w+)\s*=\s*["']([^"']*)["']""")
MAX_SETUP_BYTES = 1 << 20
MAX_PACKAGE_DEPTH = 8  # folders above the file searched for its package.xml
ROBOT_NAME_RE = re.compile(rb"<robot\b[^>]*?\bname\s*=\s*(?:\"([^\"]*)\"|'([^']*)')", re.S)


@dataclass
class Srdf:
    """One parsed SRDF: ``doc.root`` is its ``<robot>``, ``doc.problem`` why it is unusable.

    ``how`` says how it was found (``--srdf``, ``beside``, ``package``, ``setup-assistant``);
    ``expanded`` is true for a ``.srdf.xacro``; ``soft`` marks a problem that is urdflint's
    (a xacro expansion it could not do), not necessarily the file's.
    """

    path: Path
    shown: str
    how: str
    doc: Document
    expanded: bool = False
    soft: bool = False

    @property
    def root(self) -> etree._Element | None:
        return self.doc.root if self.doc.ok else None

    def elements(self, tag: str) -> list[etree._Element]:
        """The ``<robot>``'s direct children named ``tag`` (none when unusable)."""
        return children(self.root, tag) if self.root is not None else []

    def position(self, el: etree._Element, attribute: str | None = None) -> tuple[str, int, int]:
        """File, line and column where ``el`` (or its ``attribute``) is written."""
        if self.doc.origin is not None:
            origin = self.doc.origin(el, attribute)
            if origin is not None:
                return origin.path, origin.line, origin.column
        found = self.doc.attribute_at(el, attribute) if attribute else None
        line, column = found if found is not None else self.doc.start_of(el)
        return self.shown, line, column


def _is_file(path: Path) -> bool:
    """Whether the SRDF candidate exists; one that does not is an input of a cached result
    (an SRDF written later beside the URDF makes it stale)."""
    if path.is_file():
        return True
    deps.note_absent(path)
    return False


def name_of(el: etree._Element, attribute: str = "name") -> str | None:
    """An attribute as srdfdom reads it: whitespace trimmed (``None`` when absent)."""
    value = el.get(attribute)
    return value.strip() if value is not None else None


_CACHE: WeakKeyDictionary[Document, Srdf | None] = WeakKeyDictionary()


def load(doc: Document) -> Srdf | None:
    """The document's SRDF, parsed once (``None`` when there is none)."""
    if doc in _CACHE:
        return _CACHE[doc]
    found = find(doc)
    srdf = _read(doc, *found) if found is not None else None
    _CACHE[doc] = srdf
    return srdf


def disabled_pairs(doc: Document) -> set[frozenset[str]]:
    """The SRDF's ``<disable_collisions link1 link2>`` pairs (empty without an SRDF)."""
    srdf = load(doc) if doc.ok else None
    pairs: set[frozenset[str]] = set()
    for el in srdf.elements("disable_collisions") if srdf is not None else []:
        first, second = name_of(el, "link1"), name_of(el, "link2")
        if first and second:
            pairs.add(frozenset((first, second)))
    return pairs


# -- discovery -------------------------------------------------------------------------------


def find(doc: Document) -> tuple[Path, str, str] | None:
    """``(file, shown path, how)`` of the document's SRDF, by the order above."""
    settings = doc.settings
    if settings.srdf is not None:
        return settings.srdf, str(settings.srdf), "--srdf"
    real = _real_path(doc)
    if real is None or not _allowed(doc, real):
        return None
    for candidate in _beside(real):
        if _allowed(doc, candidate):
            return candidate, _shown(doc, real, candidate), "beside"
    robot = doc.robot.get("name") if doc.root is not None else None
    package = _package_of(doc, real)
    if package is not None and robot:
        for candidate in _package_srdfs(package):
            if _allowed(doc, candidate) and _robot_name(candidate, doc) == robot.strip():
                return candidate, _shown(doc, real, candidate), "package"
    paired = _setup_assistant(doc, real, package)
    if paired is not None:
        return paired, _shown(doc, real, paired), "setup-assistant"
    return None


def _real_path(doc: Document) -> Path | None:
    shown = Path(doc.path)
    if doc.base_dir is not None:
        return doc.base_dir / shown.name
    return shown if _is_file(shown) else None


def _allowed(doc: Document, path: Path) -> bool:
    """Inside the confinement root (the HTTP service), when there is one."""
    root = doc.context.root
    if root is None:
        return True
    try:
        return path.resolve().is_relative_to(root.resolve())
    except (OSError, RuntimeError):
        return False


def _stem(path: Path) -> str:
    name = path.name
    for suffix in URDF_SUFFIXES:
        if name.lower().endswith(suffix):
            return name[: -len(suffix)]
    return path.stem


def _beside(real: Path) -> list[Path]:
    stem = _stem(real)
    return [p for s in SRDF_SUFFIXES if _is_file(p := real.with_name(stem + s))]


def _shown(doc: Document, real: Path, target: Path) -> str:
    """``target`` as seen from the linted file's shown path (as xacro includes are shown)."""
    try:
        rel = os.path.relpath(target, real.parent)
    except ValueError:  # another drive
        return str(target)
    return os.path.normpath(os.path.join(os.path.dirname(doc.path), rel))


def _package_of(doc: Document, real: Path) -> Path | None:
    folder = real.parent
    for _ in range(MAX_PACKAGE_DEPTH):
        if not _allowed(doc, folder):
            return None
        if (folder / "package.xml").is_file():
            return folder
        if folder.parent == folder:
            return None
        folder = folder.parent
    return None


def _package_srdfs(package: Path) -> list[Path]:
    found: list[Path] = []
    for sub in SRDF_FOLDERS:
        folder = package / sub
        if folder.is_dir():
            found += sorted(p for p in folder.iterdir() if p.name.endswith(SRDF_SUFFIXES))
    return [p for p in found if p.is_file()]


def _robot_name(path: Path, doc: Document) -> str | None:
    """The ``<robot name>`` of an SRDF candidate (a ``.srdf.xacro`` expanded when needed)."""
    try:
        with path.open("rb") as handle:
            head = handle.read(1 << 16)
    except OSError:
        return None
    match = ROBOT_NAME_RE.search(head)
    if match is None:
        return None
    raw = (match.group(1) or match.group(2) or b"").decode("utf-8", "replace").strip()
    if "$" not in raw or not path.name.endswith(".xacro"):
        return raw
    expanded = _expand(path, str(path), doc.settings, doc.context)
    if isinstance(expanded, XmlProblem):
        return None
    match = ROBOT_NAME_RE.search(expanded[0])
    return (match.group(1) or match.group(2) or b"").decode().strip() if match else None


def _setup_assistant(doc: Document, real: Path, package: Path | None) -> Path | None:
    """The SRDF of a MoveIt config package whose ``.setup_assistant`` names this URDF."""
    if package is None:
        return None  # a .setup_assistant names its URDF by package: this file is in none
    folders = [package, *(p for p in _subdirs(package.parent) if p != package)]
    with contextlib.suppress(OSError):
        folders += list(doc.context.workspace.values())
    target = _resolved(real)
    for folder in dict.fromkeys(folders):
        config = _setup_config(folder) if _allowed(doc, folder) else None
        if config is None:
            continue
        urdf_package, urdf_path, srdf_path, xacro_args = config
        base = doc.resolver.package_dir(urdf_package)
        if (
            base is not None
            and _resolved(base / urdf_path) == target
            and _same_expansion(doc, real, xacro_args)
        ):
            candidate = folder / srdf_path
            if _is_file(candidate) and _allowed(doc, candidate):
                return candidate
    return None


def _subdirs(folder: Path) -> list[Path]:
    try:
        return sorted(p for p in folder.iterdir() if p.is_dir() and not p.name.startswith("."))
    except OSError:
        return []


def _resolved(path: Path) -> Path | None:
    try:
        return path.resolve()
    except (OSError, RuntimeError):
        return None


def _same_expansion(doc: Document, real: Path, wanted: dict[str, str]) -> bool:
    """Whether this run expands the URDF with the xacro arguments a ``.setup_assistant``
    built its SRDF for (``xacro_args: gripper:=robotiq_2f_85 dof:=6``): each one given
    with that value, or not given and declared with it as default. Kinova's kortex has a
    MoveIt config per arm variant of one ``gen3.xacro``: each SRDF fits one variant."""
    if not wanted:
        return True
    given = doc.settings.xacro_args_for(str(real)) if doc.settings is not None else {}
    defaults: dict[str, str] = {}
    if real.name.endswith(".xacro"):
        with contextlib.suppress(OSError, UnicodeDecodeError):
            text = real.read_text(encoding="utf-8")
            for tag in XACRO_ARG_RE.finditer(text):
                attrs = dict(ATTR_RE.findall(tag.group(0)))
                if "name" in attrs:
                    defaults.setdefault(attrs["name"], attrs.get("default", ""))
    return all(given.get(name, defaults.get(name)) == value for name, value in wanted.items())


def _xacro_args(value: Any) -> dict[str, str]:
    """``{"dof": "6"}`` from ``xacro_args: dof:=6 gripper:=robotiq_2f_85``."""
    found: dict[str, str] = {}
    if isinstance(value, str):
        for word in value.split():
            name, sep, arg = word.partition(":=")
            if sep and name:
                found[name] = arg.strip("'\"")
    return found


def _setup_config(folder: Path) -> tuple[str, str, str, dict[str, str]] | None:
    """``(URDF package, URDF relative path, SRDF relative path, xacro args)`` of a
    ``.setup_assistant``."""
    path = folder / SETUP_ASSISTANT
    try:
        if not path.is_file() or path.stat().st_size > MAX_SETUP_BYTES:
            return None
        import yaml

        data: Any = yaml.safe_load(path.read_text(encoding="utf-8"))
    except Exception:  # unreadable or malformed YAML: not ours to report, no pairing
        return None
    config = data.get("moveit_setup_assistant_config") if isinstance(data, dict) else None
    if not isinstance(config, dict):
        return None
    urdf = config.get("URDF") or config.get("urdf") or {}
    srdf = config.get("SRDF") or config.get("srdf") or {}
    if not isinstance(urdf, dict) or not isinstance(srdf, dict):
        return None
    values = (urdf.get("package"), urdf.get("relative_path"), srdf.get("relative_path"))
    if not all(isinstance(v, str) and v.strip() for v in values):
        return None
    args = _xacro_args(urdf.get("xacro_args"))
    return values[0].strip(), values[1].strip(), values[2].strip(), args  # type: ignore[union-attr]


# -- reading -----------------------------------------------------------------------------------


def _read(doc: Document, path: Path, shown: str, how: str) -> Srdf:
    common: dict[str, Any] = {"settings": doc.settings, "context": doc.context}
    if not path.is_file():
        problem = XmlProblem("M001", f"the SRDF file {shown} does not exist")
        return Srdf(path, shown, how, Document(shown, b"", problem=problem, **common))
    if path.name.endswith(".xacro"):
        expanded = _expand(path, shown, doc.settings, doc.context)
        if isinstance(expanded, XmlProblem):
            sub = Document(shown, b"", problem=expanded, **common)
            return Srdf(path, shown, how, sub, expanded=True, soft=True)
        source, origin = expanded
        sub = Document(shown, source, origin=origin, base_dir=path.parent, **common)
        return Srdf(path, shown, how, sub, expanded=True)
    try:
        size = path.stat().st_size
        source = path.read_bytes() if size <= MAX_BYTES else b""
    except OSError as exc:
        problem = XmlProblem("M001", f"cannot read the SRDF file {shown}: {exc.strerror}")
        return Srdf(path, shown, how, Document(shown, b"", problem=problem, **common))
    if size > MAX_BYTES:
        problem = XmlProblem("M001", f"the SRDF file {shown} is over the 64 MiB limit")
        return Srdf(path, shown, how, Document(shown, b"", problem=problem, **common))
    return Srdf(path, shown, how, Document(shown, source, base_dir=path.parent, **common))


def _expand(
    path: Path, shown: str, settings: Settings, context: Context
) -> tuple[bytes, Any] | XmlProblem:
    """A ``.srdf.xacro`` expanded by xacro, with the source map of the result."""
    from urdflint.sources.xacro.expansion import Expansion
    from urdflint.sources.xacro.sourcemap import SourceMap

    expansion = Expansion(path, shown, settings, context)
    outcome = expansion.run()
    if isinstance(outcome, XmlProblem):
        return outcome
    return outcome, SourceMap(expansion.tracker.files, expansion.dom, shown, outcome)
