"""Mesh file formats: what trimesh is asked to read, their names, and what each target loads.

Pure Python, no trimesh: the static rules C008 and C009 and the mesh cache share these tables.
"""

from __future__ import annotations

from collections.abc import Mapping

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
}
KNOWN_FORMATS = frozenset().union(*TARGET_FORMATS.values(), TRIMESH_TYPES)


def suffix(uri: str) -> str:
    """The lower-case extension of a mesh URI (``''`` when it has none)."""
    name = uri.strip().replace("\\", "/").rsplit("/", 1)[-1]
    return name.rsplit(".", 1)[-1].lower() if "." in name else ""


def format_name(ext: str) -> str:
    return FORMAT_NAMES.get(ext, f".{ext}" if ext else "extension-less")
