"""Mesh references and their resolution; the meshes they name, loaded once per run.

The pure-Python half (:func:`references`, :func:`resolved`, and the format tables
in :mod:`urdflint.sources.mesh_formats`) serves the static rules C004, C008 and C009
and never imports trimesh. :func:`load` hands a reference to the run's
:class:`~urdflint.sources.mesh_cache.MeshCache`, which reads each file through
trimesh once per (file, scale).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING
from weakref import WeakKeyDictionary

from urdflint.model.geometry import Shape, read_shape
from urdflint.model.values import has_xacro
from urdflint.sources.mesh_cache import MeshCache, MeshInfo

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document
    from urdflint.sources.resolve import Resolved

__all__ = [
    "MAX_EXTENT",
    "MIN_EXTENT",
    "PART_MAX",
    "PART_MIN",
    "MeshCache",
    "MeshInfo",
    "MeshRef",
    "load",
    "references",
    "resolved",
    "scale_hint",
    "suspicious_size",
]

Vec = tuple[float, float, float]

# REP 103: metres. Robot parts are between a millimetre and ten metres across.
MAX_EXTENT = 10.0
MIN_EXTENT = 0.001
PART_MIN, PART_MAX = 0.01, 2.0  # what a suggested scale should produce


# -- references ----------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class MeshRef:
    """One ``<mesh>`` of a link's ``<visual>`` or ``<collision>``."""

    link: str | None
    tag: str  # "visual" or "collision"
    shape: Shape

    @property
    def element(self) -> etree._Element:
        return self.shape.element

    @property
    def uri(self) -> str:
        return (self.shape.filename or "").strip()

    @property
    def scale(self) -> Vec | None:
        """The scale, or ``None`` when malformed or with a zero component (C003, X004)."""
        s = self.shape.scale
        if s is None or len(s) != 3 or any(v == 0 for v in s):
            return None
        return (s[0], s[1], s[2])


_REFS: WeakKeyDictionary[Document, list[MeshRef]] = WeakKeyDictionary()
_RESOLVED: WeakKeyDictionary[Document, dict[str, Resolved]] = WeakKeyDictionary()


def references(doc: Document) -> list[MeshRef]:
    """Every checkable mesh reference, in document order (empty or xacro filenames are skipped)."""
    found = _REFS.get(doc)
    if found is None:
        found = []
        for link in doc.links:
            for tag in ("visual", "collision"):
                for owner in link.element.findall(tag):
                    shape = read_shape(owner)
                    if shape is None or shape.kind != "mesh" or not shape.filename:
                        continue
                    if not shape.filename.strip() or has_xacro(shape.filename):
                        continue  # C003 and X008 report those
                    found.append(MeshRef(link.name, tag, shape))
        _REFS[doc] = found
    return found


def resolved(doc: Document, uri: str) -> Resolved:
    """Where ``uri`` points for this document (cached per document)."""
    cache = _RESOLVED.setdefault(doc, {})
    answer = cache.get(uri)
    if answer is None:
        answer = cache[uri] = doc.resolver.resolve(uri)
    return answer


def load(doc: Document, ref: MeshRef) -> MeshInfo | None:
    """The loaded mesh of ``ref`` (``None`` when it does not resolve or its scale is unusable)."""
    scale = ref.scale
    if scale is None:
        return None
    answer = resolved(doc, ref.uri)
    if not answer.found or answer.path is None:
        return None
    info: MeshInfo = doc.meshes.load(answer.path, scale)
    return info


def scale_hint(extent: float) -> list[tuple[float, str]]:
    """``(factor, what)`` pairs that would bring a mesh ``extent`` metres across to a
    plausible part size (1 cm to 2 m), most likely first; empty when none does."""
    units: tuple[tuple[float, str], ...]
    if extent > MAX_EXTENT:
        units = ((0.001, "millimetres"), (0.01, "centimetres"))
    elif 0 < extent < MIN_EXTENT:
        units = ((1000.0, "scaled twice, or metres read as millimetres"),)
    else:
        return []
    return [(f, unit) for f, unit in units if PART_MIN <= extent * f <= PART_MAX]


def suspicious_size(info: MeshInfo) -> bool:
    """Whether the largest extent after scale is outside 1 mm .. 10 m (C006's finding)."""
    return info.error is None and not (MIN_EXTENT <= info.largest <= MAX_EXTENT)
