"""The two snippets of a short rule page (``urdflint explain``): the lines of a failing
fixture around what the rule flags, and the same part of the passing fixture most like it.

The fixtures of a rule are mostly one model written twice, so a line diff
(:mod:`difflib`) lines the two files up: the bad snippet is the flagged element (or the
lines around it) widened to the change next to it, and the good snippet is what lines up
with it. When nothing differs there (the fix is elsewhere in the file: a namespace
declared on ``<robot>``, a plugin at the end), the snippets show the flagged lines and
the change related to them, with ``…`` between.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass

from urdflint.engine.examples import Example

CONTEXT = 1  # lines shown on each side of the flagged line, at least
SPAN = 2 * CONTEXT + 1  # lines of the bad snippet, at least
SPAN_MOST = 6  # and at most, by default (a short flagged element is shown whole)
TAG_RE = re.compile(r"(\s*)<([\w:.-]+)")  # an element's indentation and name
WORD_RE = re.compile(r"[A-Za-z_][\w-]{2,}")  # a name in an element or attribute value
PREFIX_RE = re.compile(r"<(\w+):")  # an element's namespace prefix
VALUE_RE = re.compile(r'="([^"]*)"')  # an attribute's value
ELISION = "…"

Op = tuple[str, int, int, int, int]  # difflib's opcode
Span = tuple[int, int]  # lines [start, end)


@dataclass(frozen=True, slots=True)
class Snippet:
    """Some ranges of lines of an example, shown in order with ``…`` where lines are left
    out."""

    example: Example
    spans: tuple[Span, ...]

    def lines(self) -> list[str]:
        every = self.example.lines
        shown: list[str] = []
        previous = 0
        for start, end in self.spans:
            if start > previous:
                shown.append(_indent(every[start]) + ELISION)
            shown += every[start:end]
            previous = end
        if previous < len(every):
            shown.append(_indent(every[previous - 1]) + ELISION)
        return shown


def pair(examples: list[Example], most: int = SPAN_MOST) -> tuple[Snippet, Snippet] | None:
    """The bad snippet (at most ``most`` lines and the elisions when it is one piece) and
    the good one (a line more), or ``None`` unless the rule has a failing fixture with an
    expected finding in it and a passing one."""
    bads = [e for e in examples if e.bad and e.flagged]
    goods = [e for e in examples if not e.bad]
    if not bads or not goods:
        return None
    bad = _preferred(bads)
    good = max(goods, key=lambda g: _likeness(bad, g))
    return _windows(bad, good, most)


def _preferred(bads: list[Example]) -> Example:
    """``bad.*`` when the rule has one, else the first linted with the default settings."""
    for example in bads:
        if _stem(example.name) == "bad":
            return example
    return next((e for e in bads if not e.settings), bads[0])


def _likeness(bad: Example, good: Example) -> tuple[bool, bool, bool, float]:
    """Of the same kind (URDF, SRDF), linted alike, differing near the flagged line, then
    alike in text."""
    flag = bad.flagged[0]
    matcher = difflib.SequenceMatcher(None, bad.lines, good.lines, autojunk=False)
    ops = matcher.get_opcodes()
    differs = any(_gap(op, flag, flag) <= CONTEXT for op in ops if op[0] != "equal")
    ratio = matcher.ratio()
    same_kind = _suffix(bad.name) == _suffix(good.name)
    return same_kind, good.settings == bad.settings, differs, ratio


def _windows(bad: Example, good: Example, most: int) -> tuple[Snippet, Snippet]:
    """The snippets at the first flagged line whose two snippets differ (else the first)."""
    ops = _opcodes(bad, good)
    shown = [_at(bad, good, ops, flag, most) for flag in bad.flagged]
    return next((two for two in shown if two[0].lines() != two[1].lines()), shown[0])


def _at(
    bad: Example, good: Example, ops: list[Op], flag: int, most: int
) -> tuple[Snippet, Snippet]:
    span = _around(bad, ops, flag, most)
    good_span = _aligned(ops, span, flag, len(good.lines), most + 1)
    if bad.lines[slice(*span)] == good.lines[slice(*good_span)]:
        related = _related(bad, good, ops, flag)
        if related is not None:
            return _apart(bad, good, ops, flag, related)
    return Snippet(bad, (span,)), Snippet(good, (good_span,))


def _around(bad: Example, ops: list[Op], flag: int, most: int) -> Span:
    """Lines of ``bad`` around its flagged line: the whole flagged element when it is short,
    widened towards the nearest change when it is close; ``most`` lines at most."""
    low, high = _extent(bad.lines, flag, most)
    changes = [op for op in ops if op[0] != "equal"]
    if changes:
        near = min(changes, key=lambda op: _gap(op, low, high))
        if _gap(near, low, high) <= CONTEXT:
            first, last = _touched(near)
            low = max(min(low, first), flag - CONTEXT)
            high = min(max(high, last), low + most - 1)
    return _whole(_grow((low, high + 1), len(bad.lines), SPAN), len(bad.lines))


def _aligned(ops: list[Op], span: Span, flag: int, size: int, most: int) -> Span:
    """The lines of the good fixture that line up with ``span``: as many as it has at least,
    ``most`` at most (then those nearest the flagged line)."""
    start, end = _grow(_align(ops, *span), size, span[1] - span[0])
    if end - start > most:
        middle = _align(ops, flag, flag + 1)[0]
        start = max(start, min(middle - CONTEXT, end - most))
        end = start + most
    return _whole((start, max(end, start + 1)), size)


def _related(bad: Example, good: Example, ops: list[Op], flag: int) -> Op | None:
    """The change nearest the flagged line that is inside the flagged element, else that
    names what it names: a namespace prefix (``drake`` for ``<drake:...>``) or an
    attribute value (the mimicked joint for a mimic plugin); ``None`` when none does."""
    changes = [op for op in ops if op[0] != "equal"]
    low, high = _extent(bad.lines, flag, len(bad.lines))
    inside = [op for op in changes if _gap(op, low, high) == 0]
    line = bad.lines[flag]
    names = set(PREFIX_RE.findall(line))
    for value in VALUE_RE.findall(line):
        names.update(WORD_RE.findall(value))

    def names_it(op: Op) -> bool:
        text = " ".join(bad.lines[op[1] : op[2]] + good.lines[op[3] : op[4]])
        return bool(names & set(WORD_RE.findall(text)))

    related = inside or [op for op in changes if names_it(op)]
    return min(related, key=lambda op: _gap(op, flag, flag)) if related else None


def _apart(
    bad: Example, good: Example, ops: list[Op], flag: int, change: Op
) -> tuple[Snippet, Snippet]:
    """The flagged line, and the change with one line either side (at most ``SPAN + 1``
    lines of the good fixture's side)."""
    flagged = (flag, flag + 1)
    first, last = _touched(change)
    changed = (max(first - 1, 0), min(last + 2, len(bad.lines)))
    good_flagged = _align(ops, *flagged)
    good_start = max(change[3] - 1, 0)
    good_changed = (good_start, min(max(change[4] + 1, good_start + 1), good_start + SPAN + 1))
    return (
        Snippet(bad, _merged(flagged, changed)),
        Snippet(good, _merged(good_flagged, good_changed)),
    )


def _merged(one: Span, other: Span) -> tuple[Span, ...]:
    first, second = sorted((one, other))
    if second[0] <= first[1]:
        return ((first[0], max(first[1], second[1])),)
    return first, second


def _extent(lines: tuple[str, ...], line: int, most: int) -> tuple[int, int]:
    """The first and last line of the element that opens on ``line`` when it closes within
    ``most`` lines (indented alike), else ``(line, line)``."""
    opened = TAG_RE.match(lines[line])
    if opened is None or lines[line].rstrip().endswith(("/>", f"</{opened.group(2)}>")):
        return line, line
    closing = f"{opened.group(1)}</{opened.group(2)}>"
    for end in range(line + 1, min(line + most, len(lines))):
        if lines[end].startswith(closing):
            return line, end
    return line, line


def _opcodes(bad: Example, good: Example) -> list[Op]:
    matcher = difflib.SequenceMatcher(None, bad.lines, good.lines, autojunk=False)
    return [(tag, i1, i2, j1, j2) for tag, i1, i2, j1, j2 in matcher.get_opcodes()]


def _touched(op: Op) -> tuple[int, int]:
    """The first and last line of the bad fixture a change touches (an insertion touches
    the lines on either side of it)."""
    _, i1, i2, _, _ = op
    return (i1, i2 - 1) if i2 > i1 else (i1 - 1, i1)


def _gap(op: Op, low: int, high: int) -> int:
    """How many lines a change is from lines ``low`` to ``high`` of the bad fixture."""
    first, last = _touched(op)
    return max(0, first - high, low - last)


def _align(ops: list[Op], start: int, end: int) -> Span:
    """The lines of the good fixture that line up with lines ``[start, end)`` of the bad one
    (a changed block lines up with all of its replacement)."""
    good_start = good_end = None
    for tag, i1, i2, j1, j2 in ops:
        if good_start is None and (start < i2 or i1 == i2 == start):
            good_start = j1 + (start - i1) if tag == "equal" else j1
        if end <= i2 and (i2 > i1 or tag == "equal"):
            good_end = j1 + (end - i1) if tag == "equal" else j2
            break
    last = ops[-1][4] if ops else 0
    first = good_start if good_start is not None else last
    return first, good_end if good_end is not None else last


def _grow(span: Span, size: int, lines: int) -> Span:
    """``span`` widened evenly to ``lines`` lines within ``[0, size)``."""
    start, end = span
    while end - start < min(lines, size):
        if (start > 0 and (end - start) % 2 == 0) or end >= size:
            start -= 1
        else:
            end += 1
    return start, end


def _whole(span: Span, size: int) -> Span:
    """Show a single left-out line at either end rather than ``…`` in its place."""
    start, end = span
    return (0 if start == 1 else start), (size if end == size - 1 else end)


def _indent(line: str) -> str:
    return line[: len(line) - len(line.lstrip())]


def _stem(name: str) -> str:
    return name.rsplit(".", 1)[0]


def _suffix(name: str) -> str:
    return name.rsplit(".", 1)[-1]
