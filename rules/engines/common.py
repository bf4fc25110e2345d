"""What the E rules share: the engines' outcomes for a document, and their names."""

from __future__ import annotations

from typing import Any

from urdflint.model.document import Document
from urdflint.model.providers import provided

LABELS = {"mujoco": "MuJoCo", "pybullet": "PyBullet", "drake": "Drake", "pinocchio": "Pinocchio",
          "sdformat": "sdformat (Gazebo)"}  # fmt: skip
# engines that are not Python packages: how to install them instead of EXTRA
INSTALL = {"sdformat": "install libsdformat-dev (sdformat12, found by pkg-config) and g++"}


def outcomes(doc: Document) -> list[Any]:
    """One outcome per engine named by ``--confirm`` (none without it: nothing runs)."""
    if not getattr(doc.settings, "confirm", ()):
        return []
    return list(provided("confirmation", doc))


def label(engine: str) -> str:
    return LABELS.get(engine, engine)


def install(engine: str) -> str:
    """How to install ``engine``."""
    from urdflint.model.optional import install_command

    return INSTALL.get(engine) or install_command("engines")
