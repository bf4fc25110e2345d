"""Optional dependencies: whether one is installed, and which extra installs it."""

from __future__ import annotations

import importlib.util
from functools import cache

EXTRAS = {"numpy": "model", "pinocchio": "dynamics", "trimesh": "model", "yourdfpy": "model"}


@cache
def available(module: str) -> bool:
    """Whether an optional module is installed (without importing it)."""
    return importlib.util.find_spec(module) is not None
