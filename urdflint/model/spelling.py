"""Did-you-mean for names and keys: an edit distance tuned for typos, and a suggestion only
when one candidate is clearly the closest."""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable
from functools import lru_cache


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


def bounded_distance(a: str, b: str, limit: int) -> int:
    """:func:`distance` when it is at most ``limit``, else a number above ``limit`` (the
    rows are abandoned as soon as no path can come back under it)."""
    if abs(len(a) - len(b)) > limit:
        return limit + 1  # the distance is at least the length difference
    before: list[int] = []
    rows = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        row = [i] + [0] * len(b)
        for j, cb in enumerate(b, 1):
            cost = 0 if ca == cb else 1
            row[j] = min(rows[j] + 1, row[j - 1] + 1, rows[j - 1] + cost)
            if i > 1 and j > 1 and ca == b[j - 2] and a[i - 2] == cb:
                row[j] = min(row[j], before[j - 2] + 1)
        # a cell is at least the smaller of the row above's minimum and (through a
        # transposition) the minimum two rows up plus one: past the limit on both, every
        # later row is too
        if min(row) > limit and min(rows) >= limit:
            return limit + 1
        before, rows = rows, row
    return rows[-1]


def _bag_distance(a: str, b: str) -> int:
    """Characters of one string not matched in the other: never more than the edit distance."""
    ca, cb = Counter(a), Counter(b)
    return max(sum((ca - cb).values()), sum((cb - ca).values()))


@lru_cache(maxsize=8192)
def _fold(name: str) -> str:
    return name.lower().replace("_", "").replace("-", "")


def ranked(name: str, candidates: Iterable[str]) -> list[tuple[int, int, str]]:
    """The candidates within typo range of ``name`` (:func:`near_miss`), closest first:
    ``(distance ignoring case and _, exact distance, candidate)``. A fix renames only when
    the first is alone at its distance (the automatic fixes of X007, X013, G001, G006)."""
    folded = _fold(name)
    found = []
    for candidate in candidates:
        if candidate == name:
            continue
        other = _fold(candidate)
        d = _typo(folded, other)
        if d is not None:
            found.append((d, distance(name, candidate), candidate))
    return sorted(found)


def same_digits(a: str, b: str) -> bool:
    """Whether two names have the same digits (``mu`` is not a typo of ``mu1``)."""
    return re.findall(r"\d", a) == re.findall(r"\d", b)


def near_miss(name: str, candidates: list[str] | tuple[str, ...] | frozenset[str]) -> str | None:
    """The candidate ``name`` is almost certainly a typo of, else ``None``.

    Same letters ignoring case and ``_`` (``self_collide``/``selfCollide``), or one edit
    away (two for names of 8+ letters) after folding case.
    """
    if name in candidates:
        return None
    folded = _fold(name)
    best: tuple[int, str] | None = None
    for candidate in sorted(candidates):
        d = _typo(folded, _fold(candidate))
        if d is not None and (best is None or d < best[0]):
            best = (d, candidate)
    return best[1] if best else None


@lru_cache(maxsize=65536)  # the same keys meet the same candidates in file after file
def _typo(folded: str, other: str) -> int | None:
    """The distance between two folded names when it is within typo range, else ``None``."""
    if other == folded:
        return 0
    limit = 2 if min(len(folded), len(other)) >= 8 else 1
    d = bounded_distance(folded, other, limit)
    return d if d <= limit else None


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
        d = bounded_distance(folded, other, limit)
        if d <= limit and (best is None or d < best[0]):
            best = (d, candidate)
            if d == 0:
                break
    return best[1] if best else None
