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
    "stla": "STL",
    "stlb": "STL",
    "obj": "OBJ",
    "dae": "Collada",
    "gltf": "glTF",
    "glb": "glTF",
    "fbx": "FBX",
    "msh": "MSH",
    "ply": "PLY",
}
# Mesh formats each target's loader accepts (suffix, lower case).
# Gazebo Classic 9/11 common::MeshManager: stl/stla/stlb, dae, obj (OBJ since 2016).
# gz-common 5 (Garden and later) adds glTF and FBX through assimp (Fortress: the first three).
# MuJoCo's compiler reads STL, OBJ and its own MSH (no Collada).
TARGET_FORMATS: Mapping[str, frozenset[str]] = {
    "gazebo-classic": frozenset({"stl", "stla", "stlb", "dae", "obj"}),
    "gz-sim": frozenset({"stl", "stla", "stlb", "dae", "obj", "gltf", "glb", "fbx"}),
    "mujoco": frozenset({"stl", "obj", "msh"}),
    "drake": frozenset({"obj", "vtk", "gltf"}),  # collision (proximity) geometry only
}
COLLISION_ONLY = frozenset({"drake"})  # targets whose format limit applies to collisions
KNOWN_FORMATS = frozenset().union(*TARGET_FORMATS.values(), TRIMESH_TYPES)


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
