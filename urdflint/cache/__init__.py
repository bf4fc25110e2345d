"""The analysis cache: work kept between runs, edits and requests, keyed by content.

One :class:`Cache` per run (``Context.cache``; ``None`` with ``--no-cache``) over one folder
on disk (:mod:`urdflint.cache.store`). It keeps, each under urdflint's code version
(:func:`urdflint.cache.keys.code_version`):

- ``mesh``: the facts of each mesh file by content digest and scale (bounds, triangle
  count, units, watertightness, volume, mass properties, convex hull): a run whose meshes
  were seen before, here or in another package, imports no trimesh;
- ``result``: what checking one file gave, with every input it read (:mod:`deps`): a run on
  unchanged inputs replays it without expanding xacro or running a rule;
- ``packages``: the index of the workspace's ROS packages, with the folders it listed.

Values are computed by the caller's function when missing or stale; a cache that cannot be
written is read as it is, and a cache that cannot be used at all makes every lookup a miss.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, TypeVar

from urdflint.cache import deps, keys
from urdflint.cache.store import DEFAULT_MAX_BYTES, Store, default_dir, parse_size

__all__ = ["DEFAULT_MAX_BYTES", "Cache", "default_dir", "deps", "keys", "parse_size"]

log = logging.getLogger(__name__)
T = TypeVar("T")
_MEMORY_MAX = 4096  # mesh facts kept in memory by a long-running process (LSP, service)


class Cache:
    """Lookups and stores for one run (see the module docstring)."""

    def __init__(self, folder: Path | None = None, max_bytes: int = DEFAULT_MAX_BYTES) -> None:
        self.folder = Path(folder) if folder is not None else default_dir()
        self.store = Store(self.folder, max_bytes)
        self.ignore = (str(self.folder.resolve()) + os.sep, *code_folders())
        self.pending: dict[tuple[str, str], Any] = {}
        if self.store.problem:
            log.warning("urdflint: cache not used: %s", self.store.problem)

    def __getstate__(self) -> dict[str, Any]:  # a --jobs worker opens the folder again
        return {"folder": self.folder, "max_bytes": self.store.max_bytes}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["folder"], state["max_bytes"])  # type: ignore[misc]

    @property
    def usable(self) -> bool:
        return self.store.usable

    # -- results with their inputs ------------------------------------------------------

    def result(
        self,
        kind: str,
        parts: tuple[Any, ...],
        compute: Callable[[], T],
        *,
        overlay: Mapping[str, bytes] | None = None,
        environ: Mapping[str, str] | None = None,
        keep: Callable[[T], bool] | None = None,
    ) -> T:
        """``compute()``'s value, replayed when none of the inputs it read changed.

        ``parts`` is everything besides the files that the value depends on (settings,
        options, the path as shown...). ``keep(value)`` says whether a fresh value may be
        stored (an internal error is not).
        """
        key = keys.digest(keys.code_version(), kind, parts)
        hit, value = self._replayed(kind, key, overlay, environ)
        if hit:
            return value  # type: ignore[no-any-return]
        outer = deps.current()
        with deps.recording(self.ignore) as recorder:
            value = compute()
            inputs = recorder.deps()
        if outer is not None:
            outer.inherit(inputs)
        if keep is None or keep(value):
            with deps.unrecorded():
                self.store.put(kind, key, (inputs, value))
        self.flush()
        return value

    def entry(self, kind: str, parts: tuple[Any, ...]) -> tuple[Any, Any] | None:
        """The stored ``(inputs, value)`` of :meth:`keep`, fresh or not (the caller checks)."""
        with deps.unrecorded():
            found = self.store.get(kind, keys.digest(keys.code_version(), kind, parts))
        return found if isinstance(found, tuple) and len(found) == 2 else None

    def keep(self, kind: str, parts: tuple[Any, ...], inputs: Any, value: Any) -> None:
        """Store ``value`` with the ``inputs`` a :func:`deps.recording` saw compute it, for
        :meth:`replayed` (a caller that computes more than it stores)."""
        with deps.unrecorded():
            key = keys.digest(keys.code_version(), kind, parts)
            self.store.put(kind, key, (inputs, value))
        self.flush()

    def replayed(
        self,
        kind: str,
        parts: tuple[Any, ...],
        *,
        overlay: Mapping[str, bytes] | None = None,
        environ: Mapping[str, str] | None = None,
    ) -> tuple[bool, Any]:
        """``(True, value)`` when :meth:`result` would replay, else ``(False, None)``."""
        key = keys.digest(keys.code_version(), kind, parts)
        return self._replayed(kind, key, overlay, environ)

    def _replayed(
        self,
        kind: str,
        key: str,
        overlay: Mapping[str, bytes] | None,
        environ: Mapping[str, str] | None,
    ) -> tuple[bool, Any]:
        outer = deps.current()
        with deps.unrecorded():
            entry = self.store.get(kind, key)
            if not (isinstance(entry, tuple) and len(entry) == 2):
                return False, None
            found, value = entry
            if not deps.unchanged(found, overlay, environ):
                return False, None
        if outer is not None:
            outer.inherit(found)
        return True, value

    # -- plain values by content --------------------------------------------------------

    def get(self, kind: str, *parts: Any) -> Any:
        with deps.unrecorded():
            return self.store.get(kind, keys.digest(keys.code_version(), kind, parts))

    def put(self, kind: str, value: Any, *parts: Any) -> None:
        with deps.unrecorded():
            self.store.put(kind, keys.digest(keys.code_version(), kind, parts), value)

    def key(self, kind: str, *parts: Any) -> str:
        return keys.digest(keys.code_version(), kind, parts)

    def defer(self, kind: str, key: str, value: Any) -> None:
        """Store ``value`` under :meth:`key` when the current result is stored (a later value
        for the same key replaces it: a mesh gains facts as rules ask, and is written once)."""
        self.pending[(kind, key)] = value

    def flush(self) -> None:
        with deps.unrecorded():
            while self.pending:
                (kind, key), value = self.pending.popitem()
                self.store.put(kind, key, value)

    def digest(self, path: str, info: os.stat_result | None = None) -> str | None:
        """A file's content digest (read once per process for one size, time and inode)."""
        return deps.file_digest(path, info)

    def finish(self) -> None:
        """End of a run: write what is pending, keep the folder under its size limit."""
        self.flush()
        with deps.unrecorded():
            try:
                self.store.collect()
            except OSError:
                log.debug("cache collection failed", exc_info=True)


def configured(data: Mapping[str, Any], base: Path) -> tuple[Path | None, int | None]:
    """``cache-dir`` (relative to the configuration's folder) and ``cache-max-size`` of a
    configuration table; ``ValueError`` names the key that is wrong."""
    folder = size = None
    if "cache-dir" in data:
        value = data["cache-dir"]
        if not isinstance(value, str) or not value.strip():
            raise ValueError("'cache-dir' must be the path of a folder")
        folder = base / Path(value).expanduser()
    if "cache-max-size" in data:
        try:
            size = parse_size(data["cache-max-size"])
        except (ValueError, TypeError, AttributeError):
            raise ValueError(
                '\'cache-max-size\' must be a size such as "512M" or "2G", '
                f"not {data['cache-max-size']!r}"
            ) from None
    return folder, size


def code_folders() -> tuple[str, ...]:
    """Where Python's and urdflint's own code lives: what is read there is code (covered by
    :func:`keys.code_version`), never an input of the robot."""
    import sysconfig

    found = {sysconfig.get_paths()[name] for name in ("stdlib", "platstdlib", "purelib", "platlib")}
    found |= {str(p) for p in keys._source_folders()}
    return tuple(os.path.join(os.path.realpath(f), "") for f in sorted(found))


# Mesh facts also live in memory, across the runs of one process (the language server's
# analyses, the service's requests): the facts, never a loaded mesh, so memory stays small.
MEMORY: dict[tuple[str, tuple[float, float, float]], Any] = {}


def remember(key: tuple[str, tuple[float, float, float]], facts: Any) -> None:
    if len(MEMORY) >= _MEMORY_MAX:
        MEMORY.pop(next(iter(MEMORY)))
    MEMORY[key] = facts
