"""What urdflint knows of one mesh file: :class:`MeshInfo`, its facts and mass properties.

:class:`~urdflint.sources.mesh_cache.MeshCache` makes them; the facts computed on demand
(watertightness, volume, mass properties, convex hull) are plain values, so the analysis
cache (:mod:`urdflint.cache`) can keep them by the file's content.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

Vec = tuple[float, float, float]
Mat = tuple[Vec, Vec, Vec]
ZERO: Vec = (0.0, 0.0, 0.0)


@dataclass(frozen=True, slots=True)
class Solid:
    """Mass properties at unit density: of the mesh itself, or of its convex hull."""

    kind: str  # "mesh" or "convex hull"
    volume: float  # m^3
    com: Vec  # in the mesh frame (after scale)
    tensor: Mat  # about the centre of mass, at density 1 kg/m^3

    def inertia(self, mass: float) -> Mat:
        k = mass / self.volume
        return tuple(tuple(v * k for v in row) for row in self.tensor)  # type: ignore[return-value]


@dataclass(frozen=True)
class MeshInfo:
    """What one mesh file is, after ``scale``; ``error`` says why it could not be read.

    ``unsupported`` marks errors that are not the file's fault (a format trimesh does
    not read, a loader that is not installed): C009 or nobody reports those.

    The facts computed on demand (watertightness, volume, mass properties, convex hull) are
    kept in ``_memo``; with the analysis cache they are stored by the file's content
    (:func:`facts`), and a mesh whose facts were stored is not read again: :attr:`mesh`
    loads it only when a fact is asked for that was never computed.
    """

    path: Path
    format: str
    faces: int = 0
    vertices: int = 0
    lo: Vec = ZERO
    hi: Vec = ZERO
    extents: Vec = ZERO
    error: str | None = None
    unsupported: bool = False
    size: int = 0  # bytes on disk
    unit: float = 1.0  # metres per file unit (a Collada <unit meter>), already applied
    _mesh: Any = field(default=None, repr=False, compare=False)
    _memo: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    _loader: Any = field(default=None, repr=False, compare=False)  # () -> trimesh mesh
    _stored: Any = field(default=None, repr=False, compare=False)  # (facts) -> None

    @property
    def ok(self) -> bool:
        return self.error is None

    @property
    def largest(self) -> float:
        return max(self.extents)

    @property
    def mesh(self) -> Any:
        """The trimesh mesh (after scale), read from the file if only its facts were known."""
        if self._mesh is None and self._loader is not None and self.ok:
            object.__setattr__(self, "_mesh", self._loader())
        return self._mesh

    def release(self, loader: Any) -> None:
        """Let the trimesh data go (memory), keeping the facts: ``loader`` reads it again
        when a fact never computed is asked for."""
        if self._mesh is not None:
            object.__setattr__(self, "_loader", loader)
            object.__setattr__(self, "_mesh", None)

    def _remember(self, name: str, value: Any) -> None:
        self._memo[name] = value
        if self._stored is not None:
            self._stored(facts(self))

    @property
    def watertight(self) -> bool:
        """Every edge is shared by exactly two triangles (computed on first use)."""
        if "watertight" not in self._memo:
            with quiet_numpy():
                self._remember("watertight", bool(self.ok and self.mesh.is_watertight))
        found: bool = self._memo["watertight"]
        return found

    @property
    def volume(self) -> float | None:
        """Enclosed volume in m³: only for watertight, consistently wound meshes."""
        if "volume" not in self._memo:
            self._remember("volume", _volume(self.mesh) if self.watertight else None)
        found: float | None = self._memo["volume"]
        return found

    def solid(self) -> Solid | None:
        """Mass properties of the mesh when it encloses a volume, else of its convex hull."""
        if "solid" not in self._memo:
            volume = self.volume if self.ok else None
            self._remember("solid", _solid(self.mesh, volume) if self.ok else None)
        found: Solid | None = self._memo["solid"]
        return found

    def hull_points(self) -> Any:
        """The vertices of the convex hull (the vertices themselves when qhull fails on flat
        input), an ``(n, 3)`` numpy array, or ``None`` when there are none."""
        import numpy as np

        if "hull" not in self._memo:
            points = None
            if self.ok:
                with quiet_numpy():
                    try:
                        points = np.asarray(self.mesh.convex_hull.vertices, dtype=float)
                    except Exception:  # qhull on flat or degenerate input
                        points = np.asarray(self.mesh.vertices, dtype=float)
            found = None
            if points is not None and len(points):
                found = points.astype(np.float64).tobytes()
            self._remember("hull", found)
        raw = self._memo["hull"]
        return None if raw is None else np.frombuffer(raw, dtype=np.float64).reshape(-1, 3)

    def mujoco(self, scale: Vec) -> Any:
        """The mesh as MuJoCo compiles it at ``scale`` (this mesh's:
        :class:`urdflint.sources.mujoco_mesh.Compiled`), ``None`` when it is not read here."""
        from urdflint.sources.mujoco_mesh import Compiled, compile_mesh

        if "mujoco" not in self._memo:
            found = compile_mesh(self.path, scale) if self.ok else None
            self._remember("mujoco", None if found is None else list(_fields(found)))
        raw = self._memo["mujoco"]
        return None if raw is None else Compiled(*raw)

    def inertia(self, mass: float) -> tuple[Mat, str] | None:
        """Inertia tensor about the centre of mass at ``mass`` kg, and which solid gave it."""
        solid = self.solid()
        return None if solid is None else (solid.inertia(mass), solid.kind)

    def center_mass(self) -> tuple[Vec, str] | None:
        """Centre of mass (uniform density) in the mesh frame, and which solid gave it."""
        solid = self.solid()
        return None if solid is None else (solid.com, solid.kind)


FACTS = ("format", "faces", "vertices", "lo", "hi", "extents", "error", "unsupported", "size",
         "unit")  # fmt: skip


def facts(info: MeshInfo) -> dict[str, Any]:
    """What the cache keeps of a mesh: plain values, no trimesh object."""
    found = {name: getattr(info, name) for name in FACTS}
    found["memo"] = dict(info._memo)
    return found


def from_facts(path: Path, found: dict[str, Any], loader: Any, stored: Any) -> MeshInfo:
    values = {name: found[name] for name in FACTS}
    memo = dict(found.get("memo") or {})
    return MeshInfo(path, **values, _memo=memo, _loader=loader, _stored=stored)


def _fields(found: Any) -> tuple[Any, ...]:
    return tuple(getattr(found, name) for name in found.__slots__)


def vec(values: Any) -> Vec:
    return (float(values[0]), float(values[1]), float(values[2]))


def _solid(mesh: Any, volume: float | None) -> Solid | None:
    with quiet_numpy():
        return _solid_of(mesh, volume)


def _solid_of(mesh: Any, volume: float | None) -> Solid | None:
    try:
        if volume is not None and volume > 0:
            return _properties(mesh, "mesh")
        hull = mesh.convex_hull
        if hull is None or len(hull.faces) == 0 or not hull.volume > 0:
            return None
        return _properties(hull, "convex hull")
    except Exception:  # qhull on flat or degenerate input
        return None


def _properties(mesh: Any, kind: str) -> Solid | None:
    props = mesh.mass_properties
    volume = float(props["volume"])
    if not (volume > 0 and math.isfinite(volume)):
        return None
    tensor = tuple(vec(row) for row in props["inertia"])
    return Solid(kind, volume, vec(props["center_mass"]), tensor)  # type: ignore[arg-type]


@contextmanager
def quiet_numpy() -> Iterator[None]:
    """Degenerate meshes make numpy divide by zero: the result is checked, not printed."""
    import numpy as np

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        yield


def _volume(mesh: Any) -> float | None:
    with quiet_numpy():
        return _volume_of(mesh)


def _volume_of(mesh: Any) -> float | None:
    try:
        if not mesh.is_winding_consistent:
            return None
        value = float(mesh.volume)
        if value < 0:  # consistently inward normals: the same solid
            mesh.invert()
            value = -value
    except Exception:
        return None
    return value if value > 0 and math.isfinite(value) else None
