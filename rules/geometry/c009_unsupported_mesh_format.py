"""A mesh's format is one a selected target cannot load.

## What it does
Judges each `<mesh filename>` by its extension (case-insensitive, as every loader below
compares it) against the mesh loaders of the selected targets, for the role the mesh has:

| format | Gazebo Classic | Gazebo Sim | MuJoCo | Drake | PyBullet | Pinocchio |
|---|---|---|---|---|---|---|
| STL (`.stl`) | yes | yes | yes | visual only | yes | yes |
| `.stla`, `.stlb` | yes | yes | no | visual only | no | no |
| OBJ | yes | yes | yes | yes | yes | yes |
| Collada (`.dae`) | yes | yes | no | visual only | yes | yes |
| glTF (`.gltf`) | no | yes | no | yes | no | yes |
| GLB (`.glb`) | no | yes | no | visual only | no | yes |
| PLY, OFF | no | no | no | visual only | no | yes |
| FBX | no | yes | no | visual only | no | yes |
| MSH (MuJoCo's) | no | no | yes | visual only | no | no |
| VTK | no | no | no | yes | shape dropped | no |

MuJoCo 4.0, Drake 1.51, PyBullet 3.2.7 and Pinocchio 4.1 were observed loading a box
in each format, once as a `<visual>` and once as a `<collision>`; they treat both roles
alike but Drake, which registers visual meshes without opening them (its renderer,
`RenderEngineVtk`, then draws only OBJ and `.gltf` and says "Perception role assigned to
geometry N, but no renderer accepted it" for the others), and MuJoCo, whose URDF import
skips `<visual>` elements unless the file sets `<mujoco><compiler
discardvisual="false"/></mujoco>` (URDF's default is `true`). The Gazebo columns follow
their source, since sdformat does not open meshes: Gazebo Classic 9/11
(`common::MeshManager`) reads STL, Collada and OBJ; Gazebo Sim adds glTF, GLB and FBX
through assimp since Garden (gz-common 5; Fortress has the first three).

An unknown or missing extension is reported for every target. The finding is an error
when a target among those that cannot load the mesh refuses the whole model (MuJoCo,
Drake, PyBullet, Pinocchio), a warning when they only lose the shape (Gazebo, PyBullet
with a `.vtk` file).

## Why is this bad?
Each engine stops or loses geometry at the first mesh it cannot read:
- MuJoCo refuses the model: "no decoder found for mesh file 'meshes/box.dae'". Collada is
  the most common reason a ROS robot does not load in MuJoCo.
- Drake refuses a collision mesh that is not OBJ, VTK or `.gltf` (STL, Collada, `.glb`,
  the meshes most ROS robots have): "MakeConvexHull only applies to .obj, .vtk, and .gltf
  meshes; unsupported extension '.stl'".
- PyBullet refuses glTF, GLB, PLY, FBX, MSH or an unknown extension in a visual as in a
  collision: "invalid mesh filename extension 'gltf'", "Could not parse visual element for
  Link", then "Cannot load URDF file" (Drake's own models, with glTF visuals, do not load
  in PyBullet). It reads a `.vtk` file as a deformable body's mesh and loads the model
  without the shape ("cannot extract mesh from 'meshes/box.vtk'").
- Pinocchio's `buildGeomFromUrdf` (coal, through assimp) raises on MSH, VTK and `.stla`:
  "Could not load resource ... No suitable reader found for the file format".
- Gazebo Classic logs "Invalid mesh filename extension" or "Unsupported mesh format" and
  simulates the link without that visual or collision; a lost collision lets the link pass
  through the world.

## How to fix
Convert the mesh to a format every selected target reads; the finding's fix names them:
OBJ reads everywhere (Drake's collision geometry needs OBJ, VTK or glTF), STL in all
but Drake's collisions, Collada or OBJ with a `.mtl` where colours matter in Gazebo.
For MuJoCo, keep a converted copy of Collada visuals as OBJ; for PyBullet, of glTF
visuals (for example with `trimesh` or Blender).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import effects as fx
from urdflint.model.document import Document
from urdflint.model.effects import Effect
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.model.targets import LABELS
from urdflint.sources.mesh_formats import (
    DROPPED,
    KNOWN_FORMATS,
    TARGET_FORMATS,
    format_name,
    reads,
    suffix,
)
from urdflint.sources.meshes import MeshRef, references

READS = {
    "gazebo-classic": "STL, Collada and OBJ",
    "gz-sim": "STL, Collada, OBJ, glTF, GLB and FBX",
    "mujoco": "STL, OBJ and MSH",
    "drake": "OBJ, VTK and glTF (.gltf) for collision geometry",
    "pybullet": "STL (.stl), OBJ and Collada",
    "pinocchio": "STL (.stl), OBJ, Collada, glTF, GLB, PLY, OFF and FBX",
}

GEOMETRY_LOST = fx.no_geometry("the mesh is not shown or collided with")
EFFECTS: dict[str, Effect] = {
    "gazebo-classic": GEOMETRY_LOST,
    "gz-sim": GEOMETRY_LOST,
    "mujoco": fx.refused('"no decoder found for mesh file"'),
    "drake": fx.refused('"MakeConvexHull only applies to .obj, .vtk, and .gltf meshes"'),
    "pybullet": fx.refused('"invalid mesh filename extension", then "Cannot load URDF file"'),
    "pinocchio": fx.refused('buildGeomFromUrdf: "No suitable reader found for the file format"'),
}
SHAPE_DROPPED: dict[str, Effect] = {
    "pybullet": fx.no_geometry('"cannot extract mesh from" the .vtk file: the shape is left out'),
}


@rule(
    "C009",
    "unsupported-mesh-format",
    Severity.WARNING,
    fix="Convert the mesh to a format every selected target reads (the finding names them).",
    effects={"": EFFECTS, "dropped": SHAPE_DROPPED},
)
def check(doc: Document) -> Iterator[Hit]:
    targets = [t for t in TARGET_FORMATS if t in doc.targets]
    if not targets:
        return
    visuals = _mujoco_keeps_visuals(doc)
    for ref in references(doc):
        readers = [t for t in targets if _counts(t, ref.tag, visuals)]
        ext = suffix(ref.uri)
        failing = [t for t in readers if ext not in (reads(t, ref.tag) or ())]
        if failing:
            yield _hit(ref, ext, failing, readers)


def _hit(ref: MeshRef, ext: str, failing: list[str], readers: list[str]) -> Hit:
    found = effects(failing, ext)
    refused = any(e.consequence is fx.Consequence.REFUSED for e in found.values())
    severity = Severity.ERROR if refused else Severity.WARNING
    what = f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}"
    labels = listed([LABELS[t] for t in failing])
    if not ext or ext not in KNOWN_FORMATS:
        kind = "has no extension" if not ext else f"has the unknown extension '.{ext}'"
        message = f"{what} {kind}, which {labels} cannot load"
    else:
        said = "; ".join(f"{LABELS[t]} reads {READS[t]}" for t in failing)
        message = f"{labels} cannot load {format_name(ext)} {what} ({said})"
    fix = convert_to(readers, ref.tag)
    return Hit(ref.element, message, severity=severity, effects=found, fix=fix)


PREFERRED = ("obj", "stl", "dae", "gltf")  # what to convert to, the most widely read first


def convert_to(readers: list[str], tag: str = "collision") -> str:
    """The fix: the formats every selected target that reads this mesh can load.

    Never a format one of them refuses (Drake reads no STL collision mesh, MuJoCo no
    Collada, PyBullet no glTF), so the advice cannot contradict the message.
    """
    common = [ext for ext in PREFERRED if all(ext in (reads(t, tag) or ()) for t in readers)]
    labels = listed([LABELS[t] for t in readers])
    if not common:
        return f"No one format is read by {labels}: keep a converted copy of the mesh per target."
    found = [format_name(ext) for ext in common]
    names = found[0] if len(found) == 1 else f"{', '.join(found[:-1])} or {found[-1]}"
    every = "both read" if len(readers) == 2 else "all read" if len(readers) > 2 else "reads"
    return f"Convert the mesh to {names}, which {labels} {every} (for example with trimesh)."


def listed(names: list[str]) -> str:
    """``A``, ``A and B``, ``A, B and C``."""
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def effects(failing: list[str], ext: str = "") -> dict[str, Effect]:
    """MuJoCo, Drake, PyBullet and Pinocchio refuse the model; Gazebo loads it without the
    mesh, and so does PyBullet a .vtk one."""
    return {t: SHAPE_DROPPED[t] if ext in DROPPED.get(t, ()) else EFFECTS[t] for t in failing}


def _counts(target: str, tag: str, visuals: bool) -> bool:
    """Whether the target opens this mesh when it loads the model: MuJoCo skips visuals
    unless told not to, Drake registers visual meshes without reading them."""
    if target == "mujoco" and tag == "visual":
        return visuals
    return reads(target, tag) is not None


def _mujoco_keeps_visuals(doc: Document) -> bool:
    """Whether ``<mujoco><compiler discardvisual="false"/>`` asks MuJoCo to load visuals."""
    for compiler in doc.robot.findall("mujoco/compiler"):
        if (compiler.get("discardvisual") or "").strip().lower() in ("false", "0"):
            return True
    return False
