"""ROS packages found without flags: every ``package.xml`` below the paths being checked and
below their git root, as ``colcon`` and ``catkin`` would find them in a workspace.

A folder with a ``package.xml`` is a package (packages do not nest, so the walk does not
descend into it); folders marked ``COLCON_IGNORE``, ``CATKIN_IGNORE`` or ``AMENT_IGNORE``,
hidden folders and build outputs are skipped, as the ROS build tools skip them. Every
package of a name is kept (a repository may hold a ROS 1 and a ROS 2 ``ur_description``):
the resolver takes the one nearest to the file that asks (:func:`resolve.nearest`).
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

from urdflint.sources.resolve import package_name

IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
SKIP_DIRS = frozenset({"node_modules", "__pycache__", "build", "install", "log", "devel"})
MAX_FOLDERS = 20_000  # a walk stops here (a home folder is not a workspace)


def git_root(path: Path) -> Path | None:
    """The top of the git work tree holding ``path`` (a ``.git`` folder or file), if any."""
    start = path if path.is_dir() else path.parent
    for folder in (start, *start.parents):
        if (folder / ".git").exists():
            return folder
    return None


def roots_for(paths: Iterable[Path]) -> list[Path]:
    """Where to look for packages: each folder given, the folder of each file, the git root
    above them, and, outside git, the folder holding the file's own package (``src/``)."""
    found: list[Path] = []
    for raw in paths:
        path = raw.resolve()
        if not path.exists():
            continue
        folder = path if path.is_dir() else path.parent
        found.append(folder)
        top = git_root(folder)
        if top is not None:
            found.append(top)
            continue
        for ancestor in (folder, *folder.parents):
            if (ancestor / "package.xml").is_file():
                found.append(ancestor.parent)
                break
    return list(dict.fromkeys(found))


class Found(dict[str, Path]):
    """Package name -> the first package of that name the walk found; ``every`` lists every
    package, several of one name included (the resolver takes the one nearest to a file)."""

    def __init__(self, every: list[tuple[str, Path]]) -> None:
        super().__init__()
        self.every = every
        for name, folder in every:
            self.setdefault(name, folder)

    def candidates(self, name: str) -> tuple[Path, ...]:
        return tuple(folder for found, folder in self.every if found == name)


def packages_below(roots: Iterable[Path]) -> Found:
    """Every package below ``roots`` (see :class:`Found`)."""
    return Found(listing(roots))


def listing(roots: Iterable[Path]) -> list[tuple[str, Path]]:
    """``(name, folder)`` of every package below ``roots``, in the order of the walk (the
    roots in turn, each depth first by name); a folder reached twice (a symbolic link)
    is listed once."""
    found: list[tuple[str, Path]] = []
    seen: set[Path] = set()
    budget = [MAX_FOLDERS]
    for root in roots:
        _walk(root, found, seen, budget)
    real: set[tuple[str, str]] = set()
    unique = []
    for name, folder in found:
        key = (name, os.path.realpath(folder))
        if key not in real:
            real.add(key)
            unique.append((name, folder))
    return unique


def _walk(root: Path, found: list[tuple[str, Path]], seen: set[Path], budget: list[int]) -> None:
    stack = [root]
    while stack and budget[0] > 0:
        folder = stack.pop()
        if folder in seen:
            continue
        seen.add(folder)
        budget[0] -= 1
        try:
            names = set(os.listdir(folder))
        except OSError:
            continue
        if any(marker in names for marker in IGNORE_MARKERS):
            continue
        if "package.xml" in names:
            name = package_name(folder)
            if name is not None:
                found.append((name, folder))
                continue
        subs = sorted(
            (n for n in names if not n.startswith(".") and n not in SKIP_DIRS), reverse=True
        )
        stack.extend(folder / n for n in subs if (folder / n).is_dir())


def discover(paths: Iterable[Path]) -> Found:
    """The packages a run over ``paths`` can use for ``$(find)`` and ``package://``."""
    return packages_below(roots_for(paths))


class Packages(Mapping[str, Path]):
    """The packages below ``paths``, found on first use: a run that resolves no package
    (a URDF without ``package://`` meshes, no xacro ``$(find)``) never walks the tree.

    With ``cache`` (:class:`urdflint.cache.Cache`) the index is kept with the folders the
    walk listed and the ``package.xml`` files it read: the next run checks their times
    instead of walking the tree again. A cached analysis that looked a package up records
    the index it used (``packages`` input), so a package added or moved makes it stale.
    """

    def __init__(self, paths: Iterable[Path], cache: object = None) -> None:
        self.paths = tuple(paths)
        self.cache = cache
        self._found: dict[str, Path] | None = None
        self._all: dict[str, tuple[Path, ...]] = {}
        self._digest = ""
        # its name in analysis keys and records' inputs: a digest, however many paths the
        # run was given (the paths themselves made each record of a 2,000-file run 144 kB)
        given = json.dumps(sorted({str(p.resolve()) for p in self.paths}))
        self.key = "paths:" + hashlib.blake2b(given.encode(), digest_size=16).hexdigest()
        self.walked: tuple[Path, ...] | None = None  # the folders walked, as given (messages)
        _LIVE[self.key] = self

    def __setstate__(self, state: dict[str, object]) -> None:
        """Unpickled in a worker (``--jobs``, Ray): known by its key there too."""
        self.__dict__.update(state)
        _LIVE[self.key] = self

    @property
    def found(self) -> dict[str, Path]:
        from urdflint.cache import deps

        if self._found is None:
            cache = self.cache
            if cache is not None and getattr(cache, "usable", False):
                with deps.unrecorded():  # the index's own inputs are kept with the index
                    listed = cache.result("packages", (self.key,), self._discover)  # type: ignore[attr-defined]
            else:
                with deps.unrecorded():  # the "packages" input below stands for the walk
                    listed = self._discover()
            every: dict[str, list[Path]] = {}
            for name, folder in listed:
                every.setdefault(name, []).append(Path(folder))
            self._all = {name: tuple(folders) for name, folders in every.items()}
            self._found = {name: folders[0] for name, folders in self._all.items()}
            self._digest = _digest(listed)
        deps.note("packages", self.key, self._digest)
        return self._found

    def _discover(self) -> list[tuple[str, str]]:
        # by name; a name's packages stay in the order of the walk (the sort is stable)
        found = discover(self.paths).every
        return sorted(((name, str(folder)) for name, folder in found), key=lambda p: p[0])

    def candidates(self, name: str) -> tuple[Path, ...]:
        """Every package named ``name``, the first found first (one, unless the workspace
        holds several of that name)."""
        self.found  # noqa: B018 - builds (or checks) the index
        return self._all.get(name, ())

    def duplicates(self) -> dict[str, tuple[Path, ...]]:
        """The names the workspace holds more than one package of."""
        self.found  # noqa: B018
        return {name: folders for name, folders in self._all.items() if len(folders) > 1}

    def __getitem__(self, name: str) -> Path:
        return self.found[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self.found)

    def __len__(self) -> int:
        return len(self.found)


_LIVE: dict[str, Packages] = {}  # the indexes this process read, by their roots


def _digest(listed: list[tuple[str, str]]) -> str:
    return hashlib.blake2b(json.dumps(listed).encode(), digest_size=16).hexdigest()


def _same_packages(key: str, recorded: object) -> bool:
    """A cached analysis's ``packages`` input: the index of these roots is still the same.
    The key names the paths of a run of this process (an analysis's key holds its
    workspace's: another run's results are never looked up here); unknown, it is stale."""
    live = _LIVE.get(key)
    if live is None:
        return False
    live.found  # noqa: B018 - builds (or checks) the index
    return live._digest == recorded


def _register() -> None:
    from urdflint.cache import deps

    deps.register("packages", _same_packages)


_register()
