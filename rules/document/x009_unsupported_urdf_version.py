"""The `<robot version>` is not a URDF version that the parsers accept.

## What it does
Reads `<robot version="...">` the way urdfdom reads it (`major.minor`, two
whole numbers), and reports:

- an error when no urdfdom release accepts it: not of the form `x.y`
  (`"1"`, `"1.0.0"`, `"v1"`, an empty value), or a version other than 1.0,
  1.1 and 1.2 (`"2.0"`, `"0.9"`, `"1.3"`);
- a warning for `1.1` or `1.2` when the file uses none of the features that
  need it. The declaration gains nothing and shuts out every urdfdom older
  than 5.1 (for 1.1) or 6.0 (for 1.2);
- info for `1.1` or `1.2` when the file does use them: `<capsule>` geometry
  or `quat_xyzw` origins (1.1), or `acceleration`, `deceleration` and `jerk`
  joint limits (1.2);
- a warning for 1.0 spelt another way (`" 1.0"`, `"01.0"`, `"1.00"`):
  urdfdom reads it as 1.0, but urdf_parser_py accepts only the exact string
  `"1.0"`.

A robot without a `version` attribute is URDF 1.0 and is not reported. The
version in the XML declaration (`<?xml version="0.0"?>`) is not a URDF
version: X001 reports it, as a warning, since TinyXML and TinyXML2 ignore it.

## Why is this bad?
urdfdom checks the version before anything else and refuses the whole model
when it cannot read it. `check_urdf` (urdfdom 3.0.1 and 6.0.0) prints
"ERROR: Model Parsing the xml failed" on every error case, and with it ROS
(`robot_state_publisher`, MoveIt), kdl_parser, Pinocchio and Gazebo's
URDF converter refuse the model too. The messages are "Invalid 'version'
specified; only version 1.0 is currently supported" (urdfdom before 5.1),
"... versions from 1.0 upto 1.2 are currently supported" (6.0), "The version
attribute should be in the form 'x.y'" and "Version attribute is not an
integer".

Versions 1.1 and 1.2 are real: urdfdom 5.1 (2026-02) added 1.1 and urdfdom 6.0
(2026-04) added 1.2, and Pinocchio 4.1 reads both. Every older urdfdom still
refuses them. That covers the ROS 2 LTS releases, Debian's and Ubuntu's
`check_urdf`, and sdformat builds against those urdfdom releases.
urdf_parser_py refuses them too ("Invalid version; only 1.0 is supported"), and
Drake ignores the attribute with a warning. A file that needs a 1.1 or 1.2
feature has to pay that price; a file that does not should not.

## How to fix
Remove the `version` attribute, or write exactly `version="1.0"`, unless the
file uses a feature of URDF 1.1 or 1.2. Such a file keeps `version="1.1"`
(capsules, quaternions) or `version="1.2"` (acceleration, deceleration and
jerk limits): it then needs urdfdom 5.1 or 6.0 or later, which also ignores
those features under a lower version.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree
from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.effects import Effect, refused
from urdflint.model.finding import Severity

SINCE = {(1, 0): "", (1, 1): "5.1", (1, 2): "6.0"}  # the urdfdom release that reads it
# strtol: optional leading whitespace and sign, then digits, nothing after
_PART = re.compile(r"[ \t\n\r\f\v]*[+-]?[0-9]+")
_LIMIT_12 = ("acceleration", "deceleration", "jerk")


def read_version(raw: str) -> tuple[int, int] | str:
    """``(major, minor)`` as urdfdom's ``URDFVersion`` reads ``raw``, or why it refuses it."""
    parts = raw.split(".")
    if len(parts) != 2 or not all(parts):
        return "is not of the form 'x.y'"
    if not all(_PART.fullmatch(p) for p in parts):
        return "is not of the form 'x.y' with whole numbers"
    major, minor = (int(p) for p in parts)
    if major < 0 or minor < 0:
        return "has a negative number"
    return major, minor


def features(doc: Document) -> list[tuple[tuple[int, int], str]]:
    """The URDF 1.1 and 1.2 features the document uses, with the version each needs."""
    robot = doc.robot
    found: list[tuple[tuple[int, int], str]] = []
    if any(el.get("quat_xyzw") is not None for el in robot.iter("origin")):
        found.append(((1, 1), "quat_xyzw origins"))
    if any(_parent_tag(el) == "geometry" for el in robot.iter("capsule")):
        found.append(((1, 1), "<capsule> geometry"))
    used = {a for joint in doc.joints for el in joint.element.iter("limit") for a in el.attrib}
    if any(a in used for a in _LIMIT_12):
        found.append(((1, 2), "acceleration, deceleration or jerk limits"))
    return found


def _parent_tag(el: etree._Element) -> str | None:
    parent = el.getparent()
    return parent.tag if parent is not None else None


@rule(
    "X009",
    "unsupported-urdf-version",
    Severity.ERROR,
    fix='Remove the version attribute or write version="1.0".',
    effects={"": K.URDF_VERSION, "spelling": {}, "newer": K.NEWER_URDF_VERSION},
)
def check(doc: Document) -> Iterator[Hit]:
    raw = doc.robot.get("version")
    if raw is None:
        return
    version = read_version(raw)
    if isinstance(version, str):
        yield Hit(doc.robot, f"robot version {raw!r} {version}; urdfdom refuses the model")
        return
    label = f"{version[0]}.{version[1]}"
    if version not in SINCE:
        yield Hit(
            doc.robot,
            f"robot declares URDF version {raw!r}, which no urdfdom release reads "
            "(only 1.0, 1.1 and 1.2 exist); urdfdom refuses the model",
        )
        return
    if version == (1, 0):
        if raw != "1.0":
            yield Hit(
                doc.robot,
                f"robot version {raw!r} reads as 1.0 in urdfdom, but urdf_parser_py accepts "
                "only the exact string '1.0'",
                fix='Write version="1.0" or remove the attribute.',
                severity=Severity.WARNING,
                variant="spelling",
            )
        return
    needed = [name for need, name in features(doc) if need <= version]
    since = SINCE[version]
    if needed:
        yield Hit(
            doc.robot,
            f"robot declares URDF {label} for its {' and '.join(needed)}; only urdfdom "
            f"{since} or later reads the model, older urdfdom and urdf_parser_py refuse it",
            fix=f'Keep version="{label}" only if every consumer uses urdfdom {since} or later.',
            severity=Severity.INFO,
            variant="newer",
            effects=_newer(doc, version),
        )
    else:
        yield Hit(
            doc.robot,
            f"robot declares URDF {label} but uses none of its features; urdfdom before "
            f"{since} and urdf_parser_py refuse the model",
            severity=Severity.WARNING,
            variant="newer",
            effects=_newer(doc, version),
        )


def _newer(doc: Document, version: tuple[int, int]) -> dict[str, Effect]:
    """From URDF 1.2 on, urdfdom (4.0 and later, as bundled with Pinocchio 4.1) requires
    both ``lower`` and ``upper`` on every revolute and prismatic ``<limit>`` (observed)."""
    table = dict(K.NEWER_URDF_VERSION)
    bounded = [j for j in doc.joints if j.type in ("revolute", "prismatic")]
    if version >= (1, 2) and any(
        (lim := j.find("limit")) is not None
        and (lim.get("lower") is None or lim.get("upper") is None)
        for j in bounded
    ):
        why = refused(
            '"revolute and prismatic joints must have both lower and upper position limits '
            'specified in URDF version 1.2 or later"'
        )
        table.update({"pinocchio": why, "ros": why})
    return table
