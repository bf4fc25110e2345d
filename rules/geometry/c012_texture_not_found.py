"""A `<material><texture filename>` does not lead to a file.

## What it does
Resolves the `filename` of every `<texture>` in a robot-level `<material>` and
in a visual's `<material>` exactly as C004 resolves meshes (`package://`,
`file://`, paths relative to the URDF; `--package-path`, `package-paths`,
`ROS_PACKAGE_PATH`, `AMENT_PREFIX_PATH`, `package.xml` search) and reports
every texture that is not there, with where urdflint looked. Severities follow
C004: an error when the package or folder was found and the file is not in
it, a warning when the package cannot be found although package paths are
known or when its name is a folder of the description (C004's
`package://meshes/...` case), and one info note per unknown package otherwise. A `<texture/>`
without a filename is ignored by urdfdom and here.

## Why is this bad?
urdfdom and `check_urdf` only store the string, so nothing complains until a
consumer opens the file. Drake refuses the whole model ("URI 'wood.png'
resolved to '/.../wood.png' which does not exist"); RViz logs an error and
draws the visual untextured. PyBullet, MuJoCo's URDF import and Pinocchio load
the model without the texture, and sdformat's URDF converter ignores URDF
textures altogether, so Gazebo never shows them. A texture left behind when
a package was reorganised is the usual cause.

## How to fix
Correct the filename (case matters on Linux) or add the image; point
urdflint at the package with `--package-path NAME=DIR` if it lives
elsewhere. Remove the `<texture>` if the visual should only have a colour.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.sources.meshes import textures, unresolved

FIX_PACKAGE = "Pass --package-path NAME=DIR or set package-paths in the configuration."


@rule(
    "C012",
    "texture-not-found",
    Severity.ERROR,
    fix="Correct the texture filename (case matters) or add the image file.",
)
def check(doc: Document) -> Iterator[Hit]:
    for problem in unresolved(doc, textures(doc), "texture"):
        fix = FIX_PACKAGE if problem.package_fix else None
        yield Hit(
            problem.element,
            problem.message,
            fix=fix,
            severity=problem.severity,
            attribute="filename",
        )
