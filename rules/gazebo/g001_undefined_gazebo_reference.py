"""A `<gazebo reference="X">` block names neither a link nor a joint.

## What it does
Flags `<gazebo>` blocks whose `reference` matches no `<link>` and no `<joint>` of the
robot, and suggests the closest existing name. The block's contents are still checked in
the same run (G003-G007 read them as meant for a link or a joint), so correcting the
reference does not reveal a second round of findings.

## Why is this bad?
sdformat's URDF converter (used by both Gazebo Classic and Gazebo Sim) files every
`<gazebo>` block under its reference name and only looks those names up while it writes
links and joints. A block for a name that does not exist is dropped without any message,
not even in `gz sdf -p` or the verbose log: its friction, material, sensors and plugins
silently vanish. This usually happens after a link is renamed or removed, or when a
xacro prefix is missing.

## How to fix
Point `reference` at an existing link or joint (mind xacro prefixes such as `left_`),
or delete the block if the element it configured is gone.

`urdflint fix` corrects a reference that is certainly a typo: one link or joint name is
closest and at most one edit away (two for names of 8+ letters, ignoring case and `_`),
with the same numbers and the same one- and two-letter words (`l_foot` is not a typo of
`r_foot`); every key of the block belongs to that link or joint, and none of its other
blocks sets the same keys.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.edits import Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import (
    JOINT,
    KEYS,
    LINK,
    belongs,
    blocks_for,
    homes,
    keys_of,
    scopes_of,
    suggest,
)
from urdflint.model.spelling import ranked
from urdflint.model.values import has_xacro


@rule(
    "G001",
    "undefined-gazebo-reference",
    Severity.ERROR,
    fix="Rename the reference to an existing link or joint, or remove the block.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    names = [*doc.link_map, *doc.joint_map]
    for gazebo in doc.gazebo:
        ref = gazebo.get("reference")
        if not ref or has_xacro(ref) or scopes_of(doc, gazebo) is not None:
            continue
        target = _correction(doc, gazebo, ref, names)
        guess = target or suggest(ref, names)
        hint = f" (did you mean {guess!r}?)" if guess else ""
        repair = None
        if target is not None:
            operations = (SetAttribute(gazebo, "reference", target),)
            repair = Repair("safe", f"point the block at {target!r}", operations)
        yield Hit(gazebo, f"<gazebo reference={ref!r}> names no link or joint{hint}", repair=repair)


def _correction(doc: Document, gazebo: etree._Element, ref: str, names: list[str]) -> str | None:
    """The name ``ref`` is certainly a misspelling of: the one closest name within typo
    range (:func:`near_miss`), with the same numbers and short words, whose link or joint
    takes every key of the block and whose own blocks set none of them (the block's values
    would then compete with theirs)."""
    found = ranked(ref, set(names))
    if not found or (len(found) > 1 and found[0][:2] == found[1][:2]):
        return None
    target = found[0][2]
    if _marks(ref) != _marks(target):
        return None
    scopes = frozenset({LINK} if target in doc.link_map else set())
    scopes |= {JOINT} if target in doc.joint_map else set()
    keys = [str(k.tag) for k in keys_of(gazebo)]
    if not all(belongs(k, scopes) for k in keys if homes(k)):
        return None  # a link's keys pointed at a joint: dropped there too (G007)
    taken = {str(k.tag) for g in blocks_for(doc, target) for k in keys_of(g)}
    return None if any(k in KEYS and k in taken for k in keys) else target


def _marks(name: str) -> tuple[list[str], list[str]]:
    """The numbers and the one- and two-letter words of a name: a different one names
    another element (``finger_1``/``finger_2``, ``l_foot``/``r_foot``), not a typo."""
    words = re.findall(r"[A-Z]+(?![a-z])|[A-Z]?[a-z]+", name)  # snake_case and camelCase
    return re.findall(r"\d+", name), [w.lower() for w in words if len(w) <= 2]
