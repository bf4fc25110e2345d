"""A link-wide Gazebo setting sits on a link that fixed-joint lumping merges away.

## What it does
sdformat removes every link attached by a `fixed` joint (unless the joint's block sets
`<preserveFixedJoint>` or `<disableFixedJointLumping>` true, or its parent is `world`) and
merges it into the nearest ancestor that survives. This rule flags settings of the whole
SDF `<link>` in the `<gazebo>` block of such a link — `turnGravityOff`, `gravity`,
`selfCollide`/`self_collide`, `dampingFactor`/`velocity_decay`, `kinematic`,
`enable_wind`, `must_be_base_link` — when they differ from what the surviving link has.

Not flagged, because sdformat keeps them attached to the merged link's own geometry or
re-poses them correctly: `material`, `visual`/`collision` blobs and the contact keys
(`mu1`, `mu2`, `kp`, `kd`, `fdir1`, `maxVel`, `minDepth`, `maxContacts`, `laserRetro`),
which apply to the lumped visuals/collisions only; `<sensor>`s and plugins on lumped
links (the usual `camera_link` pattern), which are re-attached with an offset pose.

## Why is this bad?
The lumped link's extension is re-filed under the surviving link (`Fixed Joint Reduction:
extension lumping from [child] to [parent]`), so a link-wide setting applies to the
whole merged body: `<turnGravityOff>true` on a small `camera_link` turns gravity off for
the entire `base_link`, and `<selfCollide>` on a fingertip changes the palm. When both
set the key, sdformat keeps whichever it writes last and warns "multiple inconsistent
<self_collide> exists due to fixed joint reduction".

## How to fix
Put the setting on the surviving link if it is meant for the whole body, remove it if it
was meant for the small link only, or keep the link by adding
`<gazebo reference="JOINT"><preserveFixedJoint>true</preserveFixedJoint></gazebo>` for its
fixed joint (the child then needs a valid `<inertial>`).
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import (
    LINK_LEVEL,
    blocks_for,
    canonical,
    keys_of,
    lumped_into,
    preserved_joints,
)


@rule(
    "G008",
    "gazebo-reference-lumped",
    Severity.WARNING,
    fix="Move the setting to the surviving link, or keep the joint with <preserveFixedJoint>.",
    targets=targets.GAZEBO,
)
def check(doc: Document) -> Iterator[Hit]:
    kept = preserved_joints(doc)
    for link in doc.links:
        if link.name is None or doc.link_map.get(link.name) is not link:
            continue
        blocks = blocks_for(doc, link.name)
        if not blocks:
            continue
        lumped = lumped_into(doc, link.name, kept)
        if lumped is None:
            continue
        joint, target = lumped
        survivor = _settings(blocks_for(doc, target))
        for gazebo in blocks:
            for el in keys_of(gazebo):
                value = canonical(str(el.tag), el)
                if value is None:
                    continue
                prop, setting = value
                current = survivor.get(prop, LINK_LEVEL[str(el.tag)][1])
                if setting == current:
                    continue
                yield Hit(
                    el,
                    f"link {link.name!r} is merged into {target!r} by fixed joint {joint.name!r}, "
                    f"so its <{el.tag}> applies to all of {target!r}",
                )


def _settings(blocks: list[etree._Element]) -> dict[str, str]:
    found: dict[str, str] = {}
    for gazebo in blocks:
        for el in keys_of(gazebo):
            value = canonical(str(el.tag), el)
            if value is not None:
                found[value[0]] = value[1]
    return found
