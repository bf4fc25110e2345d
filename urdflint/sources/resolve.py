"""Where a mesh or ``$(find pkg)`` points: ``package://``, ``file://`` and relative paths, no ROS.

Package folders are found, in order, from explicit package paths (``--package-path
NAME=DIR``, then ``package-paths`` in the configuration), the package that holds the file
(its nearest ``package.xml``, when that is the name asked for), the workspace (every
``package.xml`` below the checked paths and their git root), ``ROS_PACKAGE_PATH``,
``AMENT_PREFIX_PATH`` (``share/NAME``), and a ``package.xml`` search upward from the
URDF (each ancestor folder and its direct sub-folders). With ``root`` set (the HTTP
service), every answer must lie inside ``root`` and only explicit package paths and the
workspace given are searched.

Where the workspace or the upward search holds several packages of one name, the one
nearest to the file wins (the deepest folder they share), so the answer does not depend on
what else the repository holds; packages as near as the chosen one are its ``ties``
(C017 reports them: the choice between them is arbitrary, and colcon refuses such a
workspace).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from urdflint.cache import deps

NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
SCHEME_RE = re.compile(r"^([a-zA-Z][a-zA-Z0-9+.-]*):")
MAX_PACKAGE_XML_BYTES = 1 << 20
MAX_LEVELS = 12  # folders searched above a file for the package that holds it
# package://mesh.stl: resource_retriever (RViz, robot_state_publisher users) and Gazebo take
# "mesh.stl" as the package name and find no file; PyBullet strips the scheme and reads it
# relative to the URDF.
NO_PACKAGE_PATH = (
    "the package:// URI has a package name but no path inside it (package://PACKAGE/FILE);"
    " ROS and Gazebo cannot resolve it, PyBullet reads it relative to the URDF"
)


@dataclass(frozen=True, slots=True)
class Resolved:
    """The answer for one URI: a file, or why there is none and where we looked."""

    uri: str
    path: Path | None
    tried: tuple[str, ...] = ()
    problem: str | None = None

    @property
    def found(self) -> bool:
        return self.path is not None and self.problem is None


@dataclass(frozen=True, slots=True)
class Lookup:
    """Where package ``name`` was found (``folder`` is ``None`` when it was not), how
    (``how``: one phrase, for ``--show-packages``), the places looked at, and the other
    packages of that name as near to the file as the chosen one (``ties``)."""

    name: str
    folder: Path | None
    tried: tuple[str, ...] = ()
    how: str = ""
    ties: tuple[Path, ...] = ()


def candidates(workspace: Mapping[str, Path], name: str) -> tuple[Path, ...]:
    """Every folder of package ``name`` in ``workspace``: a workspace index
    (:class:`urdflint.sources.workspace.Packages`) lists each package of a name, a plain
    mapping one."""
    listed = getattr(workspace, "candidates", None)
    if listed is not None:
        return tuple(listed(name))
    folder = workspace.get(name)
    return (folder,) if folder is not None else ()


def nearest(folders: Sequence[Path], near: Path | None) -> tuple[Path, tuple[Path, ...]]:
    """The folder of ``folders`` nearest to ``near`` (the deepest folder they share; the
    first listed among equals), and the others as near as it."""
    if near is None:
        return folders[0], tuple(folders[1:])
    here = os.path.abspath(near)
    shared = [_shared(here, os.path.abspath(folder)) for folder in folders]
    best = max(shared)
    index = shared.index(best)
    ties = tuple(f for i, f in enumerate(folders) if shared[i] == best and i != index)
    return folders[index], ties


def _shared(a: str, b: str) -> int:
    try:
        return len(Path(os.path.commonpath([a, b])).parts)
    except ValueError:  # another drive
        return 0


def holder(folder: Path, stop: Path | None = None) -> Path | None:
    """The package that holds ``folder``: the nearest folder at or above it with a
    ``package.xml`` (not above ``stop`` when given)."""
    for level, ancestor in enumerate((folder, *folder.parents)):
        if level >= MAX_LEVELS or (stop is not None and not ancestor.is_relative_to(stop)):
            return None
        try:
            if (ancestor / "package.xml").is_file():
                return ancestor
        except OSError:
            return None
    return None


@lru_cache(maxsize=4096)
def package_name(folder: Path) -> str | None:
    """The ``<name>`` in ``folder/package.xml`` (``None`` when there is no readable one)."""
    candidate = folder / "package.xml"
    try:
        if not candidate.is_file() or candidate.stat().st_size > MAX_PACKAGE_XML_BYTES:
            return None
        match = NAME_RE.search(candidate.read_bytes())
    except OSError:
        return None
    return match.group(1).decode("utf-8", "replace") if match else None


@lru_cache(maxsize=1024)
def _subdirs(folder: Path) -> tuple[Path, ...]:
    try:
        return tuple(
            sorted(p for p in folder.iterdir() if p.is_dir() and not p.name.startswith("."))
        )
    except OSError:
        return ()


class Resolver:
    """Resolves mesh URIs and package names for one document."""

    def __init__(
        self,
        base_dir: Path | None,
        package_paths: Mapping[str, Path] | None = None,
        *,
        root: Path | None = None,
        environ: Mapping[str, str] | None = None,
        workspace: Mapping[str, Path] | None = None,
    ) -> None:
        self.base_dir = base_dir
        self.root = root.resolve() if root is not None else None
        self.package_paths = dict(package_paths or {})
        self.workspace = workspace if workspace is not None else {}  # a lazy Mapping
        env = os.environ if environ is None else environ
        # The environment and upward search are for the command line; a confined
        # resolver (the service) only sees explicit paths inside its root.
        self.ros_paths = (
            []
            if root
            else [Path(p) for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
        )
        self.ament = (
            []
            if root
            else [Path(p) for p in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
        )
        self._packages: dict[str, Lookup] = {}

    # -- packages ------------------------------------------------------------------

    def package_dir(self, name: str) -> Path | None:
        return self.lookup(name).folder

    def find_package(self, name: str) -> tuple[Path | None, tuple[str, ...]]:
        """The folder of package ``name`` and the places looked at, in order."""
        found = self.lookup(name)
        return found.folder, found.tried

    def lookup(self, name: str) -> Lookup:
        """Where package ``name`` is, how it was found, and its ties (see the module doc)."""
        if name not in self._packages:
            self._packages[name] = self._search(name)
        return self._packages[name]

    def _search(self, name: str) -> Lookup:
        tried: list[str] = []
        if name in self.package_paths:
            folder = self.package_paths[name]
            tried.append(f"package path {name}={folder}")
            if folder.is_dir() and self._inside(folder):
                return Lookup(name, folder, tuple(tried), "package path")
            deps.note_absent(folder)
        own = self._own(name)
        if own is not None:
            tried.append(f"the package holding the file, {name} at {own}")
            return Lookup(name, own, tuple(tried), "the package holding the file")
        found = [f for f in candidates(self.workspace, name) if f.is_dir() and self._inside(f)]
        if found:
            folder, ties = nearest(found, self.base_dir)
            tried.append(f"workspace package {name} at {folder}")
            how = "workspace" if len(found) == 1 else f"workspace, nearest of {len(found)}"
            return Lookup(name, folder, tuple(tried), how, ties)
        for base in self.ros_paths:
            tried.append(f"ROS_PACKAGE_PATH {base}")
            below = self._below(base, name, depth=3)
            if below is not None:
                return Lookup(name, below, tuple(tried), f"ROS_PACKAGE_PATH {base}")
        for prefix in self.ament:
            folder = prefix / "share" / name
            tried.append(f"AMENT_PREFIX_PATH {folder}")
            if folder.is_dir():
                return Lookup(name, folder, tuple(tried), f"AMENT_PREFIX_PATH {prefix}")
            deps.note_absent(folder)
        if self.base_dir is not None and self.root is None:
            tried.append(f"package.xml named {name!r} above {self.base_dir}")
            for ancestor in (self.base_dir, *self.base_dir.parents):
                level = [f for f in (ancestor, *_subdirs(ancestor)) if package_name(f) == name]
                if level:
                    how = "a package.xml above the file"
                    return Lookup(name, level[0], tuple(tried), how, tuple(level[1:]))
        return Lookup(name, None, tuple(tried))

    def _own(self, name: str) -> Path | None:
        """The package holding the file, when it is package ``name``: it always wins (on
        the command line; a confined resolver sees only the package paths it is given)."""
        if self.base_dir is None or self.root is not None:
            return None
        folder = holder(self.base_dir.absolute())
        if folder is None or package_name(folder) != name:
            return None
        return folder

    def _below(self, base: Path, name: str, depth: int) -> Path | None:
        if package_name(base) == name:
            return base
        if depth == 0 or package_name(base) is not None:
            return None  # packages do not nest
        for sub in _subdirs(base):
            found = self._below(sub, name, depth - 1)
            if found is not None:
                return found
        return None

    # -- URIs ----------------------------------------------------------------------

    def resolve(self, uri: str) -> Resolved:
        text = uri.strip()
        if not text:
            return Resolved(uri, None, (), "the filename is empty")
        scheme = SCHEME_RE.match(text)
        if scheme and len(scheme.group(1)) > 1:  # one letter: a Windows drive
            kind = scheme.group(1).lower()
            rest = text[scheme.end() :]
            if kind == "package":
                return self._package(uri, rest)
            if kind == "file":
                path = rest[2:] if rest.startswith("//") else rest
                return self._file(uri, Path(path), f"file {path}")
            return Resolved(uri, None, (), f"the {kind}:// scheme is not supported")
        return self._file(uri, Path(text), "")

    def _package(self, uri: str, rest: str) -> Resolved:
        parts = [p for p in rest.split("/") if p]
        if not parts:
            return Resolved(uri, None, (), "the package:// URI names no package")
        name, inside = parts[0], parts[1:]
        if not inside:
            return Resolved(uri, None, (), NO_PACKAGE_PATH)
        folder, tried = self.find_package(name)
        if folder is None:
            return Resolved(uri, None, tried, f"package {name!r} was not found")
        return self._confined(uri, folder.joinpath(*inside), tried)

    def _file(self, uri: str, path: Path, label: str) -> Resolved:
        if not path.is_absolute():
            if self.base_dir is None:
                return Resolved(uri, None, (), "a relative path needs the URDF's folder")
            path = self.base_dir / path
        return self._confined(uri, path, (label or str(path),))

    def _confined(self, uri: str, path: Path, tried: tuple[str, ...]) -> Resolved:
        if not self._inside(path):
            return Resolved(uri, None, tried, "the path leads outside the allowed folder")
        if ".." in Path(os.path.normpath(path)).parts and self.root is not None:
            return Resolved(uri, None, tried, "the path leads outside the allowed folder")
        if not path.is_file():
            deps.note_absent(path)  # a cached result is stale once the file appears
            return Resolved(uri, None, (*tried, str(path)), f"no file at {path}")
        deps.note_file(path)
        return Resolved(uri, path, tried)

    def _inside(self, path: Path) -> bool:
        if self.root is None:
            return True
        try:
            return path.resolve().is_relative_to(self.root)
        except (OSError, RuntimeError):
            return False
