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

`urdflint fix` renames a misspelt key when one name is closest (`<turnGravityOf>` to
`<turnGravityOff>`, `<max_contacts>` to `<maxContacts>`, `<kp_>` to `<kp>`; names of one
setting count as one: `<selfcollide>` becomes `<selfCollide>` in a link's block,
`<self_collide>` in the robot's), with the same digits, belonging in the block, and not
already set for the block's element. Two equally close names (`<mu>`: `mu1` or `mu2`?)
or a different number (`<mu3>`) get no automatic fix.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.gazebo.renaming import rename_key

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.edits import Repair
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import (
    KEYS,
    LEGACY,
    SCOPE_SDF,
    belongs,
    candidates,
    checked_scopes,
    describe,
    homes,
    keys_of,
    near_miss,
    scopes_of,
)
from urdflint.model.spelling import ranked, same_digits

# Names of the same setting: the converter key reads every value the SDF element takes, and
# sdformat reads cfmDamping exactly like implicitSpringDamper.
SYNONYMS = {"self_collide": "selfCollide", "cfmDamping": "implicitSpringDamper"}


@rule(
    "G006",
    "unrecognized-gazebo-element",
    Severity.INFO,
    fix="Fix the element's spelling, or remove it if it is not meant for Gazebo.",
    fixable="safe",
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
            target = _correction(name, known, scopes)
            guess = target or near_miss(name, known)
            if guess is not None:
                yield Hit(
                    el,
                    f"<{name}> in the <gazebo> block of {owner} is not a Gazebo key "
                    f"(did you mean <{guess}>?)",
                    fix=f"Rename it to <{guess}>.",
                    severity=Severity.WARNING,
                    repair=_rename(doc, el, target),
                )
            else:
                yield Hit(
                    el,
                    f"<{name}> in the <gazebo> block of {owner} is neither a Gazebo key nor "
                    f"an SDF element; {copied}",
                )


def _correction(name: str, known: frozenset[str], scopes: frozenset[str]) -> str | None:
    """The key ``name`` is a misspelling of, when that is certain: one name (or names of the
    same setting, :data:`SYNONYMS`) is closest, ignoring case and ``_`` first, then exactly;
    it has the same digits (``mu`` is not ``mu1``) and belongs in a block of ``scopes``.
    Among names of one setting: the current one, the closest as written, the converter key."""
    found = ranked(name, known)
    best = [c for d, e, c in found if (d, e) == found[0][:2]] if found else []
    if len({SYNONYMS.get(c, c) for c in best}) != 1:
        return None
    group = {best[0], SYNONYMS.get(best[0], best[0])}
    group |= {c for c, same in SYNONYMS.items() if same in group}
    fitting = sorted(c for c in group if belongs(c, scopes))
    fitting.sort(key=lambda c: (c in LEGACY, c not in best, c not in KEYS))
    if not fitting or not same_digits(name, fitting[0]):
        return None
    return fitting[0]


def _rename(doc: Document, el: etree._Element, target: str | None) -> Repair | None:
    return rename_key(doc, el, target)
