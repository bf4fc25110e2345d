"""A ``package://NAME/...`` whose package was not found: how sure that is, and who finds it anyway.

The resolver (:mod:`urdflint.sources.resolve`) answers "package 'NAME' was not found" both when
nothing told urdflint where packages live and when the package exists nowhere. This module
tells the second case apart where it can: ``NAME`` is a folder of the description itself
(beside the URDF's folder or up to two levels above it) that holds files the URI names, and
no ``package.xml`` names it, as in
Poppy's ``package://meshes/pelvis_visual.STL`` written for ``hardware/URDF/meshes/``. No ROS
tool, Gazebo or Drake resolves such a URI; PyBullet does, because it drops ``package://`` and
looks for the rest of the path beside the URDF and in every folder above it
(``UrdfFindMeshFile``), which :func:`pybullet_finds` repeats.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from urdflint.cache import deps
from urdflint.sources.resolve import SCHEME_RE, package_name

if TYPE_CHECKING:
    from urdflint.sources.resolve import Resolver

LEVELS = 3  # the URDF's folder and two above it: pkg/urdf/robot.urdf next to pkg/meshes/


def split(uri: str) -> tuple[str, str] | None:
    """``(NAME, rest)`` of ``package://NAME/rest`` (``None`` for another URI)."""
    text = uri.strip()
    scheme = SCHEME_RE.match(text)
    if not scheme or scheme.group(1).lower() != "package":
        return None
    parts = [p for p in text[scheme.end() :].split("/") if p]
    return (parts[0], "/".join(parts[1:])) if len(parts) > 1 else None


def description_folders(resolver: Resolver, uris: list[str]) -> dict[str, Path]:
    """Package name -> the folder of that name beside the URDF's folder or up to two levels
    above it, for each package of ``uris`` written where a folder of the description belongs:
    the folder is no package of that name and holds at least one of the files named."""
    wanted: dict[str, list[str]] = {}
    for uri in uris:
        found = split(uri)
        if found is not None:
            wanted.setdefault(found[0], []).append(found[1])
    if resolver.base_dir is None:
        return {}
    nearest = _ancestors(resolver, resolver.base_dir.absolute())[:LEVELS]
    answer: dict[str, Path] = {}
    for name, rests in wanted.items():
        for ancestor in nearest:
            folder = ancestor / name
            if _holds(folder, rests) and package_name(folder) != name:
                answer[name] = folder
                break
    return answer


def _holds(folder: Path, rests: list[str]) -> bool:
    return any(_is_file(folder / rest) for rest in rests)


def _is_file(path: Path) -> bool:
    """Whether ``path`` is a file, noted for the analysis cache (a cached result is stale
    once the file appears or goes)."""
    try:
        found = path.is_file()
    except OSError:
        return False
    if found:
        deps.note_file(path)
    else:
        deps.note_absent(path)
    return found


def pybullet_finds(resolver: Resolver, uri: str) -> Path | None:
    """The file PyBullet loads for ``uri``: it strips ``package://`` and tries the rest of
    the path below the URDF's folder and each folder above it, deepest first (the tries
    relative to the working folder are left out: they depend on where it is run)."""
    found = split(uri)
    if found is None or resolver.base_dir is None:
        return None
    rest = f"{found[0]}/{found[1]}"
    for ancestor in _ancestors(resolver, resolver.base_dir.absolute()):
        if _is_file(ancestor / rest):
            return ancestor / rest
    return None


def _ancestors(resolver: Resolver, folder: Path) -> list[Path]:
    """``folder`` and the folders above it, within the resolver's root when it has one."""
    chain = [folder, *folder.parents]
    root = resolver.root
    return [f for f in chain if root is None or f.resolve().is_relative_to(root)]


def searched(resolver: Resolver) -> list[str]:
    """Where packages were looked for beyond the resolver's own list: the package paths
    given (by name), the workspace folders walked, and the ROS environment variables when
    they are not set."""
    found: list[str] = []
    if resolver.package_paths:
        found.append(f"the package paths given ({', '.join(sorted(resolver.package_paths))})")
    roots = _walked(resolver.workspace)
    if roots:
        count = len(resolver.workspace)
        held = f"{count} packages" if count else "no package.xml"
        shown = ", ".join(str(p) for p in roots[:SHOWN_ROOTS])
        if len(roots) > SHOWN_ROOTS:
            shown += f" and {len(roots) - SHOWN_ROOTS} more folders"
        found.append(f"the workspace below {shown} ({held})")
    if resolver.root is None and not resolver.ros_paths and not resolver.ament:
        found.append("ROS_PACKAGE_PATH and AMENT_PREFIX_PATH, which are not set")
    return found


SHOWN_ROOTS = 3  # workspace folders a message names (a run over thousands of files...)


def _walked(workspace: object) -> tuple[Path, ...]:
    """The folders the workspace of a run walks, each as the run was given it (not through
    its symbolic links): once per workspace index, kept with it, not once per message."""
    from urdflint.sources.workspace import roots_for

    known = getattr(workspace, "walked", None)
    if known is not None:
        return known  # type: ignore[no-any-return]
    given = tuple(getattr(workspace, "paths", ()))
    spelled: dict[Path, Path] = {}
    for raw in given:
        folder = raw if raw.is_dir() else raw.parent
        spelled.setdefault(folder.resolve(), folder)
    found = tuple(spelled.get(root, root) for root in roots_for(given))
    if hasattr(workspace, "walked"):
        workspace.walked = found  # type: ignore[attr-defined]
    return found
