"""Meshes loaded once per run through trimesh (imported lazily, as is numpy).

The :class:`MeshCache` loads a file with ``trimesh.load(path, force="mesh")`` the
first time a rule asks for it at a given scale, and keeps the answer for the
whole run: C005, C006, C007, I007 and I008 share one load per (file, scale).
Nothing here raises on a bad file: what trimesh cannot read becomes
:attr:`MeshInfo.error`.

A Collada file's ``<asset><unit meter="..."/>`` is applied on top of the URDF scale, as
Gazebo (``ColladaLoader::Load`` scales the mesh by it), RViz (``getMeshUnitRescale``) and
PyBullet do; trimesh only records it, so the vertices it returns are in the file's units.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

from urdflint.model import optional
from urdflint.sources.mesh_formats import TRIMESH_TYPES, collada_unit, format_name
from urdflint.sources.mesh_info import (
    ZERO,
    Mat,
    MeshInfo,
    Solid,
    Vec,
    facts,
    from_facts,
    quiet_numpy,
    vec,
)

__all__ = ["ZERO", "Mat", "MeshCache", "MeshInfo", "Solid", "Vec", "quiet_numpy"]

MAX_MESH_BYTES = 100 * 2**20
_QUIET = logging.NullHandler()


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    first = text[0].strip() if text else ""
    message = f"{type(exc).__name__}: {first}" if first else type(exc).__name__
    return message if len(message) <= 200 else message[:197] + "..."


def trimesh_load(path: Path, file_type: str, resolver: Any = None) -> Any:
    """The one trimesh call urdflint makes per file (the bench times the same call)."""
    import trimesh

    return trimesh.load(
        str(path), file_type=file_type, force="mesh", resolver=resolver, skip_materials=True
    )


KEPT = 4096  # meshes a run keeps described (the least recently used go: a dataset run)
HEAVY_BYTES = 256 * 2**20  # of those, the trimesh data kept for the most recent (estimated)


class MeshCache:
    """Meshes loaded during one run, by resolved path and scale.

    ``root`` confines every file access (the HTTP service): a mesh outside it is not
    read, and the files a mesh refers to (an OBJ's ``.mtl``, a glTF's buffers) are
    looked up only inside it. With ``cache`` (:class:`urdflint.cache.Cache`), a mesh whose
    content was seen before (by this process, or by any run that shares the cache folder)
    is described from its stored facts without reading it through trimesh.

    Memory stays bounded over a dataset run: at most :data:`KEPT` meshes are described,
    and only the most recently used keep their trimesh data, up to :data:`HEAVY_BYTES`;
    an older one keeps the facts computed so far, and is read again only for a fact
    never asked of it before.
    """

    def __init__(
        self, root: Path | None = None, max_bytes: int = MAX_MESH_BYTES, cache: Any = None
    ) -> None:
        self.root = root.resolve() if root is not None else None
        self.max_bytes = max_bytes
        self.cache = cache if cache is not None and cache.usable else None
        # trimesh logs skipped textures and broken references as warnings; without a handler
        # Python would print them on stderr. Findings carry what matters.
        logging.getLogger("trimesh").addHandler(_QUIET)
        self._cache: dict[tuple[Path, Vec], MeshInfo] = {}
        self._heavy: dict[tuple[Path, Vec], int] = {}  # meshes holding trimesh data: bytes
        self._heavy_bytes = 0
        self.loads = 0  # trimesh.load calls made
        self.bytes = 0  # bytes of the files given to trimesh
        self.reused = 0  # meshes described from stored facts

    def load(self, path: Path, scale: tuple[float, float, float] = (1.0, 1.0, 1.0)) -> MeshInfo:
        try:
            real = path.resolve()
        except (OSError, RuntimeError):
            real = path
        key = (real, (float(scale[0]), float(scale[1]), float(scale[2])))
        info = self._cache.get(key)
        if info is None:
            info = self._cache[key] = self._load(real, key[1])
            if len(self._cache) > KEPT:  # a dataset run: the least recently used goes
                gone = next(iter(self._cache))
                del self._cache[gone]
                self._heavy_bytes -= self._heavy.pop(gone, 0)
            self._weigh(key, info)
            return info
        self._cache[key] = self._cache.pop(key)  # most recently used last
        self._weigh(key, info)
        if self.cache is not None:
            from urdflint.cache import deps

            deps.note_file(real)
        return info

    def _weigh(self, key: tuple[Path, Vec], info: MeshInfo) -> None:
        self._count(key, _weight(info._mesh))

    def _count(self, key: tuple[Path, Vec], weight: int) -> None:
        """Count ``weight`` bytes of trimesh data for ``key``, the most recent; beyond the
        budget, the least recently used meshes let theirs go (their facts stay)."""
        self._heavy_bytes -= self._heavy.pop(key, 0)
        if not weight:
            return
        self._heavy[key] = weight
        self._heavy_bytes += weight
        while self._heavy_bytes > HEAVY_BYTES and len(self._heavy) > 1:
            old = next(iter(self._heavy))
            self._heavy_bytes -= self._heavy.pop(old)
            found = self._cache.get(old)
            if found is not None:
                found.release(self._reader(old[0], found.format, old[1]))

    def _reader(self, path: Path, ext: str, scale: Vec) -> Any:
        """Read a mesh known by its facts again (counted in the budget)."""

        def read() -> Any:
            mesh = self._mesh_of(path, ext, scale)
            if (path, scale) in self._cache:
                self._count((path, scale), _weight(mesh))
            return mesh

        return read

    def __len__(self) -> int:
        return len(self._cache)

    def _load(self, path: Path, scale: Vec) -> MeshInfo:
        ext = path.suffix.lower().lstrip(".")
        fail = _Failure(path, ext)
        if self.root is not None and not path.is_relative_to(self.root):
            return fail("the file lies outside the allowed folder")
        try:
            info = path.stat()
        except OSError as exc:
            from urdflint.cache import deps

            deps.note_absent(path)
            return fail(f"cannot read the file ({exc.strerror or exc})")
        size = info.st_size
        if ext not in TRIMESH_TYPES:
            return fail(f"urdflint cannot read {format_name(ext)} meshes", unsupported=True)
        if size > self.max_bytes:
            return fail(
                f"the file is {size / 2**20:.0f} MB, over the {self.max_bytes / 2**20:.0f} MB "
                "limit for reading meshes",
                unsupported=True,
            )
        if size == 0:
            return fail("the file is empty")
        if self.cache is None or ext == "gltf":  # a glTF's buffers are other files
            return self._read(path, ext, scale, size)
        return self._cached(path, ext, scale, info)

    def _cached(self, path: Path, ext: str, scale: Vec, info: Any) -> MeshInfo:
        """The mesh described from the facts stored for its content, else read and stored."""
        from urdflint import cache as caching
        from urdflint.cache import deps

        cache = self.cache
        assert cache is not None
        digest = cache.digest(str(path), info)
        deps.note_file(path)
        if digest is None:
            return self._read(path, ext, scale, info.st_size)
        key = (f"{digest}.{ext}", scale)
        stored_as = cache.key("mesh", *key)

        def store(found: dict[str, Any]) -> None:
            caching.remember(key, found)
            cache.defer("mesh", stored_as, found)

        found = caching.MEMORY.get(key)
        if found is None:
            found = cache.get("mesh", *key)
            if isinstance(found, dict):
                caching.remember(key, found)
        if isinstance(found, dict):
            try:
                self.reused += 1
                return from_facts(path, found, self._reader(path, ext, scale), store)
            except (KeyError, TypeError):  # an entry of another shape: read the file again
                pass
        described = self._read(path, ext, scale, info.st_size)
        object.__setattr__(described, "_stored", store)
        store(facts(described))
        return described

    def _mesh_of(self, path: Path, ext: str, scale: Vec) -> Any:
        """The trimesh mesh of a file known by its facts, when a new fact needs it."""
        found = self._read(path, ext, scale, 0)
        return found._mesh

    def _read(self, path: Path, ext: str, scale: Vec, size: int) -> MeshInfo:
        fail = _Failure(path, ext)
        unit = 1.0
        if ext == "dae":
            if not optional.available("collada"):
                return fail("reading Collada needs pycollada (pip install pycollada)", True)
            if _has_doctype(path):
                return fail("the Collada file declares a DOCTYPE or entities; it was not read")
            unit = collada_unit(path)
        try:
            self.loads += 1
            self.bytes += size
            with quiet_numpy():
                mesh = trimesh_load(path, TRIMESH_TYPES[ext], self._resolver(path))
                if ext == "dae" and len(mesh.faces) == 0:
                    mesh = _collada_geometries(path) or mesh
                return _describe(mesh, path, ext, scale, size, unit)
        except Exception as exc:  # any parse failure becomes a finding, never a crash
            return fail(f"trimesh could not read it ({_one_line(exc)})")
        except RecursionError as exc:  # pragma: no cover - deeply nested scenes
            return fail(f"trimesh could not read it ({_one_line(exc)})")

    def _resolver(self, path: Path) -> Any:
        return assets_resolver(path, self.root)


def _weight(mesh: Any) -> int:
    """About the bytes a trimesh mesh holds once the rules have used it: 8 times its
    vertices and faces (what trimesh derives and keeps: normals, edges, the convex hull
    and its own: 255 corpus meshes, 25 MB of vertices and faces, took 231 MB)."""
    if mesh is None:
        return 0
    try:
        return 8 * (int(mesh.vertices.nbytes) + int(mesh.faces.nbytes))
    except (AttributeError, TypeError):
        return 0


class _Failure:
    def __init__(self, path: Path, ext: str) -> None:
        self.path, self.ext = path, ext

    def __call__(self, reason: str, unsupported: bool = False) -> MeshInfo:
        return MeshInfo(self.path, self.ext, error=reason, unsupported=unsupported)


def _collada_geometries(path: Path) -> Any:
    """The Collada file read again without its material bindings.

    pycollada drops a scene node whose material binding names a missing texture surface
    ("Missing surface ..."), and trimesh then sees an empty scene, while PyBullet, Gazebo
    and RViz still draw the geometry. Materials do not change the shape: without the
    bindings the scene, its node transforms included, reads whole. ``None`` when that
    gives no triangles either.
    """
    import io

    import trimesh
    from lxml import etree

    from urdflint.model.document import make_parser

    root = etree.fromstring(path.read_bytes(), make_parser())
    bindings = list(root.iter("{*}bind_material", "bind_material"))
    if not bindings:
        return None
    for el in bindings:
        el.getparent().remove(el)
    data = etree.tostring(root)
    mesh: Any = trimesh.load(io.BytesIO(data), file_type="dae", force="mesh", skip_materials=True)
    return mesh if len(mesh.faces) else None


def _has_doctype(path: Path) -> bool:
    try:
        with path.open("rb") as handle:
            head = handle.read(1 << 16)
    except OSError:
        return False
    return b"<!DOCTYPE" in head or b"<!ENTITY" in head


def _describe(
    mesh: Any, path: Path, ext: str, scale: Vec, size: int, unit: float = 1.0
) -> MeshInfo:
    import numpy as np

    faces, vertices = len(mesh.faces), len(mesh.vertices)
    if faces == 0:
        return MeshInfo(path, ext, vertices=vertices, size=size, error=_empty_reason(path))
    if not np.isfinite(mesh.vertices).all():
        return MeshInfo(
            path, ext, faces, vertices, size=size, error="it has NaN or infinite vertices"
        )
    factors = (scale[0] * unit, scale[1] * unit, scale[2] * unit)
    if factors != (1.0, 1.0, 1.0):
        matrix = np.eye(4)
        matrix[0, 0], matrix[1, 1], matrix[2, 2] = factors
        mesh.apply_transform(matrix)  # flips the winding for a mirroring scale
    lo, hi = mesh.bounds
    return MeshInfo(
        path,
        ext,
        faces,
        vertices,
        vec(lo),
        vec(hi),
        vec(hi - lo),
        size=size,
        unit=unit,
        _mesh=mesh,
    )


def _empty_reason(path: Path) -> str:
    """Why a file gave no triangles, when its first bytes tell (an LFS pointer, a web page)."""
    try:
        with path.open("rb") as handle:
            head = handle.read(512).lstrip().lower()
    except OSError:
        head = b""
    if head.startswith(b"version https://git-lfs"):
        return "the file is a Git LFS pointer, not the mesh (run git lfs pull)"
    if head.startswith((b"<!doctype html", b"<html")):
        return "the file is an HTML page, not a mesh"
    return "the file holds no triangles"


def assets_resolver(path: Path, root: Path | None = None) -> Any:
    """What trimesh may read besides the mesh itself.

    Only glTF needs other files for its geometry (``.bin`` buffers): they are read from
    the mesh's folder, inside ``root`` when set. Everything else (an OBJ's ``.mtl``,
    textures of Collada and OBJ files) is refused: urdflint needs the triangles only, and
    decoding texture images would double the loading time.
    """
    from trimesh.resolvers import FilePathResolver, Resolver

    class NoAssets(Resolver):  # type: ignore[misc]
        def __init__(self) -> None:
            pass

        def get(self, key: str) -> bytes:
            raise KeyError(f"{key!r}: urdflint reads no mesh assets")

        def write(self, name: str, data: Any) -> None:
            raise KeyError(name)

        def namespaced(self, namespace: str) -> NoAssets:
            return self

        def keys(self) -> list[str]:
            return []

    class Confined(FilePathResolver):  # type: ignore[misc]
        def get(self, name: str) -> bytes:
            target = (Path(self.parent) / name.strip()).resolve()
            if root is not None and not target.is_relative_to(root):
                raise KeyError(f"{name!r} lies outside the allowed folder")
            data: bytes = super().get(name)
            return data

    if path.suffix.lower() == ".gltf":
        return Confined(str(path.parent))
    return NoAssets()
