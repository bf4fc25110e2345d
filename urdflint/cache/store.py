"""The analysis cache on disk: content-addressed entries, written atomically, bounded in size.

Layout (``DIR`` is the cache directory, see :func:`default_dir`)::

    DIR/CACHEDIR.TAG                  marks the folder as a cache for backup tools
    DIR/analysis-v1/<kind>/<ab>/<key> one entry: a header, then a pickled value

Every entry starts with ``MAGIC``, the length and a BLAKE2b digest of its payload: an entry
that is truncated, corrupt or written by another format is ignored (and removed when the
folder is writable), so the next run computes the value again and rewrites it. A value is
written to a temporary file in the entry's folder and renamed over the entry (atomic on
POSIX and Windows), so processes writing the same entry at once never leave half an entry:
the last rename wins, and both wrote the same value. Every hit touches the entry's
modification time; when the folder grows over its limit, the entries used least recently
are removed first. A folder that cannot be written (a CI cache restored read-only) is read
as it is: nothing is written, nothing fails. The folder is the user's alone (mode 0700); a
folder that another user owns, or that others may write to, is not used.

Nothing here knows what the values mean: the callers (:mod:`urdflint.cache`) make the keys
from urdflint's version, the settings and the content of every input.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import pickle
import stat
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

log = logging.getLogger(__name__)

FORMAT = "analysis-v1"  # the folder of this entry format; another format lives beside it
MAGIC = b"URDFLINT-CACHE\x01"
DIGEST = 16
HEADER = len(MAGIC) + 8 + DIGEST
DEFAULT_MAX_BYTES = 512 * 2**20
GC_EVERY = 600.0  # s: the size is checked at most this often, or when a run wrote much
TAG = (
    "Signature: 8a477f597d28d172789f06886806bc55\n"
    "# This file is a cache directory tag created by urdflint.\n"
    "# For information about cache directory tags see https://bford.info/cachedir/\n"
)


def default_dir(environ: Any = None) -> Path:
    """``$URDFLINT_CACHE_DIR``, else ``$XDG_CACHE_HOME/urdflint``, else ``~/.cache/urdflint``."""
    env = os.environ if environ is None else environ
    if env.get("URDFLINT_CACHE_DIR"):
        return Path(env["URDFLINT_CACHE_DIR"]).expanduser()
    base = env.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "urdflint"


def parse_size(text: str | int) -> int:
    """``"512M"``, ``"2G"``, ``"100k"`` or a number of bytes."""
    if isinstance(text, int):
        return text
    raw = text.strip().upper().removesuffix("B").removesuffix("I")
    factor = 1
    for suffix, power in (("K", 1), ("M", 2), ("G", 3), ("T", 4)):
        if raw.endswith(suffix):
            factor, raw = 1024**power, raw[:-1]
            break
    value = float(raw)
    if value < 0:
        raise ValueError(text)
    return int(value * factor)


@dataclass
class Stats:
    """What one process did with the cache (``urdflint check -v`` and the bench print it)."""

    hits: int = 0
    misses: int = 0
    writes: int = 0
    written: int = 0  # bytes
    corrupt: int = 0


class Store:
    """Entries by ``(kind, key)`` in one folder; see the module docstring."""

    def __init__(self, folder: Path, max_bytes: int = DEFAULT_MAX_BYTES) -> None:
        self.folder = Path(folder)
        self.base = self.folder / FORMAT
        self.max_bytes = max_bytes
        self.stats = Stats()
        self.folders: set[Path] = set()  # entry folders known to exist
        self.usable, self.writable, self.problem = self._open()

    # -- opening ------------------------------------------------------------------------

    def _open(self) -> tuple[bool, bool, str | None]:
        folder = self.folder
        if not folder.exists():
            try:
                folder.mkdir(parents=True, mode=0o700)
                (folder / "CACHEDIR.TAG").write_text(TAG)
            except OSError:
                return False, False, f"cannot create the cache folder {folder}"
        try:
            info = folder.stat()
        except OSError as exc:
            return False, False, f"cannot read the cache folder {folder} ({exc.strerror})"
        if not stat.S_ISDIR(info.st_mode):
            return False, False, f"the cache folder {folder} is not a folder"
        if hasattr(os, "getuid") and info.st_uid != os.getuid():
            return False, False, f"the cache folder {folder} belongs to another user"
        if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
            return False, False, f"others may write to the cache folder {folder}"
        writable = os.access(folder, os.W_OK)
        if writable:
            try:
                self.base.mkdir(mode=0o700, exist_ok=True)
            except OSError:
                writable = False
        return True, writable and os.access(self.base, os.W_OK), None

    # -- entries ------------------------------------------------------------------------

    def path(self, kind: str, key: str) -> Path:
        return self.base / kind / key[:2] / key

    def get(self, kind: str, key: str) -> Any:
        """The value stored under ``(kind, key)``, or ``None``."""
        if not self.usable:
            return None
        path = self.path(kind, key)
        try:
            with open(path, "rb") as handle:
                data = handle.read()
        except OSError:
            self.stats.misses += 1
            return None
        value = self._decode(data)
        if value is None:
            self.stats.corrupt += 1
            self.stats.misses += 1
            if self.writable:
                with contextlib.suppress(OSError):
                    path.unlink()
            return None
        self.stats.hits += 1
        if self.writable:
            with contextlib.suppress(OSError):
                os.utime(path)  # recently used: evicted last
        return value[0]

    def put(self, kind: str, key: str, value: Any) -> bool:
        """Store ``value`` (any picklable object); False when the folder is read-only."""
        if not self.writable:
            return False
        try:
            payload = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # an unpicklable value is a bug of the caller, not of the run
            log.debug("cannot store a %s entry", kind, exc_info=True)
            return False
        import tempfile  # only a run that writes pays for it (random, shutil...)

        digest = hashlib.blake2b(payload, digest_size=DIGEST).digest()
        data = MAGIC + len(payload).to_bytes(8, "little") + digest + payload
        path = self.path(kind, key)
        try:
            if path.parent not in self.folders:
                path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
                self.folders.add(path.parent)
            handle, temporary = tempfile.mkstemp(prefix=".tmp-", dir=path.parent)
            try:
                with os.fdopen(handle, "wb") as out:
                    out.write(data)
                os.replace(temporary, path)
            except BaseException:
                with contextlib.suppress(OSError):
                    os.unlink(temporary)
                raise
        except OSError:
            log.debug("cannot write the cache entry %s", path, exc_info=True)
            self.writable = False  # a full disk or a folder made read-only: stop trying
            return False
        self.stats.writes += 1
        self.stats.written += len(data)
        return True

    @staticmethod
    def _decode(data: bytes) -> tuple[Any] | None:
        if len(data) < HEADER or not data.startswith(MAGIC):
            return None
        size = int.from_bytes(data[len(MAGIC) : len(MAGIC) + 8], "little")
        digest = data[len(MAGIC) + 8 : HEADER]
        payload = data[HEADER:]
        if len(payload) != size:
            return None
        if hashlib.blake2b(payload, digest_size=DIGEST).digest() != digest:
            return None
        try:
            return (pickle.loads(payload),)
        except Exception:  # a class that moved between versions: a miss
            return None

    # -- size ---------------------------------------------------------------------------

    def entries(self) -> list[tuple[float, int, Path]]:
        """``(last use, bytes, path)`` of every entry, temporary files of crashed writers
        older than an hour included (they are removed like entries)."""
        found: list[tuple[float, int, Path]] = []
        if not self.base.is_dir():
            return found
        for folder, _dirs, files in os.walk(self.base):
            for name in files:
                path = Path(folder) / name
                try:
                    info = path.stat()
                except OSError:
                    continue
                if name.startswith(".") and not (
                    name.startswith(".tmp-") and time.time() - info.st_mtime > 3600
                ):
                    continue  # the collection marker, a write under way
                found.append((info.st_mtime, info.st_size, path))
        return found

    def size(self) -> tuple[int, int]:
        """(entries, bytes)."""
        found = self.entries()
        return len(found), sum(size for _, size, _ in found)

    def collect(self, force: bool = False) -> int:
        """Remove the entries used least recently until the folder is under its limit; runs
        at most every ``GC_EVERY`` seconds unless ``force`` or this process wrote much.
        Returns the number of entries removed."""
        if not self.writable:
            return 0
        marker = self.base / ".last-collect"
        heavy = self.stats.written > self.max_bytes // 10
        if not force and not heavy:
            try:
                if time.time() - marker.stat().st_mtime < GC_EVERY:
                    return 0
            except OSError:
                pass
        with contextlib.suppress(OSError):
            marker.touch()
        found = self.entries()
        total = sum(size for _, size, _ in found)
        removed = 0
        if total <= self.max_bytes:
            return 0
        goal = int(self.max_bytes * 0.8)  # some room, so the next runs do not collect again
        for _, size, path in sorted(found):
            if total <= goal:
                break
            try:
                path.unlink()
            except OSError:
                continue
            total -= size
            removed += 1
        return removed

    def clean(self) -> int:
        """Remove every entry of every format; returns how many files were removed."""
        removed = 0
        if not self.folder.is_dir():
            return 0
        for child in self.folder.iterdir():
            if not child.name.startswith("analysis-") or not child.is_dir():
                continue
            for folder, _dirs, files in os.walk(child, topdown=False):
                for name in files:
                    with contextlib.suppress(OSError):
                        os.unlink(os.path.join(folder, name))
                        removed += 1
                with contextlib.suppress(OSError):
                    os.rmdir(folder)
        return removed
