"""Did-you-mean for names and keys: an edit distance tuned for typos, and a suggestion only
when one candidate is clearly the closest."""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable


def distance(a: str, b: str) -> int:
    """Optimal-string-alignment edit distance (a transposition counts as one edit)."""
    rows = [list(range(len(b) + 1))]
    for i, ca in enumerate(a, 1):
        row = [i] + [0] * len(b)
        for j, cb in enumerate(b, 1):
            cost = 0 if ca == cb else 1
            row[j] = min(rows[-1][j] + 1, row[j - 1] + 1, rows[-1][j - 1] + cost)
            if i > 1 and j > 1 and ca == b[j - 2] and a[i - 2] == cb:
                row[j] = min(row[j], rows[-2][j - 2] + 1)
        rows.append(row)
    return rows[-1][-1]


def _bag_distance(a: str, b: str) -> int:
    """Characters of one string not matched in the other: never more than the edit distance."""
    ca, cb = Counter(a), Counter(b)
    return max(sum((ca - cb).values()), sum((cb - ca).values()))


def _fold(name: str) -> str:
    return name.lower().replace("_", "").replace("-", "")


def ranked(name: str, candidates: Iterable[str]) -> list[tuple[int, int, str]]:
    """The candidates within typo range of ``name`` (:func:`near_miss`), closest first:
    ``(distance ignoring case and _, exact distance, candidate)``. A fix renames only when
    the first is alone at its distance (the automatic fixes of X007, X013, G001, G006)."""
    return sorted(
        (distance(_fold(name), _fold(c)), distance(name, c), c)
        for c in candidates
        if near_miss(name, [c]) is not None
    )


def same_digits(a: str, b: str) -> bool:
    """Whether two names have the same digits (``mu`` is not a typo of ``mu1``)."""
    return re.findall(r"\d", a) == re.findall(r"\d", b)


def near_miss(name: str, candidates: list[str] | tuple[str, ...] | frozenset[str]) -> str | None:
    """The candidate ``name`` is almost certainly a typo of, else ``None``.

    Same letters ignoring case and ``_`` (``self_collide``/``selfCollide``), or one edit
    away (two for names of 8+ letters) after folding case.
    """
    folded = _fold(name)
    best: tuple[int, str] | None = None
    for candidate in sorted(candidates):
        if candidate == name:
            return None
        other = _fold(candidate)
        if abs(len(other) - len(folded)) > 2:
            continue  # the edit distance is at least the length difference
        d = 0 if other == folded else distance(folded, other)
        limit = 2 if min(len(folded), len(other)) >= 8 else 1
        if d <= limit and (best is None or d < best[0]):
            best = (d, candidate)
    return best[1] if best else None


def suggest(name: str, candidates: list[str] | tuple[str, ...] | frozenset[str]) -> str | None:
    """The closest candidate for a did-you-mean hint (looser than :func:`near_miss`)."""
    folded = _fold(name)
    limit = max(1, len(folded) // 5)
    best: tuple[int, str] | None = None
    for candidate in sorted(candidates):
        other = _fold(candidate)
        if abs(len(other) - len(folded)) > limit:
            continue  # the edit distance is at least the length difference
        if _bag_distance(folded, other) > limit:
            continue  # a cheap lower bound of the edit distance
        d = distance(folded, other)
        if d <= limit and (best is None or d < best[0]):
            best = (d, candidate)
            if d == 0:
                break
    return best[1] if best else None
