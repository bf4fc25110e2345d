"""Distributions of one number over a dataset: min, median, max and a histogram.

Bins are half-open ``[low, high)`` and chosen to be read at a glance: one per integer for
small counts, else 1-2-5 widths (``0-49``, ``50-99``); a quantity whose positive values
span two decades or more (the mass of a gripper finger and of a humanoid) gets
logarithmic bins (1-2-5 steps per decade up to three decades, 1-3 up to six, whole
decades past that), with
the values at or below zero counted in a first ``≤ 0`` bin.
"""

from __future__ import annotations

import math
import statistics
from bisect import bisect_right
from collections.abc import Iterable
from typing import Any

MAX_BINS = 12
DECADES_FOR_LOG = 2.0  # max / min >= 100: log bins
STEPS = (1, 2, 5)


def describe(
    values: Iterable[float | int | None], *, unit: str = "", integer: bool = False
) -> dict[str, Any]:
    """The distribution of ``values`` (``None`` and non-finite values left out)."""
    found = sorted(
        float(v)
        for v in values
        if isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
    )
    data: dict[str, Any] = {
        "unit": unit,
        "count": len(found),
        "min": None,
        "median": None,
        "max": None,
        "scale": "linear",
        "bins": [],
    }
    if not found:
        return data
    data["min"], data["max"] = _plain(found[0], integer), _plain(found[-1], integer)
    data["median"] = _plain(statistics.median(found), integer and len(found) % 2 == 1)
    positive = [v for v in found if v > 0]
    if not integer and positive and math.log10(positive[-1] / positive[0]) >= DECADES_FOR_LOG:
        data["scale"] = "log"
        data["bins"] = _log_bins(found, positive)
    elif integer:
        data["bins"] = _integer_bins(found)
    else:
        data["bins"] = _linear_bins(found)
    return data


def _plain(value: float, integer: bool) -> float | int:
    return int(value) if integer and value == int(value) else round(value, 6)


def nice(width: float) -> float:
    """The smallest 1, 2 or 5 times a power of ten that is at least ``width``."""
    if width <= 0:
        return 1.0
    power = math.floor(math.log10(width))
    for step in (*STEPS, 10):
        candidate = _number(step, power)
        if candidate >= width * (1 - 1e-12):
            return candidate
    return _number(10, power)  # pragma: no cover (10 always fits)


def _number(mantissa: int, power: int) -> float:
    """``mantissa * 10**power`` without binary noise (0.2, not 0.20000000000000001)."""
    return float(f"{mantissa}e{power}")


def _count(values: list[float], lows: list[float]) -> list[int]:
    counts = [0] * len(lows)
    for v in values:
        counts[max(0, bisect_right(lows, v) - 1)] += 1
    return counts


def _integer_bins(values: list[float]) -> list[dict[str, Any]]:
    low, high = int(values[0]), int(values[-1])
    width = 1 if high - low < 15 else int(nice((high - low + 1) / MAX_BINS))
    start = (low // width) * width
    lows = list(range(start, high + 1, width))
    bins = []
    for edge, count in zip(lows, _count(values, [float(x) for x in lows]), strict=True):
        label = str(edge) if width == 1 else f"{edge}–{edge + width - 1}"
        bins.append({"low": edge, "high": edge + width, "label": label, "count": count})
    return bins


def _linear_bins(values: list[float]) -> list[dict[str, Any]]:
    low, high = values[0], values[-1]
    if high == low:
        return [{"low": low, "high": high, "label": _text(low), "count": len(values)}]
    width = nice((high - low) / 10)
    first = math.floor(low / width)
    lows = []
    n = first
    while not lows or lows[-1] + width <= high:
        lows.append(round(n * width, 12))
        n += 1
    counts = _count(values, lows)
    return [
        {
            "low": edge,
            "high": round(edge + width, 12),
            "label": f"{_text(edge)}–{_text(round(edge + width, 12))}",
            "count": count,
        }
        for edge, count in zip(lows, counts, strict=True)
    ]


def log_edges(low: float, high: float) -> list[float]:
    """The log bins' edges from the one at or below ``low`` to the first above ``high``."""
    decades = math.log10(high) - math.log10(low)
    steps = STEPS if decades <= 3 else (1, 3) if decades <= 6 else (1,)
    edges: list[float] = []
    power = math.floor(math.log10(low))
    while not edges or edges[-1] <= high:
        edges.extend(_number(s, power) for s in steps)
        power += 1
    edges = [e for e in edges if e <= high] + [next(e for e in edges if e > high)]
    while len(edges) > 2 and edges[1] <= low:
        edges.pop(0)
    return edges


def _log_bins(values: list[float], positive: list[float]) -> list[dict[str, Any]]:
    bins: list[dict[str, Any]] = []
    below = len(values) - len(positive)
    if below:
        bins.append({"low": None, "high": 0, "label": "≤ 0", "count": below})
    edges = log_edges(positive[0], positive[-1])
    counts = _count(positive, edges[:-1])
    for low, high, count in zip(edges, edges[1:], counts, strict=False):
        bins.append(
            {"low": low, "high": high, "label": f"{_text(low)}–{_text(high)}", "count": count}
        )
    return bins


def _text(value: float) -> str:
    """A bin edge as people write it: ``0.5``, ``20``, ``1e+04`` past six figures."""
    return f"{value:g}"
