"""A disabled (or enabled) collision pair names a link the URDF does not have.

## What it does
Checks the links named by `<disable_collisions link1 link2>`,
`<enable_collisions link1 link2>` and `<disable_default_collisions link>`: each must
be written and be a link of the URDF. Each unknown link is reported once, at the
first entry naming it, with the number of entries that name it. A pair of a link
with itself, and a pair already written earlier in the file (in either order), are
reported as information.

## Why is this bad?
srdfdom (`srdf::Model::loadCollisionPairs` and `loadCollisionDefaults` in
`src/model.cpp`) logs "Link 'L' is not known to URDF. Cannot disable/enable
collisons." and drops the entry. When a link was renamed, the pair the Setup
Assistant disabled (two adjacent links that always touch) is checked again under its
new name, and MoveIt reports the robot in self-collision in its own home pose: every
plan fails with "Start state appears to be in collision"
(panda_moveit_config#107). A self pair has no effect (a link is never checked against
itself) and a repeated pair only adds noise.

## How to fix
Rename the links to the URDF's names (regenerate the collision matrix with the MoveIt
Setup Assistant after renaming links), or delete the stale entries.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.moveit.common import Srdf, hit, name_of, srdf_of

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import did_you_mean


@rule(
    "M009",
    "collision-pair-unknown-link",
    Severity.WARNING,
    fix="Name links of the URDF, or remove the entry.",
)
def check(doc: Document) -> Iterator[Hit]:
    srdf = srdf_of(doc)
    if srdf is None:
        return
    unknown: dict[str, list[tuple[etree._Element, str]]] = {}  # link -> entries naming it
    for tag in ("disable_collisions", "enable_collisions"):
        seen: set[frozenset[str]] = set()
        for el in srdf.elements(tag):
            first, second = name_of(el, "link1"), name_of(el, "link2")
            if first is None or second is None:
                yield hit(srdf, el, f"<{tag}> lacks link1 or link2; srdfdom ignores it")
                continue
            stale = [
                (a, n) for a, n in (("link1", first), ("link2", second)) if n not in doc.link_map
            ]
            for attr, name in stale[:1]:  # srdfdom stops at the first unknown link
                unknown.setdefault(name, []).append((el, attr))
            if stale:
                continue
            pair = frozenset((first, second))
            if first == second:
                yield hit(srdf, el, f"<{tag}> pairs link {first!r} with itself",
                          fix="Remove the entry.", severity=Severity.INFO)  # fmt: skip
            elif pair in seen:
                yield hit(srdf, el, f"<{tag}> repeats the pair {first!r}, {second!r}",
                          fix="Remove the repeated entry.", severity=Severity.INFO)  # fmt: skip
            seen.add(pair)
    for el in srdf.elements("disable_default_collisions"):
        name = name_of(el, "link")
        if name is None:
            yield hit(srdf, el, "<disable_default_collisions> has no link; srdfdom ignores it")
        elif name not in doc.link_map:
            unknown.setdefault(name, []).append((el, "link"))
    for name, entries in unknown.items():
        yield _stale(doc, srdf, name, entries)


def _stale(doc: Document, srdf: Srdf, name: str, entries: list[tuple[etree._Element, str]]) -> Hit:
    """One finding per unknown link, at its first entry: the Setup Assistant writes dozens."""
    el, attr = entries[0]
    count = len(entries) - 1
    more = f" (and {count} more {'entry' if count == 1 else 'entries'})" if count else ""
    return hit(
        srdf,
        el,
        f"<{el.tag}> names link {name!r}, which is not in the URDF; srdfdom ignores "
        f"the entry{more}",
        attribute=attr,
        fix=did_you_mean(name, doc.link_map, "link"),
    )
