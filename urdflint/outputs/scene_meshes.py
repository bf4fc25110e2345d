"""The meshes of a 3D scene (:mod:`urdflint.outputs.scene`), compact and within a budget.

:class:`MeshTable` reads every ``<mesh>`` of the scene once per file and scale through the
document's resolver and mesh cache (the files the lint already loaded are not read again;
the service's cache is confined to the request's folder). :meth:`MeshTable.encode` sends
each as little-endian base64: ``positions`` float32 (x y z per vertex, metres, scale
applied) and ``indices`` uint16 or uint32 (three per triangle, ``index`` says which).

The whole scene gets at most ``TRIANGLES`` triangles, shared out fairly: a mesh under its
share is sent whole, a larger one is simplified by vertex clustering (``simplified``:
``"clustered"``, with ``triangles`` before and after) and, when that cannot get it small
enough, replaced by its bounding box (``"bounding box"``). A reference that does not
resolve or cannot be read is no entry at all: the shape says why (``missing``).
"""

from __future__ import annotations

import base64
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

    from urdflint.model.document import Document
    from urdflint.model.geometry import Shape

TRIANGLES = 150_000  # the scene's budget: a few MB of JSON, drawn at once in software GL
MIN_SHARE = 12  # a bounding box
MIN_CLUSTERED = 60  # below this many triangles a clustered mesh is a blob: its box says more
CLUSTER_ROUNDS = 10  # bisection steps over the grid size


@dataclass
class Entry:
    file: str
    vertices: Any  # (n, 3) float array
    faces: Any  # (m, 3) int array


class MeshTable:
    """The scene's meshes, one entry per resolved file and scale."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.ids: dict[Any, int] = {}
        self.entries: list[Entry] = []

    def add(self, link: str, tag: str, shape: Shape) -> tuple[int | None, str | None]:
        """The entry of the shape's mesh, or ``None`` and why it is not shown."""
        from urdflint.model.inertia import meshes_readable
        from urdflint.sources.meshes import MeshRef, load, resolved

        ref = MeshRef(link, tag, shape)
        if ref.scale is None:
            return None, "the scale is not three non-zero numbers"
        answer = resolved(self.doc, ref.uri)
        if not answer.found or answer.path is None:
            return None, answer.problem or "the file was not found"
        if not meshes_readable():
            return None, "this server cannot read meshes (trimesh is not installed)"
        info = load(self.doc, ref)
        if info is None or not info.ok or info.mesh is None:
            return None, (info.error if info is not None else None) or "the file was not read"
        key = (info.path, ref.scale)
        if key not in self.ids:
            self.ids[key] = len(self.entries)
            self.entries.append(Entry(ref.uri, info.mesh.vertices, info.mesh.faces))
        return self.ids[key], None

    def encode(self, budget: int) -> tuple[list[dict[str, Any]], list[str]]:
        """Every entry as JSON, within ``budget`` triangles in all; notes on what was cut."""
        shares = allot([len(e.faces) for e in self.entries], budget)
        encoded: list[dict[str, Any]] = []
        cut = 0
        for entry, share in zip(self.entries, shares, strict=True):
            found = encode(entry, share)
            cut += found["simplified"] is not None
            encoded.append(found)
        notes = []
        if cut:
            notes.append(
                f"{cut} of {len(encoded)} meshes were simplified to keep the scene under "
                f"{budget} triangles"
            )
        return encoded, notes


def allot(counts: list[int], budget: int) -> list[int]:
    """Triangles for each mesh: its own count when its fair share allows, the smaller
    meshes served first (water filling), never fewer than a bounding box's."""
    shares = [0] * len(counts)
    left = budget
    order = sorted(range(len(counts)), key=counts.__getitem__)
    for done, index in enumerate(order):
        fair = left // (len(counts) - done)
        shares[index] = max(MIN_SHARE, min(counts[index], fair))
        left = max(0, left - shares[index])
    return shares


def encode(entry: Entry, share: int) -> dict[str, Any]:
    import numpy as np

    vertices = np.asarray(entry.vertices, dtype=np.float64)
    faces = np.asarray(entry.faces, dtype=np.int64)
    before = len(faces)
    simplified = None
    if before > share:
        found = cluster(vertices, faces, share)
        simplified = "clustered" if found is not None else "bounding box"
        vertices, faces = found if found is not None else box_mesh(vertices)
    index = "u16" if len(vertices) <= 0xFFFF else "u32"
    return {
        "file": entry.file,
        "positions": _b64(vertices.astype("<f4")),
        "indices": _b64(faces.astype("<u2" if index == "u16" else "<u4")),
        "index": index,
        "vertices": len(vertices),
        "triangles": len(faces),
        "simplified": simplified,
        "original_triangles": before,
    }


def _b64(array: np.ndarray) -> str:
    """An explicitly little-endian array's bytes, as base64 text."""
    return base64.b64encode(array.tobytes()).decode("ascii")


def cluster(vertices: np.ndarray, faces: np.ndarray, target: int) -> tuple[Any, Any] | None:
    """The mesh simplified to at most ``target`` triangles by vertex clustering: vertices
    merged per cell of a grid (at their mean), the triangles that collapse dropped; the
    finest grid that fits is found by bisection. ``None`` when even the coarsest leaves
    too many (or none)."""
    lo = vertices.min(axis=0)
    extent = float((vertices.max(axis=0) - lo).max())
    if not extent > 0 or target < MIN_CLUSTERED:
        return None
    coarse, fine = 2, max(3, int(4 * target**0.5))  # a surface on an n-grid: ~n^2 triangles

    def fitting(cells: int) -> tuple[Any, Any] | None:
        found = _clustered(vertices, faces, lo, extent, cells)
        return found if found is not None and len(found[1]) <= target else None

    best = fitting(fine)
    if best is not None:
        return _compact(vertices, *best)
    for _ in range(CLUSTER_ROUNDS):
        if fine - coarse <= 1:
            break
        cells = (coarse + fine) // 2
        found = fitting(cells)
        if found is not None:
            best, coarse = found, cells
        else:
            fine = cells
    if best is None:
        best = fitting(2)
    return None if best is None else _compact(vertices, *best)


def _clustered(
    vertices: np.ndarray, faces: np.ndarray, lo: np.ndarray, extent: float, cells: int
) -> tuple[Any, Any] | None:
    """Each vertex's cell number on a ``cells``-grid, and the faces left, each once."""
    import numpy as np

    grid = np.minimum(((vertices - lo) / extent * cells).astype(np.int64), cells - 1)
    keys = (grid[:, 0] * cells + grid[:, 1]) * cells + grid[:, 2]
    _, inverse = np.unique(keys, return_inverse=True)
    inverse = inverse.reshape(-1)
    merged = inverse[faces]
    keep = (
        (merged[:, 0] != merged[:, 1])
        & (merged[:, 1] != merged[:, 2])
        & (merged[:, 0] != merged[:, 2])
    )
    merged = merged[keep]
    if not len(merged):
        return None
    _, first = np.unique(np.sort(merged, axis=1), axis=0, return_index=True)
    return inverse, merged[np.sort(first)]


def _compact(vertices: np.ndarray, inverse: np.ndarray, faces: np.ndarray) -> tuple[Any, Any]:
    """The cluster means of the clusters ``faces`` use, and the faces renumbered."""
    import numpy as np

    count = int(inverse.max()) + 1
    sums = np.zeros((count, 3))
    np.add.at(sums, inverse, vertices)
    means = sums / np.bincount(inverse, minlength=count)[:, None]
    used, renumbered = np.unique(faces, return_inverse=True)
    return means[used], renumbered.reshape(faces.shape)


def box_mesh(vertices: np.ndarray) -> tuple[Any, Any]:
    """The 8 corners and 12 triangles (outward) of the vertices' bounding box."""
    import numpy as np

    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    corners = np.array([[(hi if (i >> k) & 1 else lo)[k] for k in range(3)] for i in range(8)])
    faces = np.array(
        [
            [0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6],  # z- and z+
            [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],  # y- and y+
            [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5],  # x- and x+
        ]
    )  # fmt: skip
    return corners, faces
