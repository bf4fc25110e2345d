"""A mesh file exists but cannot be read as a triangle mesh.

## What it does
Loads every mesh that C004 found with trimesh (`trimesh.load(path,
force="mesh")`, Collada through pycollada) and reports the ones that fail to
parse or hold no triangles, with the reason. Formats trimesh does not read at
all are C009's business, not this rule's; a file over urdflint's 100 MB
reading limit, or a Collada file when pycollada is not installed, is a note
(info) that the mesh was not checked.

## Why is this bad?
A file that does not parse is as good as missing, but harder to spot: RViz
and Gazebo log "Unable to load mesh" and draw or collide with nothing,
MuJoCo stops compiling ("stl_decoder: invalid header in STL file" for a web
page saved as `.stl`, "mesh volume is negative", "at least 4 vertices
required"), Pinocchio's geometry loader (coal, formerly hpp-fcl) throws
("Could not load resource"), and PyBullet warns "cannot extract mesh from
'X'" and loads the link without that geometry. Typical
causes are a truncated download, a Git LFS pointer committed instead of the
file, an HTML error page saved with a `.stl` name, or an export that wrote
no geometry.

## How to fix
Re-export the mesh from the CAD tool (binary STL, OBJ or Collada), check
that Git LFS files are pulled, and open the file in a mesh viewer.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.mesh_formats import TRIMESH_TYPES
from urdflint.sources.meshes import load, references


@rule(
    "C005",
    "mesh-unreadable",
    Severity.ERROR,
    fix="Re-export the mesh (binary STL, OBJ or Collada) and check that it opens in a viewer.",
    needs=("trimesh",),
)
def check(doc: Document) -> Iterator[Hit]:
    for ref in references(doc):
        info = load(doc, ref)
        if info is None or info.error is None or info.format not in TRIMESH_TYPES:
            continue
        what = f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}"
        if info.unsupported:
            yield Hit(ref.element, f"{what} was not checked: {info.error}", severity=Severity.INFO)
        else:
            yield Hit(ref.element, f"{what} cannot be read: {info.error}")
