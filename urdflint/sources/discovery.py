"""Which files a run lints: the paths given, folders searched for robot descriptions."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

SKIP_DIRS = {"node_modules", "__pycache__", "build", "install", "log"}


def collect(paths: Sequence[str]) -> tuple[list[str], list[str]]:
    """Files to lint (``-`` kept as is) and one error message per unusable path."""
    files: list[str] = []
    errors: list[str] = []
    for raw in paths:
        if raw == "-":
            files.append(raw)
            continue
        path = Path(raw)
        if path.is_dir():
            found = sorted(
                p
                for p in path.rglob("*.urdf")
                if p.is_file()
                and not any(
                    part.startswith(".") or part in SKIP_DIRS
                    for part in p.relative_to(path).parts[:-1]
                )
            )
            files.extend(str(p) for p in found)
        elif path.is_file():
            files.append(raw)
        elif path.exists():
            errors.append(f"{raw}: not a regular file")
        else:
            errors.append(f"{raw}: no such file or directory")
    return list(dict.fromkeys(files)), errors
