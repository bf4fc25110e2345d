"""A mesh's format is one a selected target cannot load.

## What it does
Judges each `<mesh filename>` by its extension (case-insensitive) against the
loaders of the selected targets:
- Gazebo Classic 9/11 (`common::MeshManager`): STL, Collada (`.dae`) and OBJ
  (OBJ since 2016, Gazebo 7/8);
- Gazebo Sim (`gz-common`): STL, Collada and OBJ, plus glTF (`.gltf`, `.glb`)
  and FBX through assimp since Garden (gz-common 5; Fortress has the first three);
- MuJoCo: STL, OBJ and its own MSH; no Collada.
- Drake (1.51, observed): collision meshes in OBJ, VTK or glTF only; it refuses an STL or
  Collada collision mesh ("MakeConvexHull only applies to .obj, .vtk, and .gltf meshes;
  unsupported extension '.stl'"), which is what most ROS robots have.

MuJoCo's URDF import skips `<visual>` elements unless the file sets
`<mujoco><compiler discardvisual="false"/></mujoco>` (URDF's default is
`true`), so under `mujoco` only collision meshes count until then.
An unknown or missing extension is reported for every target. It is an error
when MuJoCo or Drake is among the targets that cannot load the file, since they then
refuse the whole model; a warning for Gazebo, which drops the geometry.

## Why is this bad?
MuJoCo's URDF import stops at the first unsupported mesh ("no decoder found
for mesh file 'X.dae'"), and Collada is the most common reason a ROS robot
does not load in MuJoCo. Gazebo Classic logs
"Invalid mesh filename extension" or "Unsupported mesh format" and simulates
the link without that visual or collision; a lost collision lets the link
pass through the world.

## How to fix
Convert the mesh to a format every selected target reads; the finding's fix names
them: OBJ reads everywhere (Drake's collision geometry needs OBJ, VTK or glTF), STL
in MuJoCo and both Gazebos, Collada or OBJ with a `.mtl` where colours matter in
Gazebo. For MuJoCo, keep a converted copy of Collada visuals as OBJ
(for example with `trimesh` or Blender).
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
    COLLISION_ONLY,
    KNOWN_FORMATS,
    TARGET_FORMATS,
    format_name,
    suffix,
)
from urdflint.sources.meshes import references

READS = {
    "gazebo-classic": "STL, Collada and OBJ",
    "gz-sim": "STL, Collada, OBJ, glTF and FBX",
    "mujoco": "STL, OBJ and MSH",
    "drake": "OBJ, VTK and glTF for collision geometry",
}

GEOMETRY_LOST = fx.no_geometry("the mesh is not shown or collided with")
EFFECTS: dict[str, Effect] = {
    "gazebo-classic": GEOMETRY_LOST,
    "gz-sim": GEOMETRY_LOST,
    "mujoco": fx.refused('"no decoder found for mesh file"'),
    "drake": fx.refused('"MakeConvexHull only applies to .obj, .vtk, and .gltf meshes"'),
}
REFUSING = frozenset({"mujoco", "drake"})


@rule(
    "C009",
    "unsupported-mesh-format",
    Severity.WARNING,
    fix="Convert the mesh to a format every selected target reads (the finding names them).",
    effects={"": EFFECTS},
)
def check(doc: Document) -> Iterator[Hit]:
    targets = [t for t in TARGET_FORMATS if t in doc.targets]
    if not targets:
        return
    visuals = _mujoco_keeps_visuals(doc)
    for ref in references(doc):
        ext = suffix(ref.uri)
        failing = [
            t for t in targets if ext not in TARGET_FORMATS[t] and _counts(t, ref.tag, visuals)
        ]
        if not failing:
            continue
        severity = Severity.ERROR if REFUSING & set(failing) else Severity.WARNING
        fix = convert_to([t for t in targets if _counts(t, ref.tag, visuals)])
        what = f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}"
        if not ext or ext not in KNOWN_FORMATS:
            kind = "has no extension" if not ext else f"has the unknown extension '.{ext}'"
            labels = " and ".join(LABELS[t] for t in failing)
            yield Hit(
                ref.element,
                f"{what} {kind}, which {labels} cannot load",
                severity=severity,
                effects=effects(failing),
                fix=fix,
            )
            continue
        labels = " and ".join(LABELS[t] for t in failing)
        reads = "; ".join(f"{LABELS[t]} reads {READS[t]}" for t in failing)
        yield Hit(
            ref.element,
            f"{labels} cannot load {format_name(ext)} {what} ({reads})",
            severity=severity,
            effects=effects(failing),
            fix=fix,
        )


PREFERRED = ("obj", "stl", "dae", "gltf")  # what to convert to, the most widely read first


def convert_to(readers: list[str]) -> str:
    """The fix: the formats every selected target that reads this mesh can load.

    Never a format one of them refuses (Drake reads no STL collision mesh, MuJoCo no
    Collada), so the advice cannot contradict the message.
    """
    common = [ext for ext in PREFERRED if all(ext in TARGET_FORMATS[t] for t in readers)]
    labels = " and ".join(LABELS[t] for t in readers)
    if not common:
        return f"No one format is read by {labels}: keep a converted copy of the mesh per target."
    found = [format_name(ext) for ext in common]
    names = found[0] if len(found) == 1 else f"{', '.join(found[:-1])} or {found[-1]}"
    every = "both read" if len(readers) == 2 else "all read" if len(readers) > 2 else "reads"
    return f"Convert the mesh to {names}, which {labels} {every} (for example with trimesh)."


def effects(failing: list[str]) -> dict[str, Effect]:
    """MuJoCo and Drake refuse the model; Gazebo loads it without the mesh."""
    return {t: EFFECTS[t] for t in failing}


def _counts(target: str, tag: str, visuals: bool) -> bool:
    """Whether the target reads this mesh at all: MuJoCo skips visuals unless told not to,
    Drake's limit is on collision meshes."""
    if target == "mujoco":
        return tag == "collision" or visuals
    return tag == "collision" or target not in COLLISION_ONLY


def _mujoco_keeps_visuals(doc: Document) -> bool:
    """Whether ``<mujoco><compiler discardvisual="false"/>`` asks MuJoCo to load visuals."""
    for compiler in doc.robot.findall("mujoco/compiler"):
        if (compiler.get("discardvisual") or "").strip().lower() in ("false", "0"):
            return True
    return False
