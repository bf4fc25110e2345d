"""urdflint: the linter for robot descriptions (URDF and xacro)."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from urdflint.finding import Finding, Severity

try:
    __version__ = version("urdflint")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.0.0"

__all__ = ["Finding", "Severity", "__version__"]
