"""A collision mesh has no volume as MuJoCo computes it: MuJoCo refuses the model.

## What it does
With `--target mujoco`, computes for each collision mesh what MuJoCo's compiler computes
(`mjCMesh::Process`), after the mesh's `scale`, and reports the meshes it refuses, in its
words, with the reason:

- "mesh volume is too small: NAME . Try setting inertia to shell": the volume of the
  mesh's faces, taken as MuJoCo's default (`inertia="legacy"`) takes it (the pyramids from
  each triangle to the area-weighted centroid of the triangles, each counted positive), is
  under `mjMINVAL`, 1e-15 m³. MuJoCo reads only the faces of an OBJ file's *first object*
  (its OBJ decoder keeps tinyobjloader's first shape: a new one starts at each `o` or `g`
  line), so an OBJ exported in parts whose first part is a flat cap has no volume, however
  solid the rest is; the message names that object and its share of the faces.
- "mesh 'NAME' has coplanar vertices, cannot compute convex hull. Consider using a
  primitive geom type (plane or thin box) instead": every vertex of the file lies in one
  plane (a flat plate, a 2-D outline), so qhull cannot build the hull MuJoCo collides with.

NAME is the file's name without extension, as the URDF import names its meshes. Visual
meshes are discarded (`discardvisual` is on for URDF) and not checked, unless the URDF's
`<mujoco><compiler discardvisual="false"/>` keeps them. STL and OBJ files are read (MSH, and
formats MuJoCo does not read, C009, are not).

Observed with MuJoCo 4.0 on IsaacGym's factory assets (isaac-sim/IsaacGymEnvs,
`assets/factory/urdf`, commit aeed2986): 31 of the 47 files whose meshes are in the
repository snapshot are refused with "mesh volume is too small" (the bolts, rectangular and
round pegs, rectangular holes, gear bases, `factory_franka.urdf`'s fingers): their OBJ files
hold 5 to 57 objects, the first a flat face of 2 to 144 triangles. The same meshes
re-exported as one object load, with the mass of the whole part. Refused all the same with
an `<inertial>` on the link: MuJoCo computes every collision mesh's volume whether or not it
infers the link's mass from it (I001). The check agrees with MuJoCo on 335 meshes (those 47
OBJ files, 280 meshes of the corpus robots and FANUC arms, 8 planted ones: flat, open,
inside-out, a 9 µm cube, OBJ files with `o` and `g` objects): an open mesh with a positive
volume loads (an open box has 0.81 of the closed one's), and so does an inside-out one.
Drake (its convex hull), PyBullet and Pinocchio (coal) read every object of an OBJ file
(observed on a planted two-object file).

## Why is this bad?
MuJoCo refuses the whole model, for a mesh that other simulators load and that looks solid
in any viewer: the file loads in Isaac Gym (it was made for it), PyBullet, Drake and
Pinocchio, and fails in MuJoCo only.

## How to fix
Export the mesh as one object (join the parts in Blender, or `trimesh.load(path,
force="mesh").export(path)`), or as STL; replace a flat mesh by a thin `<box>`. In MJCF
after conversion, `<mesh inertia="shell">` or `inertia="convex"` computes the mesh's inertia
another way; adding an `<inertial>` to the link does not help.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import PurePosixPath
from typing import TYPE_CHECKING

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children, local_tag
from urdflint.model.effects import refused, single
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.meshes import MeshRef, load, references

if TYPE_CHECKING:
    from urdflint.sources.mujoco_mesh import Compiled

EFFECTS = single(
    {
        "mujoco": refused(
            '"mesh volume is too small: NAME . Try setting inertia to shell", or "mesh \'NAME\' '
            'has coplanar vertices, cannot compute convex hull"'
        )
    }
)


@rule(
    "C018",
    "mesh-without-volume",
    Severity.ERROR,
    fix="Export the mesh as one object (or as STL); replace a flat mesh by a thin box.",
    needs=("trimesh",),
    targets=("mujoco",),
    effects=EFFECTS,
)
def check(doc: Document) -> Iterator[Hit]:
    roles = ("visual", "collision") if _keeps_visuals(doc) else ("collision",)
    for ref in references(doc):
        if ref.tag not in roles or ref.scale is None:
            continue
        info = load(doc, ref)
        compiled = None if info is None or not info.ok else info.mujoco(ref.scale)
        if compiled is None:
            continue
        name = PurePosixPath(ref.uri.replace("\\", "/")).stem
        refusal = compiled.refusal(name)
        if refusal is not None:
            yield Hit(ref.element, _message(ref, refusal, compiled))


def _message(ref: MeshRef, refusal: str, compiled: Compiled) -> str:
    text = f'{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}: MuJoCo refuses it ("{refusal}")'
    if "coplanar" in refusal:
        return text + ": every vertex lies in one plane"
    volume = f"{compiled.volume:.3g} m³"
    if compiled.objects > 1:
        return text + (
            f": it reads only the first of the file's {compiled.objects} objects, "
            f"{compiled.first or 'unnamed'!r}, {compiled.faces:,} of {compiled.total:,} "
            f"triangles, {volume}"
        )
    return text + f": its {compiled.faces:,} triangles enclose {volume}"


def _keeps_visuals(doc: Document) -> bool:
    """``<mujoco><compiler discardvisual="false"/>`` in the URDF."""
    extension = next((c for c in children(doc.robot) if local_tag(c) == "mujoco"), None)
    if extension is None:
        return False
    compiler = next((c for c in children(extension) if local_tag(c) == "compiler"), None)
    value = "" if compiler is None else (compiler.get("discardvisual") or "").strip()
    return value == "false"
