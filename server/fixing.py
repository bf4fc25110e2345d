"""``POST /v1/fix`` in the worker: ``urdflint fix``'s rounds, confined to the uploaded file.

A round lints the upload, applies the applicable fixes of its findings (safe ones; unsafe
ones too with ``unsafe_fixes``) with :func:`urdflint.engine.fixes.apply_all`, writes the
file and lints it again, until nothing changes or :data:`MAX_ROUNDS` rounds have run, as
the CLI does (``urdflint/cli/fix.py``; the server may not import the CLI's layer).

Only the uploaded URDF or xacro file itself is ever edited: a fix is applied only when every
one of its edits is in that file (findings name it by the upload's name), and its edits are
then pointed at that file's path in the job's folder before anything is read or written. A
fix with an edit anywhere else (a xacro file included from the meshes zip, or any other
path) is left out whole, never applied in part; the finding stays in the answer with its
``autofix``. The answer has the fixed text, so the service never edits a file it does not
return. The jobs themselves run in ``jobs.py``, in the job's fence and folder.
"""

from __future__ import annotations

import difflib
import os
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from urdflint.engine import fixes
from urdflint.model.edits import Autofix

MAX_ROUNDS = fixes.MAX_ROUNDS  # as urdflint fix
NO_NEWLINE = "\\ No newline at end of file\n"


def mine(autofix: Autofix | None, shown: str, target: Path) -> Autofix | None:
    """``autofix`` with its edits pointed at ``target`` when every edit is in the upload (the
    file findings name ``shown``) and it can be applied; else ``None``."""
    if autofix is None or autofix.unavailable or not autofix.edits:
        return None
    if any(edit.path != shown for edit in autofix.edits):
        return None
    return replace(autofix, edits=tuple(replace(e, path=str(target)) for e in autofix.edits))


def rounds(
    lint: Callable[[], Any], target: Path, shown: str, unsafe: bool
) -> tuple[Any, bytes, int]:
    """Lint and fix ``target`` until nothing changes: the last lint's result, the file's
    original bytes and how many fixes were applied."""
    original = target.read_bytes()
    result, _originals, applied = fixes.rounds(
        lint, unsafe, _write, lambda fix: mine(fix, shown, target)
    )
    return result, original, applied


def _write(path: str, data: bytes) -> None:
    """Replace the upload's bytes (never through a link; only the upload's edits are kept)."""
    fd = os.open(path, os.O_WRONLY | os.O_TRUNC | os.O_NOFOLLOW)
    with os.fdopen(fd, "wb") as out:
        out.write(data)


def unified(old: bytes, new: bytes, name: str) -> str:
    """The change as a unified diff (``""`` when there is none), as ``urdflint fix --diff``
    prints it; a last line without a newline is marked as ``diff`` marks it."""
    lines: list[str] = []
    for line in difflib.unified_diff(
        old.decode("utf-8", "replace").splitlines(keepends=True),
        new.decode("utf-8", "replace").splitlines(keepends=True),
        fromfile=name,
        tofile=name,
    ):
        lines.append(line)
        if not line.endswith("\n"):
            lines.append("\n" + NO_NEWLINE)
    return "".join(lines)


def answer(reply: dict[str, Any], name: str, original: bytes, applied: int, fixed: bytes) -> None:
    """Add ``fixed``, ``diff`` and ``applied`` to a job's JSON answer (a 200 only)."""
    data = reply["content"]
    if reply["status"] != 200 or not isinstance(data, dict):
        return
    extra = {
        "fixed": fixed.decode("utf-8", "replace"),
        "diff": unified(original, fixed, name),
        "applied": applied,
    }
    head = {key: data.pop(key) for key in ("version", "tool") if key in data}
    reply["content"] = {**head, **extra, **data}
