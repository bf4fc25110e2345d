"""urdflint: the linter for robot descriptions (URDF and xacro)."""

from __future__ import annotations

from urdflint import engines as _engines  # noqa: F401  (registers the "confirmation" view)
from urdflint.engine import views as _views  # noqa: F401  (registers the engine's document views)
from urdflint.model.finding import Finding, Severity

__version__ = "0.1.0"  # the single source of the version (pyproject reads it)

__all__ = ["Finding", "Severity", "__version__"]
