"""A collision mesh has more triangles than `max-faces` (default 5,000).

## What it does
Loads each `<collision>` mesh and reports it when it has more than
`max-faces` triangles (after loading, so a Collada scene counts all its
parts).

## Why is this bad?
Collision checking cost grows with triangle count in every engine, and a
detailed mesh makes contacts jittery. The "Using a URDF in Gazebo" tutorial
strongly suggests a simplified collision model for performance; MoveIt's
planning scene checks every collision mesh at every state; PyBullet and MuJoCo
replace the mesh by its convex hull anyway, so the detail is paid for and
then thrown away.

## How to fix
Export a decimated copy for `<collision>` (Blender's Decimate modifier,
`trimesh`, MeshLab's quadric edge collapse), a convex decomposition (CoACD,
V-HACD), or approximate the link with boxes, cylinders and spheres. Keep the
detailed mesh in `<visual>`. The limit is configurable:

```toml
[rules.C007]
max-faces = 20000
```
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.meshes import load, references


@rule(
    "C007",
    "collision-mesh-too-complex",
    Severity.INFO,
    fix="Simplify the collision model: a decimated or convex mesh, or primitive shapes.",
    needs=("trimesh",),
    options={"max-faces": 5000},
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    limit = int(opts["max-faces"])
    for ref in references(doc):
        if ref.tag != "collision":
            continue
        info = load(doc, ref)
        if info is None or info.error is not None or info.faces <= limit:
            continue
        yield Hit(
            ref.element,
            f"collision mesh {ref.uri!r} of link {q(ref.link)} has {info.faces:,} triangles "
            f"(more than {limit:,})",
        )
