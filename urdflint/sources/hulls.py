"""Convex hulls of visual meshes, written as collision meshes (``urdflint fix --write-meshes``).

The hull is computed from the mesh as the run read it (through :class:`MeshCache`, at scale
1, a Collada file's ``<unit meter>`` applied) and written as a Wavefront OBJ beside the mesh,
named ``<stem>_hull.obj``. OBJ because every target reads it for collision: both Gazebos,
MuJoCo, PyBullet, Pinocchio (assimp) and Drake, which refuses STL and Collada collision
meshes. The collision keeps the visual's ``scale``, so one hull serves every link that draws
the mesh, at any scale.

Nothing is written here: :func:`hull_file` returns the file's path, its URI for the
``<mesh filename>`` and its text, and the fix engine creates the file only when the fix is
applied (never over an existing file with other content).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from urdflint.model.document import Document
from urdflint.model.geometry import Shape

SUFFIX = "_hull.obj"
MAX_HULL_VERTICES = 5000  # qhull's hull of a scanned part; larger would be no simplification


@dataclass(frozen=True, slots=True)
class HullFile:
    path: Path  # where the file is written, beside the mesh
    uri: str  # the visual's filename with the hull's file name
    text: str  # the OBJ
    vertices: int
    faces: int


def hull_file(doc: Document, shape: Shape) -> HullFile | str:
    """The convex hull of the mesh ``shape`` as an OBJ file beside it, or why there is none."""
    from urdflint.model.inertia import meshes_readable
    from urdflint.sources.meshes import resolved

    uri = (shape.filename or "").strip()
    if not meshes_readable():
        from urdflint.model.optional import install_command

        return f"reading meshes needs trimesh ({install_command('model')})"
    found = resolved(doc, uri)
    if not found.found or found.path is None:
        return f"the mesh {uri!r} was not found"
    info = doc.meshes.load(found.path, (1.0, 1.0, 1.0))
    if info.error is not None:
        return f"the mesh {uri!r} could not be read ({info.error})"
    hull = _hull(info.mesh)
    if hull is None:
        return f"the mesh {uri!r} is flat or degenerate: it has no convex hull with a volume"
    vertices, faces = hull
    if len(vertices) > MAX_HULL_VERTICES:
        return f"the convex hull of {uri!r} has {len(vertices)} vertices: simplify it by hand"
    name = found.path.stem + SUFFIX
    path = found.path.with_name(name)
    head, slash, _ = uri.rpartition("/")
    text = obj_text(vertices, faces, f"convex hull of {found.path.name}")
    return HullFile(path, head + slash + name, text, len(vertices), len(faces))


def _hull(mesh: object) -> tuple[list[tuple[float, ...]], list[tuple[int, ...]]] | None:
    from urdflint.sources.mesh_cache import quiet_numpy

    with quiet_numpy():
        try:
            hull = mesh.convex_hull  # type: ignore[attr-defined]
            if hull is None or len(hull.faces) == 0 or not hull.volume > 0:
                return None
            vertices = [tuple(float(v) for v in row) for row in hull.vertices]
            faces = [tuple(int(i) for i in row) for row in hull.faces]
        except Exception:  # qhull on flat or degenerate input
            return None
    return vertices, faces


def obj_text(vertices: list[tuple[float, ...]], faces: list[tuple[int, ...]], what: str) -> str:
    """A Wavefront OBJ: a comment, the vertices, the triangles (1-based, outward winding)."""
    lines = [f"# {what}, written by urdflint fix --write-meshes"]
    lines += ["v " + " ".join(_number(x) for x in v) for v in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def _number(value: float) -> str:
    text = f"{value:.9g}"
    return "0" if text == "-0" else text
