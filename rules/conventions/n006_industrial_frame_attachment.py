"""A REP 199 frame (`base`, `flange`, `tool0`) moves or carries geometry.

## What it does
Runs with `profile = "industrial"` (and never without a profile). For each link named
`base`, `flange` or `tool0` beside a `base_link` of the same prefix (`tool0` beside
`base_link`, `left_tool0` beside `left_base_link`), reports its parent joint when that
joint is not `fixed`, and its first `<visual>` or `<collision>`.

## Why is this bad?
The REP 199 draft (sections "base", "flange" and "tool0") defines these as frames, not
bodies: each is attached to its parent by a fixed transform ("not across a movable
joint"), and each "shall not have any geometry associated with it". `tool0` is the
controller's all-zeros TCP: a joint above it that moves makes it something else,
and kinematics plugins generated for the chain `base_link` → `tool0` no longer match
the controller. Geometry on these frames duplicates the arm's own meshes and is
dropped by tools that treat them as pure frames.

The finding is informational: REP 199 is a draft.

## How to fix
Attach the frame with `<joint type="fixed">` to the link it belongs to, and move any
`<visual>`/`<collision>` to that physical link.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.conventions.common import INDUSTRIAL, active, has_geometry

from urdflint.engine.registry import Hit, rule
from urdflint.model import conventions as N
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.joints import label
from urdflint.model.structure import q

FRAMES = ("base", "flange", "tool0")


@rule(
    "N006",
    "industrial-frame-attachment",
    Severity.INFO,
    fix="Attach the frame with a fixed joint and move its geometry to the physical link.",
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, INDUSTRIAL) is None:
        return
    for prefix in N.prefixes(doc, "base_link"):
        for frame in FRAMES:
            link = doc.link_map.get(prefix + frame)
            if link is None:
                continue
            joint = doc.graph.parent_joint(prefix + frame)
            if joint is not None and joint.type != "fixed":
                yield Hit(
                    joint.element,
                    f"REP 199 (draft, {frame}) attaches {q(link.name)} by a fixed transform; "
                    f"here its parent is {label(joint)}",
                    attribute="type",
                )
            shape = has_geometry(link)
            if shape is not None:
                owner = (link.visuals or link.collisions)[0]
                yield Hit(
                    owner,
                    f"REP 199 (draft, {frame}): {q(link.name)} shall not have any geometry; "
                    f"it has a {shape}",
                )
