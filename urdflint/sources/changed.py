"""``--changed-since REF``: keep only the URDF/xacro files git reports as changed since REF.

Changed means ``git diff --name-only REF`` (committed, staged and unstaged changes
between REF and the working tree) plus untracked, not ignored files. git runs as a
subprocess without a shell, in the repository holding the first PATH.
"""

from __future__ import annotations

import subprocess
from collections.abc import Sequence
from pathlib import Path

SUFFIXES = (".urdf", ".xacro")


class ChangedError(Exception):
    """Not a git repository, an unknown ref, or git itself is missing."""


def _git(args: Sequence[str], cwd: Path) -> str:
    try:
        done = subprocess.run(
            ["git", *args], cwd=cwd, capture_output=True, text=True, check=False, timeout=120
        )
    except FileNotFoundError:
        raise ChangedError("--changed-since needs git, which is not installed") from None
    except subprocess.TimeoutExpired:
        raise ChangedError(f"git {args[0]} timed out") from None
    if done.returncode != 0:
        raise _GitFailed(done.stderr.strip().splitlines()[-1:] or [""])
    return done.stdout


class _GitFailed(Exception):
    pass


def toplevel(start: Path) -> Path:
    """The root of the git work tree holding ``start``."""
    folder = start if start.is_dir() else start.parent
    try:
        out = _git(["rev-parse", "--show-toplevel"], folder.resolve())
    except _GitFailed:
        raise ChangedError(f"--changed-since: {start} is not inside a git work tree") from None
    return Path(out.strip()).resolve()


def changed_files(ref: str, start: Path) -> set[Path]:
    """Resolved paths of the files changed since ``ref`` or untracked, in the repo of ``start``."""
    root = toplevel(start)
    if ref.startswith("-"):
        raise ChangedError(f"--changed-since: {ref!r} is not a git ref")
    try:
        _git(["rev-parse", "--verify", "--quiet", "--end-of-options", f"{ref}^{{commit}}"], root)
    except _GitFailed:
        raise ChangedError(f"--changed-since: unknown git ref {ref!r}") from None
    try:
        diff = _git(["diff", "--name-only", "-z", "--no-renames", ref, "--"], root)
        untracked = _git(["ls-files", "--others", "--exclude-standard", "-z"], root)
    except _GitFailed as exc:
        raise ChangedError(f"--changed-since: git failed: {exc.args[0][0]}") from None
    names = [n for n in (diff + untracked).split("\0") if n]
    return {(root / name).resolve() for name in names}


def select(
    files: Sequence[str], paths: Sequence[str], changed: set[Path], skip: set[str]
) -> list[str]:
    """The collected ``files`` that changed, plus changed ``*.xacro`` files below folder PATHs.

    ``-`` (stdin) is always kept. Deleted files are not linted.
    """
    kept = [f for f in files if f == "-" or Path(f).resolve() in changed]
    for raw in paths:
        folder = Path(raw)
        if raw == "-" or not folder.is_dir():
            continue
        base = folder.resolve()
        for path in sorted(changed):
            if not path.name.lower().endswith(SUFFIXES) or not path.is_file():
                continue
            try:
                parts = path.relative_to(base).parts
            except ValueError:
                continue
            if any(p.startswith(".") or p in skip for p in parts[:-1]):
                continue
            kept.append(str(folder / Path(*parts)))
    unique: dict[Path | str, str] = {}
    for name in kept:
        unique.setdefault(name if name == "-" else Path(name).resolve(), name)
    return list(unique.values())
