"""A link uses the same mesh file for collision as for its visual.

## What it does
Reports a `<collision>` mesh whose file (after normalising `file://`, `./`
and `//`) is also one of the same link's `<visual>` meshes.

## Why is this bad?
Visual meshes are detailed (often tens of thousands of triangles, Collada
with textures); collision checking cost grows with triangle count in every
engine. The "Using a URDF in Gazebo" tutorial strongly suggests a simplified
collision model for performance. PyBullet and MuJoCo replace the mesh by its
convex hull anyway, which silently fills concave parts (a gripper's opening,
a wheel arch); MoveIt planning slows down with every detailed mesh.

## How to fix
Export a decimated or convex-decomposed copy of the mesh for `<collision>`
(Blender's Decimate modifier, `trimesh`, CoACD or V-HACD), or approximate the
link with boxes, cylinders and spheres. Keep the detailed mesh in `<visual>`.
"""

from __future__ import annotations

import posixpath
from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.geometry import shapes
from urdflint.model.structure import q


def normalise(uri: str) -> str:
    """A comparable form of a mesh URI: no ``file://``, no ``./`` or doubled slashes."""
    text = uri.strip().replace("\\", "/")
    if text.startswith("file://"):
        text = text[len("file://") :]
    scheme, sep, rest = text.partition("://")
    if sep:
        return f"{scheme.lower()}://{posixpath.normpath(rest)}"
    return posixpath.normpath(text) if text else text


@rule(
    "C002",
    "collision-same-as-visual-mesh",
    Severity.INFO,
    fix="Use a simplified mesh or primitive shapes for the collision.",
)
def check(doc: Document) -> Iterator[Hit]:
    for link in doc.links:
        visual = {
            normalise(s.filename)
            for s in shapes(link.element, "visual")
            if s.kind == "mesh" and s.filename
        }
        visual.discard("")
        for shape in shapes(link.element, "collision"):
            if shape.kind == "mesh" and shape.filename and normalise(shape.filename) in visual:
                uri = shape.filename.strip()
                yield Hit(
                    shape.element, f"collision of link {q(link.name)} uses its visual mesh {uri!r}"
                )
