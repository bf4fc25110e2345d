"""A collision mesh as MuJoCo's compiler processes it (C018), read from the file itself.

MuJoCo 4.0 (``mjCMesh::Process`` in ``user_mesh.cc``; observed on IsaacGym's factory assets)
compiles every collision mesh of the model, whether or not its link has an ``<inertial>``:

- its convex hull, from every vertex of the file: when they all lie in one plane qhull fails
  and MuJoCo refuses the model: "mesh 'NAME' has coplanar vertices, cannot compute convex
  hull. Consider using a primitive geom type (plane or thin box) instead";
- its volume, from its faces after ``scale``, as the default ``inertia="legacy"`` computes
  it: the pyramids from each triangle to the area-weighted centroid of all triangles, each
  taken positive. Below ``mjMINVAL`` (1e-15 m³) MuJoCo refuses the model: "mesh volume is too
  small: NAME . Try setting inertia to shell". An open mesh with a positive volume passes
  (an open box: 0.81 of the closed one's), and so does an inside-out one.

Its faces are not always the file's: MuJoCo's OBJ decoder keeps the faces of the first
object only (tinyobjloader's first shape: a new one starts at each ``o`` or ``g`` line after
faces), and every vertex. A file whose first object is a flat cap (IsaacGym's pegs and bolts)
has the volume of a flat cap, whatever follows. STL files are read whole.

Visual meshes are discarded (``discardvisual`` is on for URDF) unless the URDF's
``<mujoco><compiler discardvisual="false"/>`` keeps them; the caller decides which meshes
to look at. NAME is the file's name without its extension (the URDF import's mesh name).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

MINVAL = 1e-15  # mjMINVAL: the smallest volume (m³) or area (m²) MuJoCo accepts
FLAT = 1e-9  # relative thickness under which qhull takes the vertices as coplanar


@dataclass(frozen=True, slots=True)
class Compiled:
    """What MuJoCo computes of one mesh: the ``faces`` it reads of the file's ``total``
    (``objects`` objects in the file, the first named ``first``), their ``volume`` (m³, after
    scale) and whether every vertex lies in one plane."""

    faces: int
    total: int
    objects: int
    first: str
    volume: float
    coplanar: bool

    def refusal(self, name: str) -> str | None:
        """MuJoCo's error for this mesh (``None``: it compiles)."""
        if self.coplanar:
            return (
                f"mesh '{name}' has coplanar vertices, cannot compute convex hull. Consider "
                "using a primitive geom type (plane or thin box) instead"
            )
        if self.volume < MINVAL:
            return f"mesh volume is too small: {name} . Try setting inertia to shell"
        return None


def compile_mesh(path: Path, scale: tuple[float, float, float]) -> Compiled | None:
    """The mesh as MuJoCo compiles it; ``None`` for a format it is not read here in (MuJoCo
    reads STL, OBJ and MSH) or a file that cannot be read (C005 says why)."""
    import numpy as np

    suffix = path.suffix.lower()
    try:
        if suffix == ".obj":
            vertices, faces, total, objects, first = _obj(path)
        elif suffix == ".stl":
            vertices, faces = _stl(path)
            total, objects, first = len(faces) // 3, 1, ""
        else:
            return None
    except (OSError, ValueError, IndexError):
        return None
    points = np.asarray(vertices, dtype=float).reshape(-1, 3) * np.asarray(scale, dtype=float)
    if len(points) == 0:
        return None
    triangles = points[np.asarray(faces, dtype=int).reshape(-1, 3)] if faces else None
    volume = 0.0 if triangles is None else _legacy_volume(triangles)
    return Compiled(len(faces) // 3, total, objects, first, volume, _coplanar(points))


def _legacy_volume(triangles: Any) -> float:
    """Σ |(centre - centroid) · normal| × area / 3 over the triangles (``ComputeVolume``)."""
    import numpy as np

    cross = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    double_area = np.linalg.norm(cross, axis=1)
    centers = triangles.mean(axis=1)
    total = double_area.sum()
    if not total > 0:
        return 0.0
    centroid = (centers * double_area[:, None]).sum(axis=0) / total
    # (c - centroid) · (cross / |cross|) × (|cross| / 2) / 3 = (c - centroid) · cross / 6
    return float(np.abs(np.einsum("ij,ij->i", centers - centroid, cross)).sum() / 6.0)


def _coplanar(points: Any) -> bool:
    import numpy as np

    if len(points) < 4:
        return True
    centered = points - points.mean(axis=0)
    values = np.linalg.svd(centered, compute_uv=False)
    return not values[0] > 0 or values[-1] <= FLAT * values[0]


def _obj(path: Path) -> tuple[list[float], list[int], int, int, str]:
    """Every vertex; the corners of the first object's triangles (fan-triangulated); the
    count of triangles in the file; the count of objects with faces; the first one's name."""
    vertices: list[float] = []
    faces: list[int] = []
    total, objects, first, name = 0, 0, "", ""
    current: list[int] = []
    with path.open(encoding="utf-8", errors="replace") as handle:
        for line in handle:
            head, _, rest = line.strip().partition(" ")
            if head == "v":
                vertices.extend(float(v) for v in rest.split()[:3])
            elif head == "f":
                corners = _polygon(rest.split(), len(vertices) // 3)
                current.extend(corners)
                total += len(corners) // 3
            elif head in ("o", "g"):
                if current:
                    objects += 1
                    if objects == 1:
                        faces, first = current, name
                    current = []
                name = rest.strip()
    if current:
        objects += 1
        if objects == 1:
            faces, first = current, name
    return vertices, faces, total, objects, first


def _polygon(corners: list[str], count: int) -> list[int]:
    """A face's corners (``v``, ``v/t``, ``v/t/n``; negative: from the end) as triangles."""
    found = []
    for corner in corners:
        index = int(corner.split("/")[0])
        found.append(index - 1 if index > 0 else count + index)
    return [i for k in range(1, len(found) - 1) for i in (found[0], found[k], found[k + 1])]


def _stl(path: Path) -> tuple[Any, list[int]]:
    import trimesh

    mesh: Any = trimesh.load(str(path), file_type="stl", force="mesh", process=False)
    return mesh.vertices, mesh.faces.reshape(-1).tolist()
