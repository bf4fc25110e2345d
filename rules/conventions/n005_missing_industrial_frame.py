"""An industrial arm lacks one of the REP 199 frames `base`, `flange` or `tool0`.

## What it does
Runs with `profile = "industrial"` (and never without a profile). Reports, once per
robot, the frames among `base`, `flange` and `tool0` that no link is named after
(prefixed names such as `left_tool0` or `${prefix}flange` count). The finding sits on
`base_link`, or on the root link when there is no `base_link`.

## Why is this bad?
The REP 199 draft, "Coordinate Frames for Serial Industrial Manipulators" (sections
"base", "flange" and "tool0"), followed by the ROS-Industrial support packages (ABB,
Fanuc, KUKA, Motoman, Universal Robots), defines three frames every arm should carry:

- `base`: the controller's own base (world) frame, so that poses from the teach
  pendant and from ROS can be compared;
- `flange`: where end effectors are attached, oriented as REP 103 requires (x+
  pointing out of the flange);
- `tool0`: the controller's all-zeros tool centre point, never moved by users.

Without them, end-effector xacros, MoveIt configurations and kinematics plugins
written for other arms cannot be reused, and users attach tools to the last link in
whatever orientation it happens to have.

The finding is informational: REP 199 is a draft, and older support packages predate
it.

## How to fix
Add the missing frames as massless links on fixed joints: `base` below `base_link`,
`flange` below the last link (x+ out of the flange) and `tool0` below `flange`
(the controller's all-zeros TCP, usually `rpy="0 pi/2 0"` from `flange`).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.conventions.common import INDUSTRIAL, active, root_link

from urdflint.engine.registry import Hit, rule
from urdflint.model.conventions import named
from urdflint.model.document import Document
from urdflint.model.finding import Severity

FRAMES = ("base", "flange", "tool0")


@rule(
    "N005",
    "missing-industrial-frame",
    Severity.INFO,
    fix="Add the missing frames: base under base_link, flange under the last link, "
    "tool0 under flange, all on fixed joints.",
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, INDUSTRIAL) is None:
        return
    names = [link.name for link in doc.links]
    missing = [frame for frame in FRAMES if not any(named(name, frame) for name in names)]
    anchor = doc.link_map.get("base_link") or root_link(doc)
    if not missing or anchor is None:
        return
    listed = ", ".join(f"'{frame}'" for frame in missing)
    yield Hit(
        anchor.element,
        "REP 199 (draft) gives an industrial arm the frames 'base' (controller base frame), "
        f"'flange' (end-effector mount) and 'tool0' (all-zeros TCP); this robot has no {listed}",
    )
