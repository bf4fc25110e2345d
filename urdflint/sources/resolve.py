"""Where a mesh or ``$(find pkg)`` points: ``package://``, ``file://`` and relative paths, no ROS.

Package folders are found, in order, from explicit package paths (``--package-path
NAME=DIR``, then ``package-paths`` in the configuration), the workspace (every
``package.xml`` below the checked paths and their git root), ``ROS_PACKAGE_PATH``,
``AMENT_PREFIX_PATH`` (``share/NAME``), and a ``package.xml`` search upward from the
URDF (each ancestor folder and its direct sub-folders). With ``root`` set (the HTTP
service), every answer must lie inside ``root`` and nothing outside it is searched.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from urdflint.cache import deps

NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
SCHEME_RE = re.compile(r"^([a-zA-Z][a-zA-Z0-9+.-]*):")
MAX_PACKAGE_XML_BYTES = 1 << 20
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
        self._packages: dict[str, tuple[Path | None, tuple[str, ...]]] = {}

    # -- packages ------------------------------------------------------------------

    def package_dir(self, name: str) -> Path | None:
        return self.find_package(name)[0]

    def find_package(self, name: str) -> tuple[Path | None, tuple[str, ...]]:
        """The folder of package ``name`` and the places looked at, in order."""
        if name not in self._packages:
            self._packages[name] = self._search(name)
        return self._packages[name]

    def _search(self, name: str) -> tuple[Path | None, tuple[str, ...]]:
        tried: list[str] = []
        if name in self.package_paths:
            folder = self.package_paths[name]
            tried.append(f"package path {name}={folder}")
            if folder.is_dir() and self._inside(folder):
                return folder, tuple(tried)
            deps.note_absent(folder)
        if name in self.workspace:
            folder = self.workspace[name]
            tried.append(f"workspace package {name} at {folder}")
            if folder.is_dir() and self._inside(folder):
                return folder, tuple(tried)
        for base in self.ros_paths:
            tried.append(f"ROS_PACKAGE_PATH {base}")
            found = self._below(base, name, depth=3)
            if found is not None:
                return found, tuple(tried)
        for prefix in self.ament:
            folder = prefix / "share" / name
            tried.append(f"AMENT_PREFIX_PATH {folder}")
            if folder.is_dir():
                return folder, tuple(tried)
            deps.note_absent(folder)
        if self.base_dir is not None and self.root is None:
            tried.append(f"package.xml named {name!r} above {self.base_dir}")
            for ancestor in (self.base_dir, *self.base_dir.parents):
                for folder in (ancestor, *_subdirs(ancestor)):
                    if package_name(folder) == name:
                        return folder, tuple(tried)
        return None, tuple(tried)

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
