"""The settings of the statics (D rules, ``urdflint info --statics``): gravity and payload.

``--gravity X,Y,Z`` (m/s², in the root link's frame) and ``--payload KG[@LINK]`` on the
command line of ``check`` and ``info``; ``[tool.urdflint.statics]`` in the configuration::

    [tool.urdflint.statics]
    payload = "2@tool0"          # or a number of kg: at the end of the longest chain
    gravity = [0, 0, -9.81]      # m/s², root link frame (a wall-mounted arm: [9.81, 0, 0])

The command line wins over the configuration, key by key.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass, replace
from typing import Any

from urdflint.model.values import fmt, parse_number

Vec = tuple[float, float, float]
EARTH: Vec = (0.0, 0.0, -9.81)
KEYS = ("payload", "gravity")


@dataclass(frozen=True)
class StaticsSettings:
    """Gravity in the root link's frame (m/s²), and a point mass at a link (kg).

    ``payload_link`` ``None`` means the end of the longest chain (see
    :func:`urdflint.engine.statics_model.tool_link`).
    """

    gravity: Vec = EARTH
    payload: float = 0.0
    payload_link: str | None = None

    def describe(self) -> str:
        """``2 kg at 'tool0'`` (or ``no payload``) for messages."""
        if not self.payload:
            return "no payload"
        where = f"'{self.payload_link}'" if self.payload_link else "the end of the longest chain"
        return f"{fmt(self.payload)} kg at {where}"


MAX_PAYLOAD = 1e6  # kg: far beyond any robot, and the torques stay finite
MAX_GRAVITY = 1e3  # m/s²: a hundred g


def payload(text: str) -> tuple[float, str | None]:
    """``2`` / ``2@tool0`` / ``0.5 @ wrist_3_link`` -> (kg, link or ``None``)."""
    mass_text, at, link = str(text).partition("@")
    mass = parse_number(mass_text.strip())
    if mass is None or not math.isfinite(mass) or mass < 0:
        raise ValueError(f"payload {text!r}: expected KG[@LINK] with KG a mass >= 0")
    if mass > MAX_PAYLOAD:
        raise ValueError(f"payload {text!r}: more than {MAX_PAYLOAD:g} kg")
    link = link.strip()
    if at and not link:
        raise ValueError(f"payload {text!r}: no link after @")
    return mass, (link or None)


def gravity(value: Any) -> Vec:
    """``0,0,-9.81`` (or ``[0, 0, -9.81]``) -> a vector of three finite numbers."""
    parts = value if isinstance(value, list | tuple) else str(value).replace(",", " ").split()
    numbers = [_number(p) for p in parts]
    if len(numbers) != 3 or any(n is None for n in numbers):
        raise ValueError(f"gravity {value!r}: expected X,Y,Z in m/s² (e.g. 0,0,-9.81)")
    found = (float(numbers[0]), float(numbers[1]), float(numbers[2]))  # type: ignore[arg-type]
    if math.hypot(*found) > MAX_GRAVITY:
        raise ValueError(f"gravity {value!r}: stronger than {MAX_GRAVITY:g} m/s²")
    return found


def _number(value: Any) -> float | None:
    if isinstance(value, bool):
        return None
    found = float(value) if isinstance(value, int | float) else parse_number(str(value).strip())
    return found if found is not None and math.isfinite(found) else None


DEFAULT = StaticsSettings()


def read(data: dict[str, Any], error: type[Exception]) -> StaticsSettings:
    """The ``statics`` table of a configuration mapping (defaults when it has none)."""
    return table(data["statics"], error) if "statics" in data else DEFAULT


def table(value: Any, error: type[Exception]) -> StaticsSettings:
    """``[tool.urdflint.statics]`` validated; ``error`` is raised naming the key."""
    if not isinstance(value, dict):
        raise error("'statics' must be a table (payload, gravity)")
    unknown = sorted(set(value) - set(KEYS))
    if unknown:
        raise error(f"unknown configuration key 'statics.{unknown[0]}' (known: {', '.join(KEYS)})")
    found = StaticsSettings()
    try:
        if "payload" in value:
            raw = value["payload"]
            if isinstance(raw, bool) or not isinstance(raw, int | float | str):
                raise ValueError('payload must be KG or "KG@LINK"')
            mass, link = payload(str(raw))
            found = replace(found, payload=mass, payload_link=link)
        if "gravity" in value:
            if not isinstance(value["gravity"], list):
                raise ValueError("gravity must be [x, y, z] in m/s²")
            found = replace(found, gravity=gravity(value["gravity"]))
    except ValueError as exc:
        raise error(f"'statics': {exc}") from None
    return found


# -- the command line ------------------------------------------------------------------------


def payload_option(text: str) -> tuple[float, str | None]:
    try:
        return payload(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def gravity_option(text: str) -> Vec:
    try:
        return gravity(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def add_options(parser: argparse.ArgumentParser) -> None:
    """``--payload`` and ``--gravity`` (``check`` and ``info``)."""
    parser.add_argument(
        "--payload",
        type=payload_option,
        metavar="KG[@LINK]",
        help="statics (D rules, info --statics): a point mass of KG kg at LINK (default: the "
        "end of the longest chain, or the hand it ends in); statics.payload in the configuration",
    )
    parser.add_argument(
        "--gravity",
        type=gravity_option,
        metavar="X,Y,Z",
        help="statics: gravity in m/s² in the root link's frame (default 0,0,-9.81; a "
        "wall-mounted arm: 9.81,0,0; a value that starts with - takes =: --gravity=-9.81,0,0); "
        "statics.gravity in the configuration",
    )


def apply(
    settings: StaticsSettings, payload: tuple[float, str | None] | None, gravity: Vec | None
) -> StaticsSettings:
    """``settings`` with ``--payload`` and ``--gravity`` applied (they win)."""
    if payload is not None:
        settings = replace(settings, payload=payload[0], payload_link=payload[1])
    if gravity is not None:
        settings = replace(settings, gravity=gravity)
    return settings
