"""Values given on the command line and to the HTTP API: ``NAME=VALUE`` pairs, joint
positions and mass/COM expectations (``12.3±0.2``, ``12.3+-2%``, ``0,0,0.4±0.005``).

Each parser raises ``argparse.ArgumentTypeError`` with a one-line reason, which argparse
turns into a usage error and the service into a 422.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable

from urdflint.values import parse_number


def pair(sep: str) -> Callable[[str], tuple[str, str]]:
    def parse(text: str) -> tuple[str, str]:
        name, found, value = text.partition(sep)
        if not found or not name.strip():
            raise argparse.ArgumentTypeError(f"expected NAME{sep}VALUE, got {text!r}")
        return name.strip(), value.strip()

    return parse


def number(text: str, what: str) -> float:
    value = parse_number(text.strip())
    if value is None:
        raise argparse.ArgumentTypeError(f"{what} {text!r} is not a number")
    return value


def joint_value(text: str) -> tuple[str, float]:
    name, value = pair("=")(text)
    return name, number(value, f"joint {name!r} value")


def split_tolerance(text: str) -> tuple[str, str | None]:
    for sep in ("±", "+-", "+/-"):
        if sep in text:
            value, _, tolerance = text.partition(sep)
            return value, tolerance
    return text, None


def expect_mass(text: str) -> tuple[float, float | None, float | None]:
    """``12.3`` / ``12.3±0.2`` / ``12.3+-2%`` -> (mass, absolute tolerance, fraction)."""
    value, tolerance = split_tolerance(text)
    mass = number(value, "mass")
    if tolerance is None:
        return mass, None, None
    if tolerance.strip().endswith("%"):
        return mass, None, number(tolerance.strip()[:-1], "tolerance") / 100
    return mass, number(tolerance, "tolerance"), None


def expect_com(text: str) -> tuple[tuple[float, float, float], float | None]:
    value, tolerance = split_tolerance(text)
    parts = value.replace(",", " ").split()
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z[±TOL], got {text!r}")
    com = tuple(number(p, "coordinate") for p in parts)
    return com, (number(tolerance, "tolerance") if tolerance is not None else None)  # type: ignore[return-value]
