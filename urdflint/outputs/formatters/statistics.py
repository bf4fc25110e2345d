"""``--statistics``: one row per rule, most frequent first (as ``ruff check --statistics``):
how many findings, the rule's code, name and severity, and how many have an automatic fix
(safe or unsafe). A table in the text format, a list in JSON."""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

from urdflint.model.finding import Finding

HEADER = ("count", "code", "name", "severity", "fixable")


def rows(findings: Sequence[Finding]) -> list[dict[str, Any]]:
    """``{"code", "name", "severity", "count", "fixable"}`` per rule; the severity is the
    highest of its findings."""
    by_code: dict[str, list[Finding]] = {}
    for f in findings:
        by_code.setdefault(f.code, []).append(f)
    found = [
        {
            "code": code,
            "name": group[0].name,
            "severity": str(max(f.severity for f in group)),
            "count": len(group),
            "fixable": sum(1 for f in group if _fixable(f)),
        }
        for code, group in by_code.items()
    ]
    found.sort(key=lambda row: (-row["count"], row["code"]))
    return found


def _fixable(finding: Finding) -> bool:
    return finding.autofix is not None and not finding.autofix.unavailable


def _unsafe(findings: Sequence[Finding]) -> dict[str, int]:
    counts: dict[str, int] = {}
    for f in findings:
        if f.autofix is not None and _fixable(f) and f.autofix.applicability != "safe":
            counts[f.code] = counts.get(f.code, 0) + 1
    return counts


def table(findings: Sequence[Finding]) -> list[str]:
    """The rows as aligned text under a header line (nothing when there is no finding):
    ``count  code  name  severity  fixable``, the fixable ones as ``2 (1 unsafe)``."""
    found = rows(findings)
    if not found:
        return []
    unsafe = _unsafe(findings)
    cells = [HEADER]
    for row in found:
        more = unsafe.get(row["code"], 0)
        fixable = str(row["fixable"] or "") + (f" ({more} unsafe)" if more else "")
        cells.append((str(row["count"]), row["code"], row["name"], row["severity"], fixable))
    widths = [max(len(line[i]) for line in cells) for i in range(len(HEADER))]
    return ["  ".join(_aligned(line, widths)).rstrip() for line in cells]


def _aligned(cells: Sequence[str], widths: Sequence[int]) -> list[str]:
    """The count right-aligned, the other cells left-aligned."""
    return [
        c.rjust(w) if i == 0 else c.ljust(w)
        for i, (c, w) in enumerate(zip(cells, widths, strict=True))
    ]


def render_json(findings: Sequence[Finding]) -> str:
    """The rows as a JSON list, one rule per line."""
    found = rows(findings)
    if not found:
        return "[]\n"
    return "[\n" + ",\n".join("  " + json.dumps(row) for row in found) + "\n]\n"
