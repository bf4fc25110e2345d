"""A `<gazebo><material>` names a material script Gazebo does not ship.

## What it does
Checks the script name in `<gazebo reference="link"><material>NAME</material>`:
- a `Gazebo/...` name that is not in Gazebo Classic's stock `gazebo.material` script is
  a warning, with the closest stock name (`Gazebo/Organge` -> `Gazebo/Orange`,
  `Gazebo/Gray` -> `Gazebo/Grey`; names are case-sensitive);
- any other name needs a custom OGRE material script that urdflint cannot see: info
  under `gazebo-classic`, a warning when `gz-sim` is a target, because Gazebo Sim cannot
  load custom OGRE scripts at all;
- an empty `<material/>`, or one holding SDF elements (`<ambient>`, `<script>`...) instead
  of a name, is a warning.

Blocks whose `reference` names nothing (G001) are checked too.

## Why is this bad?
sdformat copies the name into `<visual><material><script><name>` with the hard-coded URI
`file://media/materials/scripts/gazebo.material`. OGRE looks the name up at render time
and, when it is unknown, logs an error and draws the link with the default material, so a
typo silently turns the link grey. Gazebo Sim never supported OGRE scripts; since
Harmonic (gazebosim/gz-sim#2269) it maps the stock `Gazebo/...` solid colours only.
SDF elements put directly under `<gazebo><material>` are read as an (empty) script name
and the block is mangled (gazebosim/sdformat#513, #1534).

## How to fix
Use a stock name such as `Gazebo/Orange`, `Gazebo/DarkGrey` or `Gazebo/FlatBlack`. For
colours that work in both simulators, write SDF material elements inside a visual blob:
`<gazebo reference="link"><visual><material><diffuse>1 0.5 0 1</diffuse></material>...`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import describe, keys_of, materials, suggest, value_of
from urdflint.model.values import has_xacro

PREFIX = "Gazebo/"


@rule(
    "G003",
    "unknown-gazebo-material",
    Severity.WARNING,
    fix="Use a stock Gazebo material name (Gazebo/Orange, Gazebo/Grey, ...).",
)
def check(doc: Document) -> Iterator[Hit]:
    stock, internal = materials()
    gz_sim = "gz-sim" in doc.targets
    for gazebo in doc.gazebo:  # also blocks whose reference names nothing (G001)
        owner = describe(doc, gazebo)
        for el in keys_of(gazebo):
            if el.tag != "material":
                continue
            name = value_of(el)
            if children(el):
                inner = ", ".join(f"<{c.tag}>" for c in children(el)[:3])
                yield Hit(
                    el,
                    f"the <gazebo> <material> of {owner} holds {inner} instead of a script name",
                    fix="Move SDF material elements into <gazebo><visual><material>.",
                )
            elif not name:
                yield Hit(el, f"the <gazebo> <material> of {owner} is empty")
            elif has_xacro(name) or name in stock or name in internal:
                continue
            elif name.startswith(PREFIX) or name.lower().startswith(PREFIX.lower()):
                guess = suggest(name[len(PREFIX) :], sorted(s[len(PREFIX) :] for s in stock))
                hint = f" (did you mean {PREFIX + guess!r}?)" if guess else ""
                yield Hit(el, f"{name!r} on {owner} is not a stock Gazebo material{hint}")
            elif gz_sim:
                yield Hit(
                    el,
                    f"{name!r} on {owner} needs a custom OGRE material script, "
                    "which Gazebo Sim cannot load",
                    fix="Use <gazebo><visual><material> with <ambient>/<diffuse> colours instead.",
                )
            else:
                yield Hit(
                    el,
                    f"{name!r} on {owner} is not a stock Gazebo material and needs a custom "
                    "OGRE material script on GAZEBO_RESOURCE_PATH",
                    fix="Install a .material script that defines it, or use a stock name.",
                    severity=Severity.INFO,
                )
