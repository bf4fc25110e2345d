"""A link is named `map`, `odom` or `earth`, frames that REP 105 gives to other publishers.

## What it does
Runs with `profile = "mobile"` or `"humanoid"` (and never without a profile). Reports
every link named exactly `map`, `odom` or `earth`.

## Why is this bad?
REP 105 (sections "odom", "map", "earth" and "Frame Authorities") defines these as
world-fixed frames published outside the robot model: the odometry source broadcasts
`odom` → `base_link`, the localization component `map` → `odom`, and `earth` → `map`
is a static transform chosen with the map. REP 120 (section "map and odom") adopts
them for humanoids. A URDF link of the same name is published by
robot_state_publisher as well, so the frame gets two authorities: `base_link` ends up
with two parents, or TF flips between the two transforms, and navigation and
localization misbehave.

## How to fix
Remove the link and let odometry or localization publish the frame, or rename it
(`world` is the usual name for a simulation anchor).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.conventions.common import HUMANOID, MOBILE, active

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity

AUTHORITY = {
    "odom": "the world-fixed frame the odometry source publishes (odom -> base_link)",
    "map": "the world-fixed frame the localization component publishes (map -> odom)",
    "earth": "the ECEF origin, published with the map (earth -> map)",
}


@rule(
    "N002",
    "reserved-frame-link",
    Severity.WARNING,
    fix="Remove the link (odometry or localization publishes it) or rename it, e.g. 'world'.",
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, MOBILE, HUMANOID) is None:
        return
    for link in doc.links:
        if link.name in AUTHORITY:
            yield Hit(
                link.element,
                f"REP 105 reserves '{link.name}' for {AUTHORITY[link.name]}; this URDF "
                "defines a link of that name, which robot_state_publisher would publish too",
            )
