"""A `<mesh filename>` does not lead to a file.

## What it does
Resolves every `<visual>` and `<collision>` mesh the way ROS tools do, without
ROS: `package://NAME/...` through `--package-path NAME=DIR`, `package-paths`
in the configuration, `ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH` and a
`package.xml` search upward from the URDF; `file://` and plain paths relative
to the URDF's folder. Every reference that does not lead to a file is
reported, not only the first, with where urdflint looked and why it failed.
When the folder holds a file with the same name in another case or with
another extension, the message names it.

The severity says how sure the finding is:
- error: the package (or the URDF's folder) was found and the file is not in it;
- warning: the package was not found, while this run can resolve packages
  (package paths are configured, `ROS_PACKAGE_PATH`/`AMENT_PREFIX_PATH` is set,
  or another package of the same file was found);
- info, once per package (or per scheme), naming how many references it
  covers: the package was not found and nothing tells urdflint where packages
  live, or the URI uses a scheme urdflint does not resolve (`model://`,
  `http://`). Those meshes are simply not checked.

## Why is this bad?
A missing mesh breaks every consumer differently: RViz and MoveIt show an
error and leave the link undrawn or uncollidable, Gazebo logs "Unable to find
file" and simulates the link without that geometry (a collision that vanished
lets the robot fall through the floor), PyBullet refuses the whole URDF
("Cannot load URDF file"), MuJoCo stops compiling ("Error opening file"), and
Pinocchio raises "Mesh ... could not be found" for the first missing mesh only.
Stale generated URDFs that still name `.STL` files after the package moved to
`.dae` are a classic case.

## How to fix
Correct the filename (case matters on Linux) or add the missing file. If the
package lives elsewhere, tell urdflint where: `--package-path NAME=DIR`, or

```toml
[tool.urdflint]
package-paths = { my_robot_description = "../my_robot_description" }
```
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.meshes import MeshRef, references, resolved
from urdflint.sources.resolve import SCHEME_RE

FIX_PACKAGE = "Pass --package-path NAME=DIR or set package-paths in the configuration."
FIX_FILE = "Correct the filename (case matters) or add the mesh file."


@rule("C004", "mesh-not-found", Severity.ERROR, fix=FIX_FILE)
def check(doc: Document) -> Iterator[Hit]:
    refs = references(doc)
    if not refs:
        return
    answers = [(ref, resolved(doc, ref.uri)) for ref in refs]
    configured = _configured(doc) or any(
        a.found and _package(ref.uri) is not None for ref, a in answers
    )
    unchecked: dict[str, list[MeshRef]] = {}  # problem -> references, for the notes
    looked: dict[str, tuple[str, ...]] = {}
    for ref, answer in answers:
        if answer.found:
            continue
        problem = answer.problem or "the file was not found"
        what = f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}"
        if problem.startswith("no file at"):
            hint = _nearby(answer.path or _last_path(answer.tried))
            yield Hit(ref.element, f"{what} is missing: {problem}{hint}")
        elif problem.startswith("package ") and configured:
            tried = f" (looked in: {'; '.join(answer.tried)})" if answer.tried else ""
            yield Hit(
                ref.element,
                f"{what} cannot be found: {problem}{tried}",
                fix=FIX_PACKAGE,
                severity=Severity.WARNING,
            )
        elif "outside the allowed folder" in problem:
            yield Hit(ref.element, f"{what} is not readable: {problem}", severity=Severity.WARNING)
        else:  # nothing says where packages live, an unsupported scheme, no URDF folder
            unchecked.setdefault(problem, []).append(ref)
            looked.setdefault(problem, answer.tried)
    for problem, group in unchecked.items():
        first = group[0]
        count = f"its {len(group)} mesh references are" if len(group) > 1 else "its mesh is"
        tried = f" (looked in: {'; '.join(looked[problem])})" if looked[problem] else ""
        yield Hit(
            first.element,
            f"{problem}{tried}, so {count} not checked (first: {first.tag} mesh "
            f"{first.uri!r} of link {q(first.link)})",
            fix=FIX_PACKAGE if problem.startswith("package ") else None,
            severity=Severity.INFO,
        )


def _configured(doc: Document) -> bool:
    """Whether this run has been told where packages live."""
    resolver = doc.resolver
    return bool(resolver.package_paths or resolver.ros_paths or resolver.ament)


def _package(uri: str) -> str | None:
    scheme = SCHEME_RE.match(uri.strip())
    if not scheme or scheme.group(1).lower() != "package":
        return None
    parts = [p for p in uri.strip()[scheme.end() :].split("/") if p]
    return parts[0] if parts else None


def _last_path(tried: tuple[str, ...]) -> Path | None:
    return Path(tried[-1]) if tried else None


def _nearby(path: Path | None) -> str:
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
    stem = path.stem.lower()
    same_case = [n for n in names if n.lower() == wanted]
    if same_case:
        return f"; the folder has {same_case[0]!r} (the case differs)"
    other = [n for n in names if Path(n).stem.lower() == stem and not n.lower().endswith(".mtl")]
    if other:
        return f"; the folder has {', '.join(repr(n) for n in other[:3])}"
    return ""
