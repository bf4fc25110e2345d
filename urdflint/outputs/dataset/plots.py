"""Inline SVG plots for the dataset report: no script, no external resource, all text escaped.

:func:`histogram` draws one distribution of :mod:`.histogram` as bars over its bins, with
a light grid, the count on each bar and a ``<title>`` tooltip per bar; :func:`stacked` is
one horizontal bar split by outcome (the load matrix's rows). Output is deterministic.
"""

from __future__ import annotations

from html import escape
from typing import Any

FONT = "system-ui, -apple-system, Segoe UI, Roboto, Helvetica, Arial, sans-serif"
INK, MUTED, GRID, AXIS = "#1d2939", "#667085", "#eaecf0", "#98a2b3"
BAR, ODD = "#4e5ba6", "#d92d20"  # a bin of suspicious values (mass at or below zero): red
OUTCOME_COLOURS = {
    "loads": "#12b76a",
    "changes": "#f79009",
    "refused": "#f04438",
    "crashes": "#912018",
    "not-installed": "#d0d5dd",
}
WIDTH, HEIGHT = 440, 250
LEFT, RIGHT, TOP = 44, 12, 18
CHAR = 6.2  # estimated advance of an 11 px character


def _a(value: Any) -> str:
    return escape(str(value), quote=True)


def _n(value: float) -> str:
    return f"{value:.1f}".rstrip("0").rstrip(".")


def ticks(peak: int) -> list[int]:
    """Round grid values from 0 to at least ``peak`` (four or five of them)."""
    if peak <= 0:
        return [0, 1]
    step = 1
    for candidate in (1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000, 2000, 5000):
        step = candidate
        if peak / candidate <= 5:
            break
    else:
        while peak / step > 5:
            step *= 10
    top = -(-peak // step) * step
    return list(range(0, top + 1, step))


def histogram(dist: dict[str, Any], *, key: str, title: str, unit: str = "") -> str:
    """One distribution as an SVG bar chart (an empty frame that says so without data)."""
    bins = dist.get("bins") or []
    label = f"{title}: " + ", ".join(f"{b['label']}: {b['count']}" for b in bins)
    head = (
        f'<svg class="plot" id="plot-{_a(key)}" '
        f'data-plot="{_a(key)}" data-bins="{len(bins)}" role="img" aria-label="{_a(label)}" '
        f'viewBox="0 0 {WIDTH} {HEIGHT}" width="{WIDTH}" height="{HEIGHT}" '
        f'font-family="{_a(FONT)}" font-size="11">'
    )
    if not bins:
        text = f'<text x="{WIDTH / 2}" y="{HEIGHT / 2}" text-anchor="middle" fill="{MUTED}">'
        return head + text + "no values in these records</text></svg>"
    longest = max(len(b["label"]) for b in bins)
    slant = (len(bins) > 6 and longest > 3) or longest * CHAR > (WIDTH - LEFT - RIGHT) / len(bins)
    bottom = 24 + (int(longest * CHAR * 0.7) if slant else 0) + (16 if unit else 0)
    plot_h = HEIGHT - TOP - bottom
    grid = ticks(max(b["count"] for b in bins))
    scale = plot_h / grid[-1]
    parts = [head]
    for value in grid:
        y = TOP + plot_h - value * scale
        parts.append(
            f'<line x1="{LEFT}" x2="{WIDTH - RIGHT}" y1="{_n(y)}" y2="{_n(y)}" '
            f'stroke="{GRID if value else AXIS}" stroke-width="1"/>'
            f'<text x="{LEFT - 6}" y="{_n(y + 3.5)}" text-anchor="end" '
            f'fill="{MUTED}">{value}</text>'
        )
    slot = (WIDTH - LEFT - RIGHT) / len(bins)
    for n, b in enumerate(bins):
        parts.append(_bar(b, LEFT + n * slot, slot, TOP + plot_h, scale, slant, unit))
    if unit:
        parts.append(
            f'<text x="{LEFT + (WIDTH - LEFT - RIGHT) / 2}" y="{HEIGHT - 4}" '
            f'text-anchor="middle" fill="{MUTED}">{_a(unit)}</text>'
        )
    parts.append("</svg>")
    return "".join(parts)


def _bar(
    b: dict[str, Any], x: float, slot: float, base: float, scale: float, slant: bool, unit: str
) -> str:
    height = b["count"] * scale
    width = max(slot * 0.78, 1.0)
    left = x + (slot - width) / 2
    colour = ODD if b.get("low") is None and b.get("high") == 0 else BAR
    things = "value" if b["count"] == 1 else "values"
    tip = f"{b['label']}{' ' + unit if unit else ''}: {b['count']} {things}"
    out = [
        f'<g class="bin" data-label="{_a(b["label"])}" data-count="{b["count"]}">'
        f"<title>{_a(tip)}</title>"
        f'<rect x="{_n(left)}" y="{_n(base - height)}" width="{_n(width)}" '
        f'height="{_n(max(height, 0))}" rx="2" fill="{colour}"/>'
    ]
    if b["count"]:
        out.append(
            f'<text x="{_n(x + slot / 2)}" y="{_n(base - height - 4)}" '
            f'text-anchor="middle" fill="{INK}" font-size="10">{b["count"]}</text>'
        )
    cx, ty = x + slot / 2, base + 14
    if slant:
        out.append(
            f'<text x="{_n(cx)}" y="{_n(ty)}" text-anchor="end" fill="{MUTED}" '
            f'transform="rotate(-40 {_n(cx)} {_n(ty)})">{_a(b["label"])}</text>'
        )
    else:
        out.append(
            f'<text x="{_n(cx)}" y="{_n(ty)}" text-anchor="middle" '
            f'fill="{MUTED}">{_a(b["label"])}</text>'
        )
    out.append("</g>")
    return "".join(out)


def stacked(counts: dict[str, int], *, key: str, width: int = 220, height: int = 14) -> str:
    """One horizontal bar split by outcome, each part as wide as its share of files."""
    total = sum(counts.values())
    parts = [
        f'<svg class="share" data-share="{_a(key)}" '
        f'viewBox="0 0 {width} {height}" width="{width}" height="{height}" role="img" '
        f'aria-label="{_a(", ".join(f"{k}: {v}" for k, v in counts.items()))}">'
        f'<rect width="{width}" height="{height}" rx="3" fill="#f2f4f7"/>'
    ]
    x = 0.0
    for outcome, count in counts.items():
        if not count or not total:
            continue
        part = width * count / total
        parts.append(
            f'<rect class="part" data-outcome="{_a(outcome)}" x="{_n(x)}" y="0" '
            f'width="{_n(part)}" height="{height}" '
            f'fill="{OUTCOME_COLOURS.get(outcome, MUTED)}">'
            f"<title>{_a(outcome)}: {count}</title></rect>"
        )
        x += part
    parts.append("</svg>")
    return "".join(parts)
