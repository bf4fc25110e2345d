"""``path:line:col: severity CODE name: message`` (editors make it clickable), then one
indented ``in macro `m`, called from path:line:col`` line per macro call for xacro input."""

from __future__ import annotations

from collections.abc import Sequence

from urdflint.model.finding import Finding
from urdflint.outputs.formatters.run import RunInfo, summary_line


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    lines: list[str] = []
    for f in findings:
        lines.append(f"{f.path}:{f.line}:{f.column}: {f.severity} {f.code} {f.name}: {f.message}")
        lines.extend(f"    {call}" for call in f.trace)  # xacro: the macro calls, innermost first
    lines.append(summary_line(findings, run))
    return "\n".join(lines) + "\n"
