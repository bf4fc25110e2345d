"""The prose of a short rule page (``urdflint explain``): each section of the rule's
documentation cut to a few lines, at a paragraph, list item or sentence, never in a word
unless one sentence is longer than the room.
"""

from __future__ import annotations

import re
import textwrap

WIDTH = 88  # the width a paragraph is rewrapped to when it is cut
# a sentence ends at ., ! or ? and a space, but not after "e.g." or "i.e."
SENTENCE_RE = re.compile(r"(?<!\be\.g\.)(?<!\bi\.e\.)(?<=[.!?])\s+")
ITEM_RE = re.compile(r"\s*(?:[-*]|\d+\.)\s")
FLOOR = 2  # lines every section keeps, when it has them


def fit(texts: list[str], room: int, caps: list[int]) -> list[list[str]]:
    """``texts`` cut to ``room`` lines in all: each keeps ``FLOOR`` lines, and the lines
    left go one at a time to the sections in order, each up to its cap."""
    needs = [len(condense(text, cap)) for text, cap in zip(texts, caps, strict=True)]
    given = [min(need, FLOOR) for need in needs]
    spare = room - sum(given)
    while spare > 0 and given != needs:
        for index, need in enumerate(needs):
            if spare > 0 and given[index] < need:
                given[index] += 1
                spare -= 1
    return [condense(text, most) for text, most in zip(texts, given, strict=True)]


def condense(text: str, most: int) -> list[str]:
    """The first paragraphs and list items of ``text`` that fit in ``most`` lines, then as
    many sentences of the next as fit; `` …`` ends a cut text. Code blocks are left out."""
    taken: list[list[str]] = []
    for unit in units(text):
        if unit[0].startswith("```"):
            continue
        room = most - sum(map(len, taken))
        if len(unit) <= room:
            taken.append(unit)
            continue
        taken.append(sentences(unit, room))
        return _ended(taken)
    return [line for unit in taken for line in unit]


def units(text: str) -> list[list[str]]:
    """The paragraphs, list items and fenced code blocks of ``text``, in order."""
    found: list[list[str]] = []
    fenced = False
    for line in text.strip().splitlines():
        if fenced:
            found[-1].append(line)
            fenced = not line.startswith("```")
        elif line.startswith("```"):
            found.append([line])
            fenced = True
        elif not line.strip():
            found.append([])
        elif found and not (found[-1] and (ITEM_RE.match(line) or found[-1][0].startswith("```"))):
            found[-1].append(line)  # the paragraph or item goes on (or starts after a blank)
        else:
            found.append([line])
    return [unit for unit in found if unit]


def sentences(unit: list[str], room: int) -> list[str]:
    """As many whole sentences of a paragraph or list item as fit in ``room`` lines once
    rewrapped; the words that fit when not even the first sentence does."""
    if room <= 0:
        return []
    marker = ITEM_RE.match(unit[0])
    first = marker.group(0) if marker else ""
    joined = " ".join(line.strip() for line in unit)[len(first.strip()) :].strip()
    indent = " " * len(first)

    def wrap(words: str) -> list[str]:
        return textwrap.wrap(
            words, WIDTH, initial_indent=first, subsequent_indent=indent, break_on_hyphens=False
        )

    kept = ""
    for sentence in SENTENCE_RE.split(joined):
        candidate = f"{kept} {sentence}".strip()
        if len(wrap(candidate)) > room:
            break
        kept = candidate
    if kept:
        return wrap(kept)
    return wrap(joined)[:room]


def _ended(taken: list[list[str]]) -> list[str]:
    """A cut text: without an introduction whose list was cut away (unless it is all there
    is), and with `` …``."""
    taken = [unit for unit in taken if unit]
    while len(taken) > 1 and taken[-1][-1].rstrip().endswith(":"):
        taken.pop()
    lines = [line for unit in taken for line in unit]
    if lines:
        lines[-1] = lines[-1].rstrip() + " …"
    return lines
