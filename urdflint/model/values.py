"""Strict number parsing shared by every rule.

URDF numbers are written as decimal floats (``1``, ``-0.5``, ``1e-3``). Python's
``float()`` also takes ``nan``, ``inf`` and ``1_000``, which urdfdom does not, so
the parsing here is explicit. Rules ask for a value and get ``None`` when it is
missing or malformed: reporting malformed numbers is X004's and X005's job, and
every other rule simply does not judge what it cannot read.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lxml import etree

NUMBER_RE = re.compile(r"^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$")
XACRO_RE = re.compile(r"\$\{|\$\(")


@lru_cache(maxsize=8192)
def parse_number(text: str | None) -> float | None:
    """A finite float, or ``None`` when ``text`` is missing or not a URDF number."""
    if text is None:
        return None
    text = text.strip()
    if not NUMBER_RE.fullmatch(text):
        return None
    value = float(text)
    return value if math.isfinite(value) else None


@lru_cache(maxsize=8192)
def parse_numbers(text: str | None) -> tuple[float, ...] | None:
    """All whitespace-separated numbers, or ``None`` if any one is malformed."""
    if text is None:
        return None
    values = tuple(parse_number(part) for part in text.split())
    if any(v is None for v in values):
        return None
    return values  # type: ignore[return-value]


def number(el: etree._Element | None, attr: str, default: float | None = None) -> float | None:
    """``el.get(attr)`` as a number; ``default`` when absent, ``None`` when malformed."""
    if el is None:
        return default
    raw = el.get(attr)
    if raw is None:
        return default
    return parse_number(raw)


def vector(
    el: etree._Element | None, attr: str, size: int = 3, default: tuple[float, ...] | None = None
) -> tuple[float, ...] | None:
    """``el.get(attr)`` as ``size`` numbers; ``default`` when absent, ``None`` when malformed."""
    if el is None:
        return default
    raw = el.get(attr)
    if raw is None:
        return default
    values = parse_numbers(raw)
    if values is None or len(values) != size:
        return None
    return values


def has_xacro(text: str | None) -> bool:
    """True for ``${...}`` / ``$(...)`` left over from an unexpanded xacro file."""
    return text is not None and "$" in text and XACRO_RE.search(text) is not None


def fmt(value: float) -> str:
    """A compact, readable number for messages (``0.001``, ``12.5``, ``1.2e-08``)."""
    return f"{value:.6g}"


XML_ATTRIBUTE = str.maketrans(
    {
        "&": "&amp;",
        "<": "&lt;",
        ">": "&gt;",
        '"': "&quot;",
        "\n": "&#10;",
        "\r": "&#13;",
        "\t": "&#9;",
    }
)


def xml_attribute(text: str) -> str:
    """``text`` escaped for a double-quoted XML attribute value (what ``xml.sax.saxutils``
    does, without importing it: it pulls in urllib, http and email, 30 ms at start-up)."""
    return text.translate(XML_ATTRIBUTE)
