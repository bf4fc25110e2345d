"""An `*_optical_frame` is not rotated z forward, x right, y down from its camera frame.

## What it does
Runs with any profile (and never without one). For every link whose name ends in
`_optical` or `_optical_frame`, finds the camera's body frame: the link of the same
name without the suffix (`camera_rgb_optical_frame` → `camera_rgb_frame`,
`camera_rgb_link` or `camera_rgb`), else the optical frame's parent. When the two are
joined by fixed joints only, reports the optical frame's parent joint if the rotation
between them is not the standard one, `rpy="-pi/2 0 -pi/2"`.

## Why is this bad?
REP 103 (sections "Axis Orientation" and "Suffix Frames"): body frames are x forward,
y left, z up, and the `_optical` frame of a camera is z forward, x right, y down, the
convention of image coordinates that camera drivers, `image_geometry`,
`depth_image_proc` and point-cloud consumers assume when they stamp and project their
data. From a REP 103 body frame that is exactly the rotation `rpy="-pi/2 0 -pi/2"`. An
optical frame rotated otherwise makes every image, depth cloud and detection land
rotated in the world.

## How to fix
Attach the optical frame to the camera's body frame with
`<origin xyz="0 0 0" rpy="${-pi/2} 0 ${-pi/2}"/>` on a fixed joint, and orient the body
frame itself x forward (along the lens axis), y left, z up.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from urdflint.rules.conventions.common import EVERY, active

from urdflint.engine.registry import Hit, rule
from urdflint.model import conventions as N
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.inertia import rpy_matrix
from urdflint.model.structure import q

SUFFIXES = ("_optical_frame", "_optical")
STANDARD = rpy_matrix((-math.pi / 2, 0.0, -math.pi / 2))


@rule(
    "N004",
    "optical-frame-orientation",
    Severity.WARNING,
    fix='Give the optical frame rpy="-pi/2 0 -pi/2" from the camera body frame (fixed joint).',
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, *EVERY) is None:
        return
    for link in doc.links:
        body = _body_frame(doc, link.name)
        joint = doc.graph.parent_joint(link.name) if link.name else None
        if body is None or joint is None or link.name is None:
            continue
        pose = N.relative(doc, body, link.name)
        if pose is None or N.angle(STANDARD, pose[0]) <= N.ANGLE_TOL:
            continue
        rpy = N.fmt_angles(N.rpy_of(pose[0]))
        yield Hit(
            joint.element,
            f"REP 103 (Suffix Frames) orients {q(link.name)} z forward, x right, y down: "
            f'rpy="-pi/2 0 -pi/2" from the body frame {q(body)}; here it is rpy="{rpy}"',
        )


def _body_frame(doc: Document, name: str | None) -> str | None:
    """The camera body frame an optical frame is measured from, or ``None``."""
    stem = next((name[: -len(s)] for s in SUFFIXES if name and name.endswith(s)), None)
    if not stem or name is None:
        return None
    for candidate in (f"{stem}_frame", f"{stem}_link", stem):
        if candidate in doc.link_map and candidate != name:
            return candidate
    return doc.graph.parent_link(name)
