"""A `<gazebo>` child belongs to another kind of block (link, joint or robot).

## What it does
Flags children of a `<gazebo>` block that sdformat only honours in another scope:
- link keys (`mu1`, `mu2`, `kp`, `kd`, `material`, `selfCollide`, `turnGravityOff`,
  `maxContacts`, ...) in a joint's or the robot-level block;
- joint keys (`stopCfm`, `stopErp`, `implicitSpringDamper`, `provideFeedback`,
  `fudgeFactor`, `preserveFixedJoint`, ...) in a link's or the robot-level block;
- the robot key `static` in a link or joint block;
- SDF elements copied into the wrong SDF parent, e.g. a `<sensor>` in the robot-level
  block (SDF `<model>` has no sensors) or a `<plugin>` in a link block (SDF `<link>` has
  no plugins; model plugins go in the robot-level block).

A block whose `reference` names nothing (G001) was meant for a link or a joint: only what
belongs to neither (`static`, a model `<plugin>`...) is reported there.

## Why is this bad?
The converter parses every key it knows whatever the block, but inserts each one only
where it belongs: `InsertSDFExtensionLink`/`Collision`/`Visual` read only the link keys,
`InsertSDFExtensionJoint` only the joint keys, `InsertSDFExtensionRobot` only `static`
and the blobs. A key in the wrong block is therefore dropped without any message, and a
misplaced SDF blob is copied where SDF does not define it and ignored.

## How to fix
Move the element to the block it belongs to: `<gazebo reference="LINK">` for contact and
visual properties, `<gazebo reference="JOINT">` for joint properties, `<gazebo>` without
reference for `static` and model plugins. At robot level, use SDF `<self_collide>`
instead of `selfCollide`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import KEYS, LEGACY, SCOPE_SDF, block_keys, homes

BLOCK = {
    "robot": "the robot-level <gazebo> block",
    "link": "a link's block",
    "joint": "a joint's block",
}


@rule(
    "G007",
    "gazebo-element-wrong-scope",
    Severity.WARNING,
    fix="Move the element into the <gazebo> block of the link, joint or robot it belongs to.",
    targets=targets.GAZEBO,
)
def check(doc: Document) -> Iterator[Hit]:
    for el, scopes, owner in block_keys(doc):
        name = str(el.tag)
        where = homes(name)
        if name in LEGACY or not where or any(s in scopes for s in where):
            continue
        wanted = " or ".join(BLOCK[s] for s in where)
        if name in KEYS:
            what = f"a {KEYS[name].scope} key"
        else:
            what = "an SDF " + "/".join(SCOPE_SDF[s] for s in where) + " element"
        yield Hit(
            el,
            f"<{name}> is {what}, ignored in the <gazebo> block of {owner}",
            fix=f"Move it to {wanted}.",
        )
