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


def effects_line(finding: Finding) -> str | None:
    """``MuJoCo refuses the model · PyBullet loads it as written, silently`` when the
    message does not already name every target concerned."""
    if not finding.effects:
        return None
    if all(T.LABELS[t].split(" (")[0] in finding.message for t, _ in finding.effects):
        return None
    return " · ".join(f"{T.LABELS[t]} {e.consequence.phrase}" for t, e in finding.effects)


def table(rows: Sequence[dict[str, Any]]) -> list[str]:
    """One block per file: a line per target with the prediction, the engine's outcome when
    it was confirmed, and the findings that decide it."""
    lines: list[str] = []
    for path, block in groupby(rows, key=lambda r: r["path"]):
        lines.append(f"{path}: what each target does with the model (--matrix)")
        for row in block:
            predicted = LABELS[row["predicted"]["outcome"]]
            confirmed = row["confirmed"]
            seen = f"engine: {LABELS[confirmed['outcome']]}" if confirmed else ""
            why = _deciding(row["predicted"]["findings"])
            basis = "" if row["basis"] == "engine" else " (from its source and docs)"
            text = f"  {row['label'] + basis:<42} {predicted:<19} {seen:<24} {why}"
            lines.append(text.rstrip())
    return lines


def _deciding(found: list[dict[str, Any]]) -> str:
    """``I002 refused (line 20), G002 tag ignored (lines 12, 19, 25)``."""
    parts = []
    ordered = sorted(found, key=lambda d: (d["code"], d["consequence"], d["line"]))
    for (code, consequence), group in groupby(ordered, key=lambda d: (d["code"], d["consequence"])):
        lines = sorted({d["line"] for d in group})
        shown = ", ".join(str(n) for n in lines[:MAX_LINES])
        if len(lines) > MAX_LINES:
            shown += f" +{len(lines) - MAX_LINES}"
        noun = "line" if len(lines) == 1 else "lines"
        parts.append(f"{code} {consequence} ({noun} {shown})")
    return ", ".join(parts)
