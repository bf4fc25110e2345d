"""Cache keys: urdflint's code and the libraries that shape a result, and a stable digest of
any settings object.

:func:`code_version` changes with urdflint's version, with any change to its code (the
hashes of an installed wheel's files, or the content of a source checkout's files: an
editable install under development gives no stale result, a reinstall of the same code keeps
the cache), and with the versions of Python and of the libraries whose answers end up in
findings (lxml, xacro, trimesh, Pinocchio, numpy, scipy, pycollada) or whose absence skips
rules.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import hashlib
import importlib.util
import json
import os
import sys
from pathlib import Path
from typing import Any

PACKAGE = Path(__file__).resolve().parent.parent  # urdflint/
LIBRARIES = ("lxml", "xacro", "trimesh", "pin", "numpy", "scipy", "pycollada", "yourdfpy")


def digest(*parts: Any) -> str:
    """A hex digest of ``parts`` made canonical (see :func:`canonical`)."""
    text = json.dumps(canonical(parts), sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.blake2b(text.encode("utf-8"), digest_size=20).hexdigest()


def canonical(value: Any) -> Any:
    """JSON-able and independent of hashing order: sets sorted, paths as strings, dataclasses
    as their class name and fields."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, enum.Enum):
        return f"{type(value).__name__}.{value.name}"
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, bytes):
        return hashlib.blake2b(value, digest_size=16).hexdigest()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: canonical(getattr(value, f.name)) for f in dataclasses.fields(value)}
        return {"__class__": type(value).__name__, **fields}
    if isinstance(value, dict):
        return {"__dict__": sorted((str(canonical(k)), canonical(v)) for k, v in value.items())}
    if isinstance(value, set | frozenset):
        return {"__set__": sorted((canonical(v) for v in value), key=repr)}
    if isinstance(value, list | tuple):
        return [canonical(v) for v in value]
    return repr(value)


@functools.lru_cache(maxsize=1)
def code_version() -> str:
    """What urdflint's results depend on besides its inputs (see the module docstring)."""
    version = getattr(sys.modules.get("urdflint"), "__version__", "")  # the package's own

    parts: list[Any] = [version, sys.version, sys.platform, _installed_code()]
    for name in LIBRARIES:
        parts.append((name, _library(name)))
    return digest(*parts)


def _installed_code() -> str:
    """A digest of urdflint's code: the ``RECORD`` of an installed wheel (the hash of every
    file it installed: the same on every machine and every CI run), else, for a source
    checkout or an editable install, the content of its source files."""
    package = os.path.realpath(PACKAGE)
    for folder, names in _site_listings():
        for entry in names:
            if entry.startswith("urdflint-") and entry.endswith(".dist-info"):
                if not package.startswith(os.path.realpath(folder) + os.sep):
                    continue  # an editable install: the code is elsewhere
                try:
                    with open(os.path.join(folder, entry, "RECORD"), "rb") as handle:
                        return hashlib.blake2b(handle.read(), digest_size=16).hexdigest()
                except OSError:
                    break
    found = hashlib.blake2b(digest_size=16)
    for source in _source_folders():
        for name, path in _tree(source):
            try:
                with open(path, "rb") as handle:
                    found.update(name.encode() + b"\0" + handle.read() + b"\0")
            except OSError:
                continue
    return found.hexdigest()


def _source_folders() -> list[Path]:
    folders = [PACKAGE]
    for name in ("urdflint.rules", "urdflint.server"):
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            continue
        if spec is not None and spec.submodule_search_locations:
            folders.extend(Path(p) for p in spec.submodule_search_locations)
    return list(dict.fromkeys(folders))


def _tree(folder: Path) -> list[tuple[str, str]]:
    """(relative path, path) of every source and data file below, in a stable order."""
    found: list[tuple[str, str]] = []
    for top, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__" and not d.startswith("."))
        for name in sorted(files):
            if name.endswith((".py", ".txt", ".cc", ".json")):
                path = os.path.join(top, name)
                found.append((os.path.relpath(path, folder), path))
    return found


def _library(name: str) -> str | None:
    """The installed version of a library, read from the names of the ``*.dist-info``
    folders beside it (``importlib.metadata`` costs 50 ms to import), else the modification
    time of its module (``None``: not installed)."""
    wanted = name.lower().replace("-", "_")
    for folder, names in _site_listings():
        for entry in names:
            if entry.endswith(".dist-info"):
                dist, _, version = entry[: -len(".dist-info")].partition("-")
                if dist.lower().replace("-", "_") == wanted:
                    return f"{version}@{folder}"
    try:  # a module installed without metadata (Debian's python3-lxml, a source tree)
        spec = importlib.util.find_spec("collada" if name == "pycollada" else name)
    except (ImportError, ValueError):
        return None
    if spec is None or spec.origin is None:
        return None
    try:
        return f"{spec.origin}:{os.stat(spec.origin).st_mtime_ns}"
    except OSError:
        return spec.origin


@functools.lru_cache(maxsize=1)
def _site_listings() -> tuple[tuple[str, tuple[str, ...]], ...]:
    found = []
    # site-packages folders only: not what a library adds below one (Ray's thirdparty_files)
    for folder in dict.fromkeys(p for p in sys.path if p and _site_folder(p)):
        try:
            found.append((folder, tuple(os.listdir(folder))))
        except OSError:
            continue
    return tuple(found)


def _site_folder(path: str) -> bool:
    return os.path.basename(os.path.normpath(path)) in ("site-packages", "dist-packages")


def settings_key(settings: Any) -> Any:
    """What of a file's settings shapes its result (not where the cache lives)."""
    return canonical(dataclasses.replace(settings, cache_dir=None, cache_max_size=None))


def context_key(context: Any) -> Any:
    """What of a run's context shapes a result besides the files it reads."""
    env = context.environ if context.environ is not None else os.environ
    return (
        {name: str(Path(folder).resolve()) for name, folder in context.package_paths.items()},
        str(context.root) if context.root is not None else None,
        dict(context.q),
        getattr(context.workspace, "key", None),
        {name: env.get(name) for name in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")},
        os.getcwd(),
    )
