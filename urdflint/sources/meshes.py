"""Mesh and texture references and their resolution; the meshes they name, loaded once per run.

The pure-Python half (:func:`references`, :func:`textures`, :func:`resolved`,
:func:`unresolved` and the format tables in :mod:`urdflint.sources.mesh_formats`) serves
the static rules C004, C008, C009 and C012 and never imports trimesh. :func:`load` hands a
reference to the run's :class:`~urdflint.sources.mesh_cache.MeshCache`, which reads each
file through trimesh once per (file, scale).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING
from weakref import WeakKeyDictionary

from urdflint.model.finding import Severity
from urdflint.model.geometry import Shape, read_shape
from urdflint.model.structure import q
from urdflint.model.values import has_xacro
from urdflint.sources.case import case_variant
from urdflint.sources.mesh_cache import MeshCache, MeshInfo
from urdflint.sources.resolve import NO_PACKAGE_PATH, SCHEME_RE
from urdflint.sources.unknown_package import description_folders, pybullet_finds, searched

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document
    from urdflint.sources.resolve import Resolved

__all__ = [
    "MAX_EXTENT",
    "MIN_EXTENT",
    "PART_MAX",
    "PART_MIN",
    "FileProblem",
    "FileRef",
    "MeshCache",
    "MeshInfo",
    "MeshRef",
    "load",
    "references",
    "resolved",
    "scale_hint",
    "suspicious_size",
    "textures",
    "unresolved",
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


def references(doc: Document) -> list[MeshRef]:
    """Every checkable mesh reference, in document order (empty or xacro filenames are skipped)."""
    found = _REFS.get(doc)
    if found is None:
        found = []
        for link in doc.links:
            for tag in ("visual", "collision"):
                for owner in link.visuals if tag == "visual" else link.collisions:
                    shape = read_shape(owner)
                    if shape is None or shape.kind != "mesh" or not shape.filename:
                        continue
                    if not shape.filename.strip() or has_xacro(shape.filename):
                        continue  # C003 and X008 report those
                    found.append(MeshRef(link.name, tag, shape))
        _REFS[doc] = found
    return found


@dataclass(frozen=True, slots=True)
class FileRef:
    """A file a description names: ``what`` describes it for messages."""

    element: etree._Element
    uri: str
    what: str  # "visual mesh 'a.stl' of link 'arm'"


def textures(doc: Document) -> list[FileRef]:
    """Every ``<texture filename>`` of a robot-level or a visual's ``<material>``, in
    document order (empty and xacro filenames are skipped; read once per document, the list
    is shared: do not change it)."""
    found = doc.memo.get("meshes.textures")
    if found is None:
        found = doc.memo["meshes.textures"] = _textures(doc)
    return found  # type: ignore[no-any-return]


def _textures(doc: Document) -> list[FileRef]:
    found: list[FileRef] = []
    owners = [(m, f"material {q(m.get('name'))}") for m in doc.materials]
    for link in doc.links:
        for visual in link.visuals:
            material = visual.find("material")
            if material is not None:
                owners.append((material, f"a visual of link {q(link.name)}"))
    for material, owner in owners:
        for texture in material.findall("texture"):
            uri = (texture.get("filename") or "").strip()
            if uri and not has_xacro(uri):
                found.append(FileRef(texture, uri, f"texture {uri!r} of {owner}"))
    return found


def resolved(doc: Document, uri: str) -> Resolved:
    """Where ``uri`` points for this document (cached per document)."""
    cache = doc.memo.get("meshes.resolved")
    if cache is None:
        cache = doc.memo["meshes.resolved"] = {}
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


# -- files that do not resolve (C004 for meshes, C012 for textures) ---------------------------


@dataclass(frozen=True, slots=True)
class FileProblem:
    """A finding about a file reference: the rule turns it into a hit as it is."""

    element: etree._Element
    message: str
    severity: Severity | None = None  # None: the rule's own (error)
    package_fix: bool = False  # the fix is to say where packages live
    package: str | None = None  # a package nobody resolves (not merely one not configured)
    pybullet: bool = False  # with ``package``: PyBullet's own search finds the file anyway
    folder: Path | None = None  # with ``package``: the description's folder of that name


def unresolved(doc: Document, refs: list[FileRef], noun: str) -> Iterator[FileProblem]:
    """What is wrong with each reference that does not lead to a file.

    An error when the package (or the URDF's folder) was found and the file is not in
    it; a warning, with the package's name (:func:`unknown_package`: the rule may weigh it
    per target), when the package was not found while this run can resolve packages or
    when it names a folder of the description; otherwise one info note per problem
    (unknown package, unsupported scheme) naming how many ``noun`` references it leaves
    unchecked.
    """
    answers = [(ref, resolved(doc, ref.uri)) for ref in refs]
    configured = packages_configured(doc) or any(
        a.found and package_of(ref.uri) is not None for ref, a in answers
    )
    folders = description_folders(doc.resolver, [r.uri for r, a in answers if not a.found])
    unchecked: dict[str, list[FileRef]] = {}  # problem -> references, for the notes
    looked: dict[str, tuple[str, ...]] = {}
    for ref, answer in answers:
        if answer.found:
            continue
        problem = answer.problem or "the file was not found"
        if problem.startswith("no file at"):
            last = Path(answer.tried[-1]) if answer.tried else None
            wanted = answer.path or last
            if wanted is not None and case_variant(wanted.absolute()) is not None:
                continue  # C016 reports a name in another letter case
            hint = nearby(answer.path or last)
            yield FileProblem(ref.element, f"{ref.what} is missing: {problem}{hint}")
        elif problem.startswith("package ") and (configured or package_of(ref.uri) in folders):
            folder = folders.get(package_of(ref.uri) or "")
            yield unknown_package(doc, ref, answer, folder, mesh=noun == "mesh")
        elif "outside the allowed folder" in problem:
            message = f"{ref.what} is not readable: {problem}"
            yield FileProblem(ref.element, message, Severity.WARNING)
        else:  # nothing says where packages live, an unsupported scheme, no URDF folder
            unchecked.setdefault(problem, []).append(ref)
            looked.setdefault(problem, answer.tried)
    for problem, group in unchecked.items():
        count = f"its {len(group)} {noun} references are" if len(group) > 1 else f"its {noun} is"
        where = [*looked[problem]]
        if problem.startswith("package "):
            where += searched(doc.resolver)
        tried = f" (looked in: {'; '.join(where)})" if where else ""
        yield FileProblem(
            group[0].element,
            f"{problem}{tried}, so {count} not checked (first: {group[0].what})",
            Severity.WARNING if problem == NO_PACKAGE_PATH else Severity.INFO,
            package_fix=problem.startswith("package "),
        )


def unknown_package(
    doc: Document, ref: FileRef, answer: Resolved, folder: Path | None, mesh: bool = True
) -> FileProblem:
    """A reference to a package that was not found where this run looks for packages, or
    that names a folder of the description: where it was looked for, and (for a ``mesh``)
    whether PyBullet's own search finds the file."""
    resolver = doc.resolver
    looked = [*answer.tried, *searched(resolver)]
    tried = f" (looked in: {'; '.join(looked)})" if looked else ""
    message = f"{ref.what} cannot be found: {answer.problem}{tried}"
    name = package_of(ref.uri)
    if folder is not None:
        message += f"; {name!r} is a folder of the description ({folder}), not a package"
    found = pybullet_finds(resolver, ref.uri) if mesh else None
    if found is not None:
        message += f"; PyBullet, which drops package://, reads {found}"
    elif folder is not None:
        message += nearby(folder.parent / _inside(ref.uri))
    return FileProblem(ref.element, message, Severity.WARNING, True, name, bool(found), folder)


def _inside(uri: str) -> str:
    """``NAME/rest`` of ``package://NAME/rest``."""
    return "/".join(p for p in uri.strip()[len("package://") :].split("/") if p)


def packages_configured(doc: Document) -> bool:
    """Whether this run has been told where packages live."""
    resolver = doc.resolver
    return bool(resolver.package_paths or resolver.ros_paths or resolver.ament)


def package_of(uri: str) -> str | None:
    """``NAME`` of a ``package://NAME/...`` URI."""
    scheme = SCHEME_RE.match(uri.strip())
    if not scheme or scheme.group(1).lower() != "package":
        return None
    parts = [p for p in uri.strip()[scheme.end() :].split("/") if p]
    return parts[0] if parts else None


def nearby(path: Path | None) -> str:
    """``; the folder has 'x.dae'`` when a file differs only by case or extension."""
    if path is None:
        return ""
    folder = path.parent
    try:
        if not folder.is_dir():
            return f"; the folder {folder} does not exist"
        names = sorted(p.name for p in folder.iterdir() if p.is_file())
    except OSError:
        return ""
    if len(names) > 5000:
        return ""
    wanted = path.name.lower()
    same_case = [n for n in names if n.lower() == wanted]
    if same_case:
        return f"; the folder has {same_case[0]!r} (the case differs)"
    stem = path.stem.lower()
    other = [n for n in names if Path(n).stem.lower() == stem and not n.lower().endswith(".mtl")]
    if other:
        return f"; the folder has {', '.join(repr(n) for n in other[:3])}"
    return ""
