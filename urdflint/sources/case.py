"""A file named with another letter case: found on macOS and Windows, missing on Linux.

C016 reports such references; C004 leaves them to it (one finding per element).
"""

from __future__ import annotations

import os
from pathlib import Path

MAX_ENTRIES = 5000  # a folder with more names is not searched


def _names(folder: Path, cache: dict[Path, frozenset[str] | None]) -> frozenset[str] | None:
    if folder in cache:
        return cache[folder]
    cache[folder] = None
    try:
        with os.scandir(folder) as entries:
            names = [entry.name for _, entry in zip(range(MAX_ENTRIES + 1), entries, strict=False)]
    except OSError:
        return None
    cache[folder] = frozenset(names) if len(names) <= MAX_ENTRIES else None
    return cache[folder]


def case_variant(path: Path, cache: dict[Path, frozenset[str] | None] | None = None) -> Path | None:
    """The existing file whose path differs from ``path`` (absolute) only in letter case,
    ``None`` when the names match exactly, or no single such file exists. ``cache`` holds
    folder listings for one run of the rule (folders change between runs)."""
    cache = {} if cache is None else cache
    current, rest = _deepest_existing(path)
    changed = False
    for part in rest:
        names = _names(current, cache)
        if names is None:
            return None
        if part not in names:
            matches = [n for n in names if n.lower() == part.lower()]
            if len(matches) != 1:
                return None
            part, changed = matches[0], True
        current = current / part
    return current if changed and current.is_file() else None


def _deepest_existing(path: Path) -> tuple[Path, tuple[str, ...]]:
    """The deepest folder above ``path`` that exists as written, and the parts below it.

    Letter case is searched only below it: a folder that exists as written is the one a
    case-insensitive file system opens too. Nothing above it is listed (the service's
    fence refuses listings outside the upload, and a machine's folders are no business
    of the model's).
    """
    parts = path.parts
    for depth in range(len(parts) - 1, 0, -1):
        folder = Path(*parts[:depth])
        if folder.is_dir():
            return folder, parts[depth:]
    return Path(path.anchor), parts[1:]
