"""``path:line:col: severity CODE name: message`` (editors make it clickable), then one
indented ``in macro `m`, called from path:line:col`` line per macro call for xacro input.

Unless the run shows infos (``--show-info``, ``--fail-on info``), infos are summarised in
one line per run, most frequent rule first; machine formats always carry every finding.

``--output-format concise`` (the default) writes the findings of one rule at one source
location (a macro line instantiated N times) as one line: the first finding, then
`` ×N (joints a, b, …)``. ``full`` writes each finding with its call chain, its per-target
effects and the source line it points to. ``--statistics`` writes one row per rule instead
(:mod:`urdflint.outputs.formatters.statistics`); ``--quiet`` only the findings.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Sequence
from dataclasses import replace

from urdflint.engine.instances import NAME_STEP_RE
from urdflint.model.finding import Finding, Severity
from urdflint.outputs import matrix_text
from urdflint.outputs.formatters.run import RunInfo, summary_line, targets_lines

MAX_CODES = 6  # rules named in the info summary line
MAX_NAMES = 5  # element names on a grouped line; the rest are "…"


def render(findings: Sequence[Finding], run: RunInfo) -> str:
    if run.statistics:
        from urdflint.outputs.formatters import statistics

        lines = statistics.table(findings)
        hidden: list[Finding] = []
    else:
        lines, hidden = listed(findings, run)
    if hidden and not run.quiet:
        lines.append(info_summary(hidden))
    if run.matrix:
        lines.extend(matrix_text.table(run.matrix))
    if not run.quiet:
        fixable = None if run.statistics else fixable_line(findings)
        if fixable:
            lines.append(fixable)
        if not run.statistics:
            lines.extend(targets_lines(run))
        lines.append(summary_line(findings, run))
    return "\n".join(lines) + "\n" if lines else ""


def listed(findings: Sequence[Finding], run: RunInfo) -> tuple[list[str], list[Finding]]:
    """The lines of the findings shown, and the infos left for the summary line."""
    shown: list[Finding] = []
    hidden: list[Finding] = []
    for f in findings:
        (hidden if f.severity is Severity.INFO and not run.show_info else shown).append(f)
    # each finding's per-target line when the user chose several targets; for inferred or
    # assumed ones the targets line says which, and --matrix sums the effects up
    chosen = all(t.get("how", "given") == "given" for t in run.targets.values() if t)
    lines: list[str] = []
    if run.output_format == "full":
        from urdflint.outputs.formatters.excerpt import Sources

        sources = Sources(run.unread)
        for f in shown:
            lines.extend(entry([f], True))  # every finding's effects
            lines.extend(sources.excerpt(f.path, f.line, f.column))
        return lines, hidden
    for group in groups(shown):
        lines.extend(entry(group, chosen))
    return lines, hidden


def groups(findings: Sequence[Finding]) -> list[list[Finding]]:
    """The findings of one rule at one source location (path, line, column, code) together,
    in the order of each group's first finding."""
    found: dict[tuple[str, int, int, str], list[Finding]] = {}
    for f in findings:
        found.setdefault((f.path, f.line, f.column, f.code), []).append(f)
    return list(found.values())


def entry(group: Sequence[Finding], chosen: bool) -> list[str]:
    """A group's lines: its first finding (with `` ×N (names)`` for several), its macro call
    chain (with the number of call sites when they differ) and its per-target effects."""
    f = group[0]
    severity = max(g.severity for g in group)
    if severity != f.severity:
        f = replace(f, severity=severity)
    marks = {mark(g) for g in group}
    shown = next((m for m in (" [fix]", " [unsafe fix]") if m in marks), "")
    lines = [f"{f.path}:{f.line}:{f.column}: {f.severity} {f.code} {f.name}: {f.message}"]
    lines[0] += group_note(group) + shown
    lines.extend(f"    {call}" for call in f.trace)  # xacro: the macro calls, innermost first
    sites = len({g.trace for g in group})
    if sites > 1:
        lines.append(f"    {sites} call sites in all (--output-format full lists each)")
    effects = matrix_text.effects_line(f) if chosen else None
    if effects:
        lines.append(f"    {effects}")
    return lines


def group_note(group: Sequence[Finding]) -> str:
    """`` ×14 (links a, b, c, d, e, …)``: how many findings one line stands for, and the
    kind and names of their elements (``elements`` when the kinds differ; no names when the
    first finding's message already names them all)."""
    if len(group) < 2:
        return ""
    named = [_named(f.element) for f in group]
    names = list(dict.fromkeys(n[1] for n in named if n is not None))
    if all(_mentions(group[0].message, name) for name in names):
        return f" ×{len(group)}"
    kinds = {n[0] if n is not None else None for n in named}
    kind = kinds.pop() if len(kinds) == 1 else None
    plural = kind + ("es" if kind.endswith(("s", "x")) else "s") if kind else "elements"
    shown = ", ".join(names[:MAX_NAMES]) + (", …" if len(names) > MAX_NAMES else "")
    return f" ×{len(group)} ({plural} {shown})"


def _mentions(message: str, name: str) -> bool:
    """Whether ``message`` names ``name`` (as a whole word, not inside a longer name)."""
    return re.search(rf"(?<![\w.-]){re.escape(name)}(?![\w.-])", message) is not None


def _named(element: str) -> tuple[str, str] | None:
    """The kind and name of the deepest named step of an element path."""
    steps = NAME_STEP_RE.findall(element)
    if not steps:
        return None
    tag, single, double = steps[-1]
    return tag.rpartition(":")[2], single or double


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
