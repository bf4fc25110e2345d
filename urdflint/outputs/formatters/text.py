"""``path:line:col: severity CODE name: message`` (editors make it clickable)."""

from __future__ import annotations

from collections.abc import Sequence

from urdflint.model.finding import Finding
from urdflint.outputs.formatters.run import RunInfo, summary_line


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    lines = [
        f"{f.path}:{f.line}:{f.column}: {f.severity} {f.code} {f.name}: {f.message}"
        for f in findings
    ]
    lines.append(summary_line(findings, run))
    return "\n".join(lines) + "\n"
