"""A `<mesh filename>` does not lead to a file.

## What it does
Resolves every `<visual>` and `<collision>` mesh the way ROS tools do, without
ROS: `package://NAME/...` through `--package-path NAME=DIR`, `package-paths`
in the configuration, `ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH` and a
`package.xml` search upward from the URDF; `file://` and plain paths relative
to the URDF's folder. Every reference that does not lead to a file is
reported, not only the first, with where urdflint looked and why it failed.
When the folder holds a file with the same name and another extension, the
message names it; a path that exists in another letter case is C016's
(path-case-mismatch), not reported here.

The severity says how sure the finding is:
- error: the package (or the URDF's folder) was found and the file is not in it;
- warning: the package was not found, while this run can resolve packages
  (package paths are configured, `ROS_PACKAGE_PATH`/`AMENT_PREFIX_PATH` is set,
  or another package of the same file was found);
- info, once per package (or per scheme), naming how many references it
  covers: the package was not found and nothing tells urdflint where packages
  live, or the URI uses a scheme urdflint does not resolve (`model://`,
  `http://`). Those meshes are simply not checked.
- warning, once per file: `package://box.stl`, a package name with no path in
  it. ROS's resource_retriever (RViz, MoveIt) takes `box.stl` as the package
  name and Gazebo finds no model of that name, while PyBullet strips the scheme
  and reads `box.stl` next to the URDF: the file works in one simulator only.

## Why is this bad?
A missing mesh breaks every consumer differently: RViz and MoveIt show an
error and leave the link undrawn or uncollidable, Gazebo logs "Unable to find
file" and simulates the link without that geometry (a collision that vanished
lets the robot fall through the floor), PyBullet refuses the whole URDF
("cannot find 'X' in any directory in urdf path", then "Cannot load URDF
file"), MuJoCo stops compiling ("Error opening file 'X'"), Drake refuses the
model ("URI 'X' resolved to '...' which does not exist"), and Pinocchio
raises "Mesh X could not be found." when it builds the geometry models, for
the first missing mesh only.
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

from lxml import etree
from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import mujoco_compiler
from urdflint.model.document import Document
from urdflint.model.effects import Effect, single
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.meshes import FileRef, references, unresolved

FIX_PACKAGE = "Pass --package-path NAME=DIR or set package-paths in the configuration."
FIX_FILE = "Correct the filename (case matters) or add the mesh file."


@rule("C004", "mesh-not-found", Severity.ERROR, fix=FIX_FILE, effects=single(K.MISSING_MESH))
def check(doc: Document) -> Iterator[Hit]:
    refs = [
        FileRef(ref.element, ref.uri, f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}")
        for ref in references(doc)
    ]
    for problem in unresolved(doc, refs, "mesh"):
        fix = FIX_PACKAGE if problem.package_fix else None
        yield Hit(
            problem.element,
            problem.message,
            fix=fix,
            severity=problem.severity,
            effects=_effects(doc, problem.element),
        )


def _effects(doc: Document, mesh: etree._Element | None) -> dict[str, Effect]:
    """MuJoCo's URDF import discards visuals (``discardvisual`` defaults to true): a
    missing visual mesh costs it nothing (observed on six corpus robots)."""
    table = dict(K.MISSING_MESH)
    owner = mesh.getparent() if mesh is not None else None
    owner = owner.getparent() if owner is not None else None
    visual = owner is not None and owner.tag == "visual"
    if visual and mujoco_compiler(doc, "discardvisual", "true").lower() not in ("false", "0"):
        del table["mujoco"]
    return table
