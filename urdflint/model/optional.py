"""Optional dependencies: whether one is installed, and which extra installs it."""

from __future__ import annotations

import importlib.util
from functools import cache

EXTRAS = {"numpy": "model", "pinocchio": "dynamics", "trimesh": "model", "yourdfpy": "model"}


@cache
def available(module: str) -> bool:
    """Whether an optional module is installed (without importing it)."""
    return importlib.util.find_spec(module) is not None


@cache
def install_command(extras: str) -> str:
    """The pip command that installs ``extras`` (``"dynamics"``, ``"model,dynamics"``) for
    the urdflint that is running: from its checkout (``pip install -e '/src/urdflint[x]'``)
    or the git URL it came from; the bare distribution name only for an index install."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    if (root / "pyproject.toml").is_file() and (root / "urdflint" / "__init__.py").is_file():
        return f"pip install -e '{root}[{extras}]'"
    origin = _origin()
    if origin is not None:
        return f"pip install 'urdflint[{extras}] @ {origin}'"
    return f"pip install 'urdflint[{extras}]'"


def _origin() -> str | None:
    """Where the installed distribution came from (PEP 610), when not from an index."""
    import importlib.metadata
    import json

    try:
        text = importlib.metadata.distribution("urdflint").read_text("direct_url.json")
        url = json.loads(text or "null")
    except (importlib.metadata.PackageNotFoundError, ValueError):
        return None
    if not isinstance(url, dict) or not isinstance(url.get("url"), str):
        return None
    vcs = url.get("vcs_info")
    if isinstance(vcs, dict):
        commit = vcs.get("commit_id")
        return f"{vcs.get('vcs', 'git')}+{url['url']}" + (f"@{commit}" if commit else "")
    return url["url"]
