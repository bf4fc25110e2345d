"""Mesh file formats: what trimesh is asked to read, their names, and what each target loads.

Pure Python, no trimesh: the static rules C008 and C009 and the mesh cache share these tables.
The unit a Collada file declares is read here too (lxml only).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import BinaryIO

# What trimesh is asked to read, by suffix (the file type it is given).
TRIMESH_TYPES: Mapping[str, str] = {
    "stl": "stl",
    "stla": "stl",
    "stlb": "stl",
    "obj": "obj",
    "dae": "dae",
    "ply": "ply",
    "off": "off",
    "glb": "glb",
    "gltf": "gltf",
}
FORMAT_NAMES: Mapping[str, str] = {
    "stl": "STL",
    "stla": "STL (.stla)",
    "stlb": "STL (.stlb)",
    "obj": "OBJ",
    "dae": "Collada",
    "gltf": "glTF",
    "glb": "GLB",
    "fbx": "FBX",
    "msh": "MSH",
    "ply": "PLY",
    "off": "OFF",
    "vtk": "VTK",
}
# Mesh formats each target's loader reads, per role (suffix, lower case: every loader here
# compares extensions case-insensitively, so box.STL reads as box.stl). None: the target
# does not open meshes of that role when it loads the model (Drake registers visuals as
# they are). Observed by loading a box in each format (issue 29) unless noted:
# - Gazebo Classic 9/11 common::MeshManager: STL (stl/stla/stlb), Collada, OBJ (source);
#   gz-common 5 (Garden and later) adds glTF and FBX through assimp (source; Fortress:
#   the first three).
# - MuJoCo 4.0: STL, OBJ and its own MSH ("no decoder found for mesh file" otherwise).
# - Drake 1.51: collision meshes in OBJ, VTK or glTF (.gltf only, not .glb): "MakeConvexHull
#   only applies to .obj, .vtk, and .gltf meshes"; visual meshes of any extension load.
# - PyBullet 3.2.7 (UrdfFindMeshFile): .stl, .obj, .dae for both roles; else "invalid mesh
#   filename extension" and "Cannot load URDF file". It takes .vtk (a deformable body's
#   mesh) and then drops the shape: DROPPED.
# - Pinocchio 4.1 (coal, assimp 6): STL, OBJ, Collada, glTF, GLB, PLY, OFF and FBX; not
#   .stla/.stlb, MSH or VTK ("No suitable reader found for the file format").
STL = frozenset({"stl", "stla", "stlb"})
_GAZEBO = STL | {"dae", "obj"}
_PINOCCHIO = frozenset({"stl", "obj", "dae", "gltf", "glb", "ply", "off", "fbx"})
TARGET_FORMATS: Mapping[str, Mapping[str, frozenset[str] | None]] = {
    "gazebo-classic": {"visual": _GAZEBO, "collision": _GAZEBO},
    "gz-sim": {
        "visual": _GAZEBO | {"gltf", "glb", "fbx"},
        "collision": _GAZEBO | {"gltf", "glb", "fbx"},
    },
    "mujoco": {
        "visual": frozenset({"stl", "obj", "msh"}),
        "collision": frozenset({"stl", "obj", "msh"}),
    },
    "drake": {"visual": None, "collision": frozenset({"obj", "vtk", "gltf"})},
    "pybullet": {
        "visual": frozenset({"stl", "obj", "dae"}),
        "collision": frozenset({"stl", "obj", "dae"}),
    },
    "pinocchio": {"visual": _PINOCCHIO, "collision": _PINOCCHIO},
}
# Formats a target accepts and then loads without the shape (PyBullet: "cannot extract mesh").
DROPPED: Mapping[str, frozenset[str]] = {"pybullet": frozenset({"vtk"})}
KNOWN_FORMATS = frozenset().union(
    *(f for table in TARGET_FORMATS.values() for f in table.values() if f is not None),
    TRIMESH_TYPES,
)


def reads(target: str, role: str) -> frozenset[str] | None:
    """The formats ``target`` loads for a ``role`` ("visual" or "collision") mesh, ``None``
    when it does not open such meshes at load time."""
    return TARGET_FORMATS[target][role]


def suffix(uri: str) -> str:
    """The lower-case extension of a mesh URI (``''`` when it has none)."""
    name = uri.strip().replace("\\", "/").rsplit("/", 1)[-1]
    return name.rsplit(".", 1)[-1].lower() if "." in name else ""


def format_name(ext: str) -> str:
    return FORMAT_NAMES.get(ext, f".{ext}" if ext else "extension-less")


def collada_unit(path: Path) -> float:
    """Metres per unit declared by a Collada file's ``<asset><unit meter>`` (1.0 without one).

    Read as Gazebo reads it: the ``meter`` attribute of the first ``<unit>`` in the first
    ``<asset>`` under ``<COLLADA>``. A value that is not a positive number counts as 1
    (RViz keeps 1 when the attribute does not convert). Only the file's head is parsed.
    """
    from lxml import etree

    try:
        with path.open("rb") as handle:
            return _unit_in(handle)
    except (etree.XMLSyntaxError, OSError, ValueError):
        return 1.0


def _unit_in(handle: BinaryIO) -> float:
    from lxml import etree

    depth, in_asset = 0, False
    events = etree.iterparse(
        handle,
        events=("start", "end"),
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        huge_tree=False,
    )
    for event, el in events:
        depth += 1 if event == "start" else -1
        tag = etree.QName(el).localname if isinstance(el.tag, str) else ""
        if event == "start" and depth == 2:
            in_asset = tag == "asset"
        elif event == "start" and depth == 3 and in_asset and tag == "unit":
            return _positive(el.get("meter"))
        elif event == "end" and depth == 1:
            if tag == "asset":
                return 1.0
            el.clear()
    return 1.0


def _positive(text: str | None) -> float:
    try:
        value = float((text or "").strip())
    except ValueError:
        return 1.0
    return value if value > 0 and math.isfinite(value) else 1.0
