"""An attribute that URDF does not define on that element.

## What it does
Checks the attributes of every URDF element against URDF's table
(urdflint/model/schema.py) and reports the ones URDF does not define there:
typos (`<joint typ="revolute">`), attributes that belong to a child element
(`<inertial mass="1">`, where `<mass value>` is meant), and attributes no parser
reads (`<link type="laser">`, `<axis rpy="0 0 1.57">`). The message suggests
the closest known name.

Not reported: namespaced attributes (`xacro:*`, `drake:*`, `xsi:schemaLocation`),
anything inside extension blocks (`<gazebo>`, `<transmission>`, `<ros2_control>`,
`<sensor>`...) and namespaced elements, and the extension attributes real
descriptions carry on purpose: PyBullet's `<collision group mask concave>`
(PyBullet's collision filter group and mask, and a concave triangle mesh),
Drake's `<link drake_ignore>`, franka_description's `<dynamics D K mu_coulomb
mu_viscous>` and sr_description's `<geometry name>`. An `rpy="0 0 0"` on
`<axis>` (husky_description writes it) changes nothing and is not reported
either. Unknown *elements* are X007's.

## Why is this bad?
URDF parsers read the attributes they know by name and ignore the others
without a word: urdfdom (`check_urdf` 3.0.1), Pinocchio, sdformat (Gazebo),
MuJoCo and PyBullet load `<joint typ="revolute" type="revolute">` or
`<link type="laser">` silently. Only Drake warns, and only for a link's `type`
("The attribute 'type' found in a 'link' tag is currently unsupported and will
be ignored"), and urdf_parser_py prints "Unknown attribute". A misspelt attribute
is therefore a missing one: a joint whose only type attribute is `typ` has no type,
and urdfdom refuses the model ("joint [j] has no type, check to see if it's a
reference."); a misspelt `<limit velocity>` or `<mass value>` is read as absent. An
`rpy` on `<axis>` does not rotate the axis: URDF's axis has no orientation of its own.

## How to fix
Rename the attribute as suggested, move it where it belongs (`<mass value="1"/>`
inside `<inertial>`; an axis rotation into the joint's `<origin rpy>` or the axis
vector itself), or delete it. Data for a specific tool goes in that tool's
namespace (`xmlns:mytool="..."`, then `mytool:attr="..."`), which no URDF rule reads.

`urdflint fix` handles a misspelt attribute when one URDF name is certainly meant (the
suggested one, the only closest name at most one edit away, two for names of 8+ letters,
ignoring case and `_`, with the same digits): it deletes the misspelt attribute when the
element also carries the right one with the same value (`typ="revolute"
type="revolute"`), and, in a plain URDF file, renames it when the right one is missing
(written at the end of the tag). Different values, and xacro sources (the value may be an
expression), are left to you.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.edits import RemoveAttribute, Repair, SetAttribute
from urdflint.model.finding import Severity
from urdflint.model.schema import EXTENSION_ATTRS, SPECS, describe, visits
from urdflint.model.spelling import ranked, same_digits
from urdflint.model.values import vector

# Attributes written in the wrong place often enough to deserve a specific hint.
HINTS = {
    ("axis", "rpy"): "URDF's <axis> has no orientation; rotate the joint's <origin> instead",
}


@rule(
    "X013",
    "unknown-attribute",
    Severity.WARNING,
    fix="Rename the attribute as suggested, move it where it belongs, or delete it.",
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    elements = [(doc.robot, "robot")]
    elements += [(v.element, v.key) for v in visits(doc.robot) if v.key is not None]
    for el, key in elements:
        spec = SPECS[key]
        accepted = EXTENSION_ATTRS.get(key, {})
        for attr, value in el.attrib.items():
            if attr.startswith("{") or attr in spec.attrs or attr in accepted:
                continue  # namespaced (xacro:, drake:, xsi:), URDF's own, or a known extension
            if (key, attr) == ("axis", "rpy") and vector(el, "rpy", 3) == (0.0, 0.0, 0.0):
                continue  # the identity: nothing is lost
            hint, suggested = _hint(key, attr)
            yield Hit(
                el,
                f"{_what(el, key)} has the attribute {attr}={value!r}, which URDF does not "
                f"define there{hint}",
                attribute=attr,
                repair=_repair(doc, el, key, attr, suggested),
            )


def _what(el: etree._Element, key: str) -> str:
    return "<robot>" if key == "robot" else describe(el)


def _hint(key: str, attr: str) -> tuple[str, str | None]:
    """The hint for the message, and the attribute it suggests (a did-you-mean)."""
    if (key, attr) in HINTS:
        return f" ({HINTS[key, attr]})", None
    spec = SPECS[key]
    if attr in spec.children:
        return f" (<{attr}> is a child element of <{key}>, not an attribute)", None
    known = [*spec.attrs, *EXTENSION_ATTRS.get(key, {})]
    close = difflib.get_close_matches(attr, known, n=1, cutoff=0.7)
    if not close and attr.lower() in known:
        close = [attr.lower()]
    return (f" (did you mean {close[0]}?)", close[0]) if close else ("", None)


def _repair(
    doc: Document, el: etree._Element, key: str, attr: str, suggested: str | None
) -> Repair | None:
    """Delete a misspelt duplicate, or rename a misspelt attribute (plain URDF only: in a
    xacro source the value may be an expression, which the expanded value would replace)."""
    known = [*SPECS[key].attrs, *EXTENSION_ATTRS.get(key, {})]
    if suggested is None or not _certain(attr, suggested, known):
        return None
    right = el.get(suggested)
    if right is not None:
        if right != el.get(attr):
            return None  # two values: which one was meant is not certain
        description = f"delete {attr}, a misspelt duplicate of {suggested}"
        return Repair("safe", description, (RemoveAttribute(el, attr),))
    if doc.origin is not None:
        return None
    operations = (RemoveAttribute(el, attr), SetAttribute(el, suggested, el.get(attr) or ""))
    return Repair("safe", f"rename {attr} to {suggested}", operations)


def _certain(attr: str, suggested: str, known: list[str]) -> bool:
    """``suggested`` is the only closest name within typo range, with the same digits."""
    found = ranked(attr, known)
    if not found or found[0][2] != suggested:
        return False
    if len(found) > 1 and found[0][:2] == found[1][:2]:
        return False
    return same_digits(attr, suggested)
