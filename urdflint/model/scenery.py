"""Scenery: a terrain, a ground plane, stairs or a whole scene written as a URDF.

Simulators load such files beside the robot (PyBullet's ``plane.urdf`` and ``terrain.urdf``,
a quadruped's ramps): they are many metres across, and a mesh over 10 m is no sign of a
unit error there (C006). :func:`scenery` says why a mesh belongs to scenery, if it does:

- the model is static: no joint moves (every joint is ``fixed``, or there is none), and
  either nothing has mass (PyBullet keeps a massless base where it is) or the root link is
  the world (``world``, ``map``, ``ground``...), to which everything is welded;
- or the mesh's link, or the mesh file itself, is named like scenery: one of the words of
  :data:`WORDS` in the name (``terrain_link``, ``groundPlane``, ``ramps.obj``).

Names are split into words at non-letters and at a lower-case letter followed by a capital
(``terrainLink`` is ``terrain``, ``link``), so ``airplane_wing`` or ``floorboard_bracket``
do not count.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from urdflint.model.document import Document, Link

WORDS = frozenset(
    {
        "ground",
        "terrain",
        "floor",
        "ramp",
        "ramps",
        "stair",
        "stairs",
        "staircase",
        "scene",
        "world",
        "plane",
        "heightfield",
        "heightmap",
        "arena",
        "slope",
    }
)
WORLD = frozenset({"world", "map", "ground", "terrain", "floor", "scene"})  # a root welded to it


def words(name: str | None) -> set[str]:
    """The lower-case words of ``name``: ``terrainLink`` -> {``terrain``, ``link``}."""
    spaced = re.sub(r"([a-z])([A-Z])", r"\1 \2", name or "")
    return set(re.findall(r"[a-z]+", spaced.lower()))


def static_model(doc: Document) -> bool:
    """No joint moves, and nothing has mass or the root is the world (see the module)."""
    if not doc.links or any((j.type or "").strip() != "fixed" for j in doc.joints):
        return False
    if not any(_mass(link) > 0 for link in doc.links):
        return True
    root = doc.graph.root
    return bool(words(root) & WORLD)


def scenery(doc: Document, link: str | None, filename: str) -> str | None:
    """Why the mesh ``filename`` of ``link`` is scenery (``None``: it is a robot part)."""
    memo = doc.memo.get("scenery.static")
    if memo is None:
        memo = doc.memo["scenery.static"] = static_model(doc)
    if memo:
        return "the model is static scenery: no joint moves"
    if words(link) & WORDS:
        return f"link {link!r} is named like scenery"
    stem = filename.replace("\\", "/").rsplit("/", 1)[-1].rsplit(".", 1)[0]
    if words(stem) & WORDS:
        return f"mesh {stem!r} is named like scenery"
    return None


def _mass(link: Link) -> float:
    inertial = link.inertial
    mass = inertial.find("mass") if inertial is not None else None
    try:
        return float((mass.get("value") if mass is not None else None) or "0")
    except ValueError:
        return 0.0
