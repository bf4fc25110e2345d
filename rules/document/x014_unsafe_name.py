"""A link or joint name contains spaces or characters that importers rename or reject.

## What it does
Checks the `name` of every `<link>` and `<joint>`:

- a warning for whitespace, control characters and any character other than
  ASCII letters, digits, `_`, `-`, `.`, `/` and `:` (`arm link`, `wrist(1)`,
  `Gelenk_ä`, `joint#2`);
- one info per file, only when the `isaac` target is selected, for the names
  Isaac Sim rewrites although other consumers take them: a `.`, `-`, `:` or `/` in the
  name, or a leading digit (`link_4.0`, `joint_6-flange`, `1_hip`).

Dots, dashes and slashes are otherwise not reported: urdfdom, sdformat 12,
MuJoCo 4.0, Drake 1.51, PyBullet 3.2.7 and Pinocchio 4.1 load names with
spaces, dots, `::` or a leading digit unchanged (observed with urdflint's
`--confirm all`), and well-known models use them (the Allegro hand's
`link_4.0`, ABB's `joint_6-flange`, NASA R2's `r2/left_arm/...`).
Names with an unexpanded xacro expression are X008's.

## Why is this bad?
A name is an identifier that other tools repeat: TF frames, `joint_states`,
controller configurations, SRDF groups, launch arguments. Isaac Sim's URDF
importer turns every name into a USD prim path, which allows only letters,
digits and `_` and cannot start with a digit: it logs "The path X is not a
valid usd path, modifying to X_" and the articulation's joints then carry other
names than the URDF's, so policies and ROS bridges that look joints up by name
miss them; names starting with a digit have made the converter fail with
"Accessed invalid null prim" (generalroboticslab/legged_env#2). ROS graph
names (topics, parameters, controllers, which tools derive from joint names)
allow only letters, digits, `_` and `/`, and a name with a space has to be
quoted in every shell command, YAML file and launch argument that names it.

## How to fix
Rename the link or joint to letters, digits and underscores
(`arm_link`, `link_4_0`), and update every reference to it (joints' parent and
child, `<gazebo reference>`, transmissions, `<ros2_control>`, SRDF,
controller configuration).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import has_xacro

UNSAFE_RE = re.compile(r"[^A-Za-z0-9_./:-]")
USD_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")  # a USD prim name (Isaac Sim)
FIX = "Use letters, digits and underscores only, and rename every reference to it."


def _describe(name: str) -> str:
    bad = sorted({c for c in UNSAFE_RE.findall(name)})
    shown = ", ".join("a space" if c == " " else repr(c) for c in bad)
    return shown


@rule("X014", "unsafe-name", Severity.WARNING, fix=FIX)
def check(doc: Document) -> Iterator[Hit]:
    named = [(link.element, "link", link.name) for link in doc.links]
    named += [(joint.element, "joint", joint.name) for joint in doc.joints]
    named.sort(key=lambda item: item[0].sourceline or 0)  # document order
    renamed: list[tuple[etree._Element, str]] = []
    for el, kind, name in named:
        if not name or not name.strip() or has_xacro(name):
            continue  # X003 and X008
        if UNSAFE_RE.search(name):
            yield Hit(
                el,
                f"{kind} name {name!r} contains {_describe(name)}: Isaac Sim renames it, and "
                "it cannot be a ROS graph name or be written unquoted in YAML and shells",
                attribute="name",
            )
        elif not USD_RE.match(name):
            renamed.append((el, name))
    if renamed and "isaac" in doc.targets:
        yield _isaac(renamed)


def _isaac(renamed: list[tuple[etree._Element, str]]) -> Hit:
    """One note for the names Isaac Sim rewrites (dots, dashes, slashes, a leading digit)."""
    first = ", ".join(repr(name) for _, name in renamed[:3])
    count = f"{len(renamed)} link and joint names are" if len(renamed) > 1 else "a name is"
    return Hit(
        renamed[0][0],
        f"{count} not USD identifiers (first: {first}): Isaac Sim's importer renames them, "
        "so the imported articulation's names differ from the URDF's",
        severity=Severity.INFO,
        attribute="name",
    )
