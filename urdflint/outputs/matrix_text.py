"""The compatibility matrix and a finding's effects as text lines."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import groupby
from typing import Any

from urdflint.model import targets as T
from urdflint.model.effects import Outcome
from urdflint.model.finding import Finding

LABELS = {o.key: o.label for o in Outcome} | {"not-installed": "not installed"}
MAX_LINES = 3  # lines named per rule in a row
MAX_RULES = 3  # rules named in a row


def effects_line(finding: Finding) -> str | None:
    """``refused: Gazebo Classic, MuJoCo · as written: PyBullet, Pinocchio`` when the run
    aims at several targets and the message does not already name every one concerned."""
    if len(finding.effects) < 2:
        return None
    if all(T.LABELS[t].split()[0] in finding.message for t, _ in finding.effects):
        return None
    grouped: dict[str, list[str]] = {}
    for target, effect in finding.effects:
        grouped.setdefault(effect.consequence.key, []).append(T.LABELS[target])
    return " · ".join(f"{key}: {', '.join(labels)}" for key, labels in grouped.items())


def table(rows: Sequence[dict[str, Any]]) -> list[str]:
    """One block per file: a line per target with the prediction, the engine's outcome when
    it was confirmed, and the findings that decide it."""
    lines: list[str] = []
    width = max(len(r["label"]) for r in rows) + 1
    confirmed = any(r["confirmed"] for r in rows)
    for path, block in groupby(rows, key=lambda r: r["path"]):
        lines.append(f"{path}: what each target does with the model (--matrix)")
        for row in block:
            label = row["label"] + ("" if row["basis"] == "engine" else "*")
            predicted = LABELS[row["predicted"]["outcome"]]
            mark = "✓" if row.get("selected", True) else " "
            text = f"  {mark} {label:<{width}} {predicted:<19}"
            if confirmed:
                seen = row["confirmed"]
                text += f" {'engine: ' + LABELS[seen['outcome']] if seen else '':<27}"
            brief = row["predicted"]["outcome"] in ("refused", "crashes")
            lines.append(f"{text} {_deciding(row['predicted']['findings'], brief)}".rstrip())
    if not all(r.get("selected", True) for r in rows):
        lines.append("  ✓ the targets checked: their findings are the ones reported")
    if any(r["basis"] != "engine" for r in rows):
        lines.append("  * not run here: predicted from its source code and documentation")
    return lines


def _deciding(found: list[dict[str, Any]], brief: bool = False) -> str:
    """``I002 inertia substituted (line 20), G002 tag ignored (lines 12, 19, 25)``; without
    the consequences when ``brief`` (they are all the row's refusal or crash)."""
    parts = []
    ordered = sorted(found, key=lambda d: (d["code"], d["consequence"], d["line"]))
    for (code, consequence), group in groupby(ordered, key=lambda d: (d["code"], d["consequence"])):
        lines = sorted({d["line"] for d in group})
        shown = ", ".join(str(n) for n in lines[:MAX_LINES])
        if len(lines) > MAX_LINES:
            shown += f" +{len(lines) - MAX_LINES}"
        noun = "line" if len(lines) == 1 else "lines"
        parts.append(
            f"{code} ({noun} {shown})" if brief else f"{code} {consequence} ({noun} {shown})"
        )
    if len(parts) > MAX_RULES:
        parts[MAX_RULES:] = [f"{len(parts) - MAX_RULES} more (JSON: matrix)"]
    return ", ".join(parts)
