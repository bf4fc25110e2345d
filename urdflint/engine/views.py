"""The document views that need the engine, registered with the model's provider table.

Imported by the package (``urdflint/__init__.py``), so every document has them. Each view
imports what it needs on first use: a run whose rules never ask for physics never imports
Pinocchio.
"""

from __future__ import annotations

from typing import Any

from urdflint.model.document import Document
from urdflint.model.providers import provide


@provide("settings")
def default_settings(doc: Document) -> Any:
    from urdflint.engine.config import Settings

    return Settings(targets=tuple(sorted(doc.targets)))


@provide("context")
def default_context(doc: Document) -> Any:
    from urdflint.engine.context import Context

    return Context()


@provide("mesh_bounds")
def mesh_bounds(doc: Document) -> Any:
    """``shape -> (lo, hi)`` in the mesh's own frame after scale, or ``None`` when the mesh
    does not resolve, cannot be read, or is not in metres (C004-C006)."""
    from urdflint.sources.meshes import MeshRef, load, suspicious_size

    def bounds(shape: Any) -> Any:
        info = load(doc, MeshRef(None, "", shape))
        if info is None or info.error is not None or suspicious_size(info):
            return None
        return (info.lo, info.hi)

    return bounds


@provide("physics")
def physics(doc: Document) -> Any:
    from urdflint.engine.physics import build

    return build(doc)
