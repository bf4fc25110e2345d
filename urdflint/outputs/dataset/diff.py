"""Two runs of one dataset compared (``urdflint report NEW --against OLD``), as plain dicts.

Files are matched by path. A file present in both got ``worse`` or ``better`` by, in this
order: whether it could be read, whether a rule crashed on it, how many targets refuse it
or crash on it, its outcomes on the targets both runs predicted for (loads < loads with
changes < refused < crashes), its errors, its warnings; ``changed`` when it moved both
ways at once (one target better, another worse). Findings are matched by fingerprint
(path, code and element path, as :meth:`urdflint.model.finding.Finding.fingerprint`:
a finding keeps it when lines move or its message is reworded); new and fixed findings
are those of the files in both runs (the findings of added and removed files come and go
with their files). Rules compare their finding counts over the whole runs.
"""

from __future__ import annotations

import hashlib
from collections import Counter
from collections.abc import Iterable
from typing import Any

from urdflint.outputs.dataset.summary import (
    BLOCKING,
    OUTCOMES,
    File,
    matrix,
    normalize,
    rules,
    status,
    target_order,
)

LIMIT = 500  # entries kept in each list (the counts are whole)


def fingerprint(finding: dict[str, Any]) -> str:
    """A JSON finding's fingerprint: :meth:`Finding.fingerprint` of the finding it writes."""
    parts = (
        str(finding.get("path", "")).replace("\\", "/"),
        str(finding.get("code", "")),
        str(finding.get("element", "")),
    )
    return hashlib.sha256("\0".join(parts).encode("utf-8")).hexdigest()[:32]


def compare(
    old_items: Iterable[dict[str, Any]], new_items: Iterable[dict[str, Any]], *, limit: int = LIMIT
) -> dict[str, Any]:
    """What changed from the ``old`` run's records to the ``new`` one's."""
    old = {f.path: f for f in map(normalize, old_items)}
    new = {f.path: f for f in map(normalize, new_items)}
    both = sorted(old.keys() & new.keys())
    changes: dict[str, list[dict[str, Any]]] = {"worse": [], "better": [], "changed": []}
    for path in both:
        change = _change(old[path], new[path])
        if change is not None:
            changes[change["verdict"]].append(change)
    # the most worsened first, the most improved first
    changes["worse"].sort(key=lambda c: (tuple(-d for d in _moved(c)), c["path"]))
    changes["better"].sort(key=lambda c: (_moved(c), c["path"]))
    added, removed = sorted(new.keys() - old.keys()), sorted(old.keys() - new.keys())
    appeared, gone = _findings([old[p] for p in both], [new[p] for p in both])
    return {
        "files": {
            "old": len(old),
            "new": len(new),
            "added": len(added),
            "removed": len(removed),
            "worse": len(changes["worse"]),
            "better": len(changes["better"]),
            "changed": len(changes["changed"]),
            "same": len(both) - sum(len(v) for v in changes.values()),
        },
        "added": added[:limit],
        "removed": removed[:limit],
        **{k: v[:limit] for k, v in changes.items()},
        "status": _pairs(status(list(old.values())), status(list(new.values()))),
        "matrix": _matrix(list(old.values()), list(new.values())),
        "rules": _rules(list(old.values()), list(new.values()), limit),
        "new_findings": {"count": len(appeared), "items": appeared[:limit]},
        "fixed_findings": {"count": len(gone), "items": gone[:limit]},
    }


def _rank(f: File, targets: list[str]) -> tuple[int, ...]:
    """How bad a file is, worst first in the tuple (compared only on ``targets``)."""
    shown = [f.predicted[t] for t in targets]
    return (
        int(f.error is not None),
        int(f.crashed),
        sum(o in BLOCKING for o in shown),
        sum(OUTCOMES.index(o) for o in shown),
        f.counts.get("error", 0),
        f.counts.get("warning", 0),
    )


def _change(old: File, new: File) -> dict[str, Any] | None:
    shared = [t for t in target_order(old.predicted) if t in new.predicted]
    moved = {
        t: [old.predicted[t], new.predicted[t]]
        for t in shared
        if old.predicted[t] != new.predicted[t]
    }
    before, after = _rank(old, shared), _rank(new, shared)
    counts = [(old.counts.get(s, 0), new.counts.get(s, 0)) for s in ("error", "warning", "info")]
    if not moved and before == after:  # (infos alone do not make a file better or worse)
        return None
    up = any(OUTCOMES.index(b) > OUTCOMES.index(a) for a, b in moved.values())
    down = any(OUTCOMES.index(b) < OUTCOMES.index(a) for a, b in moved.values())
    if up and down and before[:3] == after[:3]:
        verdict = "changed"
    elif after > before:
        verdict = "worse"
    elif after < before:
        verdict = "better"
    else:
        verdict = "changed"
    return {
        "path": new.path,
        "verdict": verdict,
        "errors": list(counts[0]),
        "warnings": list(counts[1]),
        "infos": list(counts[2]),
        "unreadable": [old.error is not None, new.error is not None],
        "crashed": [old.crashed, new.crashed],
        "targets": moved,
    }


def _moved(change: dict[str, Any]) -> tuple[int, ...]:
    """How much a file moved (positive: worse), in the order of :func:`_rank`."""
    moved = change["targets"].values()
    return (
        int(change["unreadable"][1]) - int(change["unreadable"][0]),
        int(change["crashed"][1]) - int(change["crashed"][0]),
        sum((b in BLOCKING) - (a in BLOCKING) for a, b in moved),
        sum(OUTCOMES.index(b) - OUTCOMES.index(a) for a, b in moved),
        change["errors"][1] - change["errors"][0],
        change["warnings"][1] - change["warnings"][0],
    )


def _pairs(old: dict[str, int], new: dict[str, int]) -> dict[str, list[int]]:
    return {key: [old.get(key, 0), new.get(key, 0)] for key in new}


def _matrix(old: list[File], new: list[File]) -> list[dict[str, Any]]:
    """Per target: each outcome's file count, before and after."""
    before = {r["target"]: r for r in matrix([f for f in old if f.error is None])["targets"]}
    after = {r["target"]: r for r in matrix([f for f in new if f.error is None])["targets"]}
    found = []
    for target in target_order(before.keys() | after.keys()):
        a, b = before.get(target, {}), after.get(target, {})
        label = (b or a)["label"]
        found.append(
            {"target": target, "label": label, **{o: [a.get(o, 0), b.get(o, 0)] for o in OUTCOMES}}
        )
    return found


def _rules(old: list[File], new: list[File], limit: int) -> dict[str, list[dict[str, Any]]]:
    """The rules whose finding counts went up, and down, the largest change first."""
    before = {r["code"]: r for r in rules([f for f in old if f.error is None])}
    after = {r["code"]: r for r in rules([f for f in new if f.error is None])}
    moved = []
    for code in sorted(before.keys() | after.keys()):
        a, b = before.get(code), after.get(code)
        was, now = (a["findings"] if a else 0), (b["findings"] if b else 0)
        if was != now:
            rule = b or a
            assert rule is not None
            moved.append(
                {
                    "code": code,
                    "name": rule["name"],
                    "severity": rule["severity"],
                    "old": was,
                    "new": now,
                    "delta": now - was,
                }
            )
    up = sorted((r for r in moved if r["delta"] > 0), key=lambda r: (-r["delta"], r["code"]))
    down = sorted((r for r in moved if r["delta"] < 0), key=lambda r: (r["delta"], r["code"]))
    return {"up": up[:limit], "down": down[:limit]}


def _findings(
    old: list[File], new: list[File]
) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The findings of ``new`` not in ``old`` and those of ``old`` gone from ``new`` (as
    many times as a fingerprint is in one and not in the other)."""
    before = Counter(fingerprint(x) for f in old for x in f.findings)
    after = Counter(fingerprint(x) for f in new for x in f.findings)
    return _beyond(new, before), _beyond(old, after)


def _beyond(files: list[File], other: Counter[str]) -> list[dict[str, Any]]:
    left = Counter(other)
    found = []
    for f in files:
        for x in f.findings:
            key = fingerprint(x)
            if left[key] > 0:
                left[key] -= 1
                continue
            found.append(
                {
                    "file": f.path,
                    "path": str(x.get("path", f.path)),
                    "code": str(x.get("code")),
                    "name": str(x.get("name") or ""),
                    "severity": str(x.get("severity")),
                    "line": x.get("line"),
                    "element": str(x.get("element") or ""),
                    "message": str(x.get("message") or ""),
                    "fingerprint": key,
                }
            )
    found.sort(
        key=lambda x: (
            ("error", "warning", "info").index(x["severity"])
            if x["severity"] in ("error", "warning", "info")
            else 3,
            x["code"],
            x["path"],
            x["element"],
        )
    )
    return found
