"""One defect, one finding: merge the findings a macro line produces once per instance.

A defect written in a macro body that is instantiated N times yields N findings at the
same source line, differing only in the instance's names (``left_finger``,
``right_finger``). They become one finding that names the instances. Instances whose
messages differ in anything but names (a bad value passed by only some calls, different
values per call) stay separate, each with its own call chain.
"""

from __future__ import annotations

import re
from dataclasses import replace

from urdflint.model.finding import Finding

NAME_STEP_RE = re.compile(r"([\w:]+)\[@(?:name|reference)=(?:'([^']*)'|\"([^\"]*)\")\]")
QUOTED_NAME_RE = re.compile(r"'[^'/\s]*'")  # a quoted identifier (a name, not a file path)
HINT_RE = re.compile(r" \(did you mean [^)]*\)")  # a did-you-mean some instances get
MAX_NAMED = 6  # instances named in the message; the rest are counted


def _instance(finding: Finding) -> tuple[str, str] | None:
    """The instance's kind and name: the deepest named step of the element path."""
    steps = NAME_STEP_RE.findall(finding.element)
    if not steps:
        return None
    tag, single, double = steps[-1]
    return tag.rpartition(":")[2], single or double


def _shape(finding: Finding) -> str:
    """The message with quoted names masked: equal shapes differ only in names."""
    return QUOTED_NAME_RE.sub("'…'", HINT_RE.sub("", finding.message))


def _plural(kind: str) -> str:
    return kind + ("es" if kind.endswith(("s", "x")) else "s")


def merge(findings: list[Finding]) -> list[Finding]:
    """Findings with a macro call chain, grouped by code, source position and message shape."""
    groups: dict[tuple[str, int, int, str, str], list[Finding]] = {}
    out: list[Finding] = []
    for finding in findings:
        if not finding.trace:
            out.append(finding)
            continue
        key = (finding.path, finding.line, finding.column, finding.code, _shape(finding))
        groups.setdefault(key, []).append(finding)
    for group in groups.values():
        out.append(group[0] if len(group) == 1 else _merged(group))
    out.sort(key=Finding.sort_key)
    return out


def _merged(group: list[Finding]) -> Finding:
    first = group[0]
    instances = [_instance(f) for f in group]
    names = list(dict.fromkeys(i[1] for i in instances if i is not None))
    kinds = {i[0] for i in instances if i is not None}
    if len(names) < 2:
        note = f" ({len(group)} instances of this macro line)"
    else:
        kind = _plural(kinds.pop()) + " " if len(kinds) == 1 else ""
        shown = ", ".join(names[:MAX_NAMED])
        more = f" and {len(names) - MAX_NAMED} more" if len(names) > MAX_NAMED else ""
        note = f" (for {kind}{shown}{more})"
    return replace(first, message=first.message + note, severity=max(f.severity for f in group))


def across_files(findings: list[Finding]) -> list[Finding]:
    """A run's findings with each defect once: entry files that include the same macro or
    file report its defects once (exact repeats dropped, then instances merged)."""
    first: dict[tuple[str, int, int, str, str], Finding] = {}
    for f in findings:
        first.setdefault((f.path, f.line, f.column, f.code, f.message), f)
    unique = list(first.values())
    return merge(unique)
