"""A `<gazebo>` child is neither a converter key nor an SDF element of its scope.

## What it does
Looks at each child of a `<gazebo>` block that sdformat's URDF converter does not read
(`mu1`, `selfCollide`, `material`, ... are read; see the "Using a URDF in Gazebo"
tutorial) and that is not an SDF element of the element it is copied into: `<model>` for
robot-level blocks (`plugin`, `static`, `self_collide`, `link`, `joint`, `frame`, `pose`,
`gripper`, ...), `<link>` (`sensor`, `gravity`, `self_collide`, `kinematic`,
`velocity_decay`, `projector`, `visual`, `collision`, `battery`, `light`, ...), or
`<joint>` (`sensor`, `physics`, `axis`, `pose`, ...). Legitimate SDF such as plugins and
sensors is never flagged.

A name that is almost a known one (`<mu>` for `<mu1>`, `<selfcollide>` for
`<selfCollide>`, `<turnGravityOf>`, `<max_contacts>` for `<maxContacts>`) is a warning:
it is a typo that silently does nothing. Anything else is info. Blocks whose `reference`
names nothing (G001) are checked as if they were a link's or a joint's.

## Why is this bad?
The converter copies unknown children verbatim into the SDF element with only a debug
message ("extension [...] not converted from URDF, probably already in SDF format"); the
SDF parser then warns "XML Element[X], child of element[link], not defined in SDF" at best
and the setting has no effect. A misspelt friction or self-collision key therefore
leaves the robot with Gazebo's defaults while its author believes it is tuned.

## How to fix
Fix the spelling (keys are case-sensitive: `mu1`, `mu2`, `kp`, `kd`, `selfCollide`,
`maxContacts`, `turnGravityOff`, ...), or remove the element. For a deliberate custom
element read by your own plugin, put it inside that `<plugin>`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import (
    LEGACY,
    SCOPE_SDF,
    candidates,
    checked_scopes,
    describe,
    homes,
    keys_of,
    near_miss,
    scopes_of,
)


@rule(
    "G006",
    "unrecognized-gazebo-element",
    Severity.INFO,
    fix="Fix the element's spelling, or remove it if it is not meant for Gazebo.",
)
def check(doc: Document) -> Iterator[Hit]:
    known = candidates()
    for gazebo in doc.gazebo:
        scopes = checked_scopes(doc, gazebo)  # a dangling block is still checked (G001)
        owner = describe(doc, gazebo)
        into = " and ".join(SCOPE_SDF[s] for s in sorted(scopes))
        copied = f"sdformat copies it verbatim into {into}"
        if scopes_of(doc, gazebo) is None:
            copied = "sdformat would copy it verbatim into the SDF <link> or <joint>"
        for el in keys_of(gazebo):
            name = str(el.tag)
            if name in LEGACY or homes(name):
                continue
            guess = near_miss(name, known)
            if guess is not None:
                yield Hit(
                    el,
                    f"<{name}> in the <gazebo> block of {owner} is not a Gazebo key "
                    f"(did you mean <{guess}>?)",
                    fix=f"Rename it to <{guess}>.",
                    severity=Severity.WARNING,
                )
            else:
                yield Hit(
                    el,
                    f"<{name}> in the <gazebo> block of {owner} is neither a Gazebo key nor "
                    f"an SDF element; {copied}",
                )
