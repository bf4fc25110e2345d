"""``path:line:col: severity CODE name: message`` (editors make it clickable), then one
indented ``in macro `m`, called from path:line:col`` line per macro call for xacro input.

Unless the run shows infos (``--show-info``, ``--fail-on info``), infos are summarised in
one line per run, most frequent rule first; machine formats always carry every finding.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

from urdflint.model.finding import Finding, Severity
from urdflint.outputs import matrix_text
from urdflint.outputs.formatters.run import RunInfo, summary_line, targets_lines

MAX_CODES = 6  # rules named in the info summary line


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    lines: list[str] = []
    hidden: list[Finding] = []
    # each finding's per-target line when the user chose several targets; for inferred or
    # assumed ones the targets line says which, and --matrix sums the effects up
    chosen = all(t.get("how", "given") == "given" for t in run.targets.values() if t)
    for f in findings:
        if f.severity is Severity.INFO and not run.show_info:
            hidden.append(f)
            continue
        lines.append(
            f"{f.path}:{f.line}:{f.column}: {f.severity} {f.code} {f.name}: {f.message}{mark(f)}"
        )
        lines.extend(f"    {call}" for call in f.trace)  # xacro: the macro calls, innermost first
        effects = matrix_text.effects_line(f) if chosen else None
        if effects:
            lines.append(f"    {effects}")
    if hidden:
        lines.append(info_summary(hidden))
    if run.matrix:
        lines.extend(matrix_text.table(run.matrix))
    fixable = fixable_line(findings)
    if fixable:
        lines.append(fixable)
    lines.extend(targets_lines(run))
    lines.append(summary_line(findings, run))
    return "\n".join(lines) + "\n"


def info_summary(infos: Sequence[Finding]) -> str:
    """``3 infos not shown: J011 ×2, C001 ×1 (--show-info lists them)``."""
    counts = Counter(f.code for f in infos).most_common()
    shown = ", ".join(f"{code} ×{count}" for code, count in counts[:MAX_CODES])
    if len(counts) > MAX_CODES:
        shown += f", {len(counts) - MAX_CODES} more rules"
    noun = "info" if len(infos) == 1 else "infos"
    return f"{len(infos)} {noun} not shown: {shown} (--show-info lists them)"


def mark(finding: Finding) -> str:
    """`` [fix]`` or `` [unsafe fix]`` after a finding that ``urdflint fix`` can repair."""
    fix = finding.autofix
    if fix is None or fix.unavailable or not fix.edits:
        return ""
    return " [fix]" if fix.applicability == "safe" else " [unsafe fix]"


def fixable_line(findings: Sequence[Finding]) -> str | None:
    """``3 fixable with urdflint fix (2 more with --unsafe-fixes)``."""
    ready = [f.autofix for f in findings if f.autofix is not None and not f.autofix.unavailable]
    safe = sum(1 for fix in ready if fix.applicability == "safe")
    unsafe = len(ready) - safe
    if not ready:
        return None
    if not safe:
        return f"{unsafe} fixable with urdflint fix --unsafe-fixes"
    more = f" ({unsafe} more with --unsafe-fixes)" if unsafe else ""
    return f"{safe} fixable with urdflint fix{more}"
