"""The fix tool: the automatic fixes as edits and a unified diff, written only when asked.

``write=false`` (the default) is ``urdflint fix --diff``: the fixes of the findings as they
are now (safe ones; unsafe ones too with ``unsafe=true``), each with its text edits (byte
offsets into the file as it is, :meth:`urdflint.model.edits.Edit.to_dict`), and the unified
diff of applying them with :func:`urdflint.model.edits.apply`; nothing is written. An edit
that overlaps one before it is left out of the diff, as ``urdflint fix`` leaves it for its
next round. ``write=true`` is ``urdflint fix``: rounds of lint, apply, write
(:func:`urdflint.engine.fixes.rounds`) until nothing changes, then what is left.

Either way a fix is offered or applied only when every file it edits is inside the client's
roots (symbolic links resolved); the others are counted in ``outside``. A text given instead
of a file can be previewed, not written.
"""

from __future__ import annotations

import difflib
import os
from collections.abc import Mapping
from typing import Any

from urdflint.engine import fixes
from urdflint.mcp import runs
from urdflint.mcp.roots import Refused, Roots
from urdflint.model import edits as E
from urdflint.model.edits import Autofix, Edit
from urdflint.model.finding import Finding

NO_NEWLINE = "\\ No newline at end of file\n"


def fix(arguments: Mapping[str, Any], roots: Roots) -> tuple[str, dict[str, Any]]:
    """The tool's text and structured content."""
    req = runs.request(arguments, roots)
    unsafe = bool(arguments.get("unsafe"))
    if arguments.get("write"):
        if req.is_text:
            raise Refused("write=true needs files: a text given as text can only be previewed")
        data = written(req, unsafe)
        head = (
            f"fixed {data['applied']} finding(s) in {len(data['written'])} file(s); "
            f"{len(data['remaining']['findings'])} finding(s) remain"
        )
    else:
        data = preview(req, unsafe)
        head = (
            f"{len(data['fixes'])} fix(es) would change {data['files']} file(s); "
            "nothing was written (write=true applies them)"
        )
    if data["outside"]:
        head += f"; {data['outside']} fix(es) edit files outside the roots: left out"
    if data["unsafe_left"]:
        head += f"; {data['unsafe_left']} more with unsafe=true"
    return "\n".join([head, data["diff"]]).rstrip("\n"), data


def preview(req: runs.Request, unsafe: bool) -> dict[str, Any]:
    """The fixes of the findings now, their edits and the diff; nothing is written."""
    run = runs.check(req)
    chosen = [(f, f.autofix) for f in run.findings if usable(f.autofix, unsafe, req.roots)]
    by_path: dict[str, list[Edit]] = {}
    for _, autofix in chosen:
        for edit in autofix.edits:  # type: ignore[union-attr]
            by_path.setdefault(edit.path, []).append(edit)
    diffs = []
    for path, found in sorted(by_path.items()):
        old = _current(path, req, creating=all(e.create for e in found))
        if old is None:
            continue
        new, _later = E.apply(old, found)
        diffs.append(unified(old, new, path))
    return {
        "fixes": [_fix_dict(f, autofix) for f, autofix in chosen],  # type: ignore[arg-type]
        "files": sum(1 for text in diffs if text),
        "diff": "".join(diffs),
        "written": [],
        **_left(run.findings, unsafe, req.roots),
    }


def written(req: runs.Request, unsafe: bool) -> dict[str, Any]:
    """``urdflint fix [--unsafe-fixes]``, confined: the changed files, their diff, what is left."""

    def choose(autofix: Autofix | None) -> Autofix | None:
        return autofix if usable(autofix, unsafe, req.roots) else None

    def write(path: str, data: bytes) -> None:
        real = os.path.realpath(os.path.abspath(path))
        if req.roots.containing(real) is None:  # usable() let no such edit through
            raise Refused(f"{path}: outside the allowed roots ({req.roots.describe()})")
        with open(real, "wb") as out:
            out.write(data)

    run, originals, applied = fixes.rounds(lambda: runs.check(req), unsafe, write, choose)
    diffs = []
    for path, old in sorted(originals.items()):
        with open(path, "rb") as handle:
            diffs.append(unified(old, handle.read(), path))
    return {
        "applied": applied,
        "written": sorted(originals),
        "diff": "".join(diffs),
        "remaining": runs.envelope(run),
        **_left(run.findings, unsafe, req.roots),
    }


def usable(autofix: Autofix | None, unsafe: bool, roots: Roots) -> bool:
    """Whether the fix can be applied here: edits, no reason against, allowed, inside the
    roots."""
    if autofix is None or autofix.unavailable or not autofix.edits:
        return False
    if autofix.applicability == "unsafe" and not unsafe:
        return False
    return all(_inside(edit.path, roots) for edit in autofix.edits)


def _inside(path: str, roots: Roots) -> bool:
    return roots.containing(os.path.abspath(path)) is not None


def _left(findings: list[Finding], unsafe: bool, roots: Roots) -> dict[str, int]:
    """Fixes left out: those only ``unsafe=true`` applies, those editing outside the roots."""
    ready = [f.autofix for f in findings if f.autofix and not f.autofix.unavailable]
    ready = [fix for fix in ready if fix.edits]
    outside = sum(1 for fix in ready if not all(_inside(e.path, roots) for e in fix.edits))
    more = 0 if unsafe else sum(1 for fix in ready if fix.applicability == "unsafe")
    return {"outside": outside, "unsafe_left": more}


def _current(path: str, req: runs.Request, creating: bool) -> bytes | None:
    """The bytes the edits of ``path`` apply to: a text given, else the file (``b""`` for a
    file a fix creates); ``None`` when it cannot be read, or exists where one is created."""
    full = os.path.abspath(path)
    if full in req.overlay:
        return req.overlay[full]
    if creating:
        return None if os.path.lexists(full) else b""
    try:
        with open(full, "rb") as handle:
            return handle.read()
    except OSError:
        return None


def _fix_dict(finding: Finding, autofix: Autofix) -> dict[str, Any]:
    return {
        "code": finding.code,
        "path": finding.path,
        "line": finding.line,
        "element": finding.element,
        **autofix.to_dict(),
    }


def unified(old: bytes, new: bytes, name: str) -> str:
    """The change as a unified diff (``""`` when there is none), as ``urdflint fix --diff``
    prints it; a last line without a newline is marked as ``diff`` marks it."""
    lines: list[str] = []
    for line in difflib.unified_diff(
        old.decode("utf-8", "replace").splitlines(keepends=True),
        new.decode("utf-8", "replace").splitlines(keepends=True),
        fromfile=name if old else "/dev/null",
        tofile=name,
    ):
        lines.append(line)
        if not line.endswith("\n"):
            lines.append("\n" + NO_NEWLINE)
    return "".join(lines)
