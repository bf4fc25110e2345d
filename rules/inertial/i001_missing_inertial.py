"""A link has no `<inertial>`, so Gazebo drops it with its joint and everything below it.

## What it does
Finds links without an `<inertial>` and judges them the way Gazebo's URDF
converter (sdformat) does, after fixed-joint lumping:

- **error** when the link hangs from a movable joint (or a movable joint hangs
  below it) and neither it nor any link fixed to it has mass;
- **warning** when a massless link that is kept apart from its parent (fixed
  joint to `world`, or lumping disabled with `disableFixedJointLumping` or
  `preserveFixedJoint`) carries visuals or collisions;
- **info** when a link merged into its parent through a fixed joint has
  geometry but no mass.

Pure frames under fixed joints (sensor, tool and optical frames without
geometry) are not reported: Gazebo merges them into their parent and nothing is
lost. A massless link whose fixed children carry mass is not reported either:
Gazebo and Pinocchio lump that mass into it. Root links are not judged: a
massless root (`base_footprint`, `world`) is the pattern KDL asks for.

## Why is this bad?
- Gazebo (sdformat's URDF converter) drops a link without mass (at most 1e-6 kg)
  together with its parent joint and its whole subtree. sdformat before 9.10.1,
  12.7.2 and 13.5.0 does it without a word, so in Gazebo Classic a wheel or an
  arm simply disappears; newer versions print "link[X] has no <inertial> block
  defined" and still drop it.
- Pinocchio loads a massless moving link with a zero inertia, which makes the
  joint-space mass matrix singular.
- PyBullet silently gives every link without `<inertial>` a mass of 1 kg and
  a unit inertia.
- MuJoCo rejects moving bodies without mass ("mass and inertia of moving bodies
  must be larger than mjMINVAL") unless it computes inertia from geometry.

## How to fix
Add an `<inertial>` with the link's real mass, centre of mass and inertia
tensor (CAD tools export them). A link that is only a frame should hang from a
`fixed` joint. For the root link, KDL wants no inertia: keep a massless root
(for example `base_footprint`) and fix the real base link, with its mass, to
it.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import massless_verdict
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "I001",
    "missing-inertial",
    Severity.ERROR,
    fix="Add an <inertial> with the link's real mass, centre of mass and inertia.",
)
def check(doc: Document) -> Iterator[Hit]:
    for name, link in doc.link_map.items():
        if link.inertial is not None or not doc.graph.parent_joints.get(name):
            continue
        verdict = massless_verdict(doc, name)
        if verdict is not None:
            yield Hit(
                link.element,
                f"link '{name}' has no <inertial>, so {verdict.consequence}",
                severity=verdict.severity,
            )
