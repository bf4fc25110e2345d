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

The severity says how sure the finding is, and what the targets do:
- error: the package (or the URDF's folder) was found and the file is not in it;
- a package that was not found, while this run can resolve packages (package paths are
  configured, `ROS_PACKAGE_PATH`/`AMENT_PREFIX_PATH` is set, or another package of the
  same file was found), or whose name is a folder of the description: a folder beside
  the URDF's folder or up to two levels above it that holds files the URIs name, and that
  no `package.xml` names (Poppy's `package://meshes/pelvis_visual.STL`, written for
  `hardware/URDF/meshes/`). Each reference is reported, naming the package and where
  urdflint looked (the package paths given, the workspace folders walked, the ROS
  variables), with the severity of the worst of the selected targets' effects: an error
  for MuJoCo, Drake, PyBullet and Pinocchio, which refuse the model; a warning for Gazebo
  and Isaac Sim, which load it without the mesh; an info for ROS (robot_state_publisher
  does not read meshes, RViz draws nothing there). PyBullet does not count when it finds
  the file anyway: it drops `package://` and tries the rest of the path beside the URDF
  and in every folder above it, so it loads Poppy's `package://meshes/...` from
  `robots/../meshes/`, and the message says which file it reads;
- info, once per package (or per scheme), naming how many references it
  covers and where urdflint looked: the package was not found and nothing tells urdflint
  where packages live, or the URI uses a scheme urdflint does not resolve (`model://`,
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

A package that exists nowhere is refused the same way (observed on Poppy's
`Poppy_Humanoid.URDF`, 52 references to `package://meshes/...`): Drake 1.51 says
"URI 'package://meshes/pelvis_visual.STL' refers to unknown package 'meshes'" (it
resolves only the packages of its `PackageMap`); MuJoCo 4.0 opens the URI as a file path,
"Error opening file 'package:/meshes/pelvis_respondable.STL'" (it resolves no
`package://` URI: only collision meshes count, as it discards visuals); Pinocchio 4.1 says
"Mesh package://meshes/pelvis_respondable.STL could not be found." unless one of its
package directories holds a `meshes/` folder. PyBullet 3.2.7 loads the model once the
letter case of Poppy's files is right, finding `../meshes/pelvis_visual.STL`, and refuses
the original at the first of its ten `.stl` files named `.STL` ("cannot find
'meshes/l_hip_respondable.STL' in any directory in urdf path", "Cannot load URDF file").

## How to fix
Correct the filename (case matters on Linux) or add the missing file. If the
package lives elsewhere, tell urdflint where: `--package-path NAME=DIR`, or

```toml
[tool.urdflint]
package-paths = { my_robot_description = "../my_robot_description" }
```

When the "package" is a folder of the description, name the package that holds it
(`package://my_robot_description/meshes/pelvis_visual.STL`, with a `package.xml` at its
root) or write the path relative to the URDF (`../meshes/pelvis_visual.STL`).
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model import effects as fx
from urdflint.model.bodies import mujoco_compiler
from urdflint.model.document import Document
from urdflint.model.effects import Effect
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.sources.meshes import FileProblem, FileRef, references, unresolved

FIX_PACKAGE = "Pass --package-path NAME=DIR or set package-paths in the configuration."
FIX_FILE = "Correct the filename (case matters) or add the mesh file."
FIX_FOLDER = (
    "Name the package that holds the mesh (package://PACKAGE/meshes/...) or a path relative "
    "to the URDF; or pass --package-path NAME=DIR if such a package exists."
)

# A package nobody resolves (observed on Poppy's package://meshes/..., issue 29).
UNKNOWN_PACKAGE: dict[str, Effect] = {
    **K.gazebo(fx.no_geometry("Gazebo finds no such package on its paths and shows nothing")),
    "mujoco": fx.refused("\"Error opening file 'package:/meshes/...'\": it resolves no package"),
    "drake": fx.refused("\"URI 'package://meshes/...' refers to unknown package 'meshes'\""),
    "pybullet": fx.refused(
        '"cannot find \'meshes/...\' in any directory in urdf path", "Cannot load URDF file"'
    ),
    "isaac": fx.no_geometry('"Failed to resolve mesh"; the shape is left out'),
    "pinocchio": fx.refused('buildGeomFromUrdf: "Mesh package://meshes/... could not be found"'),
    "ros": fx.no_geometry(
        "RViz draws nothing there; robot_state_publisher does not read meshes", Severity.INFO
    ),
}


@rule(
    "C004",
    "mesh-not-found",
    Severity.ERROR,
    fix=FIX_FILE,
    effects={"": K.MISSING_MESH, "package": UNKNOWN_PACKAGE},
)
def check(doc: Document) -> Iterator[Hit]:
    refs = [
        FileRef(ref.element, ref.uri, f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}")
        for ref in references(doc)
    ]
    for problem in unresolved(doc, refs, "mesh"):
        if problem.package is not None:
            yield _unknown_package(doc, problem)
            continue
        fix = FIX_PACKAGE if problem.package_fix else None
        yield Hit(
            problem.element,
            problem.message,
            fix=fix,
            severity=problem.severity,
            effects=_effects(doc, problem.element),
        )


def _unknown_package(doc: Document, problem: FileProblem) -> Hit:
    """Per target: refused where the engine stops at the mesh, a warning where it loads the
    model without it, an info for ROS; PyBullet loads it when its own search finds the file."""
    table = _effects(doc, problem.element, UNKNOWN_PACKAGE)
    if problem.pybullet:
        del table["pybullet"]
    chosen = [effect.level for target, effect in table.items() if target in doc.targets]
    severity = max(chosen, default=Severity.INFO)
    fix = FIX_FOLDER if problem.folder is not None else FIX_PACKAGE
    return Hit(
        problem.element,
        problem.message,
        fix=fix,
        severity=severity,
        variant="package",
        effects=table,
    )


def _effects(
    doc: Document, mesh: etree._Element | None, effects: dict[str, Effect] = K.MISSING_MESH
) -> dict[str, Effect]:
    """MuJoCo's URDF import discards visuals (``discardvisual`` defaults to true): a
    missing visual mesh costs it nothing (observed on six corpus robots)."""
    table = dict(effects)
    owner = mesh.getparent() if mesh is not None else None
    owner = owner.getparent() if owner is not None else None
    visual = owner is not None and owner.tag == "visual"
    if visual and mujoco_compiler(doc, "discardvisual", "true").lower() not in ("false", "0"):
        table.pop("mujoco", None)
    return table
