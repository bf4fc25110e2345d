"""A Gazebo extension key has a value of the wrong type or out of range.

## What it does
Checks the value (text, or a `value="..."` attribute) of every key sdformat's URDF
converter reads in a `<gazebo>` block of the right scope:
- booleans (`selfCollide`, `provideFeedback`, `implicitSpringDamper`, `static`,
  `turnGravityOff`, ...) must be `true`/`false`/`yes`/`no`/`1`/`0`; the copied SDF element
  `<gravity>` takes `true`/`false`/`1`/`0`;
- numbers (`mu1`, `mu2`, `kp`, `kd`, `maxVel`, `minDepth`, `laserRetro`, `dampingFactor`,
  `stopCfm`, `stopErp`, `fudgeFactor`, `springStiffness`, `springReference`) must be decimal
  numbers, `maxContacts` an integer and `fdir1` three numbers;
- ranges: friction, contact stiffness/damping, `maxVel`, `minDepth`, `laserRetro`,
  `maxContacts`, `stopCfm` and `springStiffness` must not be negative; `fudgeFactor`,
  `stopErp` and `dampingFactor` must lie in [0, 1].

A malformed value is an error; a value out of range a warning. The keys of a block whose
`reference` names nothing (G001) are checked as link and joint keys alike.

## Why is this bad?
The converter parses numbers with `std::stod`/`std::stoi`: text that does not start with a
number throws out of the URDF conversion, and trailing junk is silently cut (`0.5.1` reads
as 0.5, `2.7` as 2 for `maxContacts`). Any boolean other than true/yes/1 silently reads as
false (`<selfCollide>on</selfCollide>` disables self-collision), and for `turnGravityOff`
anything but false/no/0 turns gravity off. `fdir1` is copied as text into SDF's `vector3`
`<fdir1>`, which fails to parse unless it is three numbers. Out-of-range values load, but
ODE then sees negative friction or stiffness (unstable contacts), an ERP above 1, or a
`dampingFactor` above 1, which multiplies the link velocity by `1 - dampingFactor` < 0.

## How to fix
Write plain decimal numbers and `true`/`false`, e.g. `<mu1>0.8</mu1>`,
`<fdir1>1 0 0</fdir1>`, `<selfCollide>true</selfCollide>`, within the ranges above.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import KEYS, block_keys, value_of, value_problem


@rule(
    "G004",
    "invalid-gazebo-value",
    Severity.ERROR,
    fix="Write a plain decimal number (or true/false) within the key's valid range.",
)
def check(doc: Document) -> Iterator[Hit]:
    for el, scopes, owner in block_keys(doc):
        key = KEYS.get(str(el.tag))
        if key is None or key.scope not in scopes:
            continue
        problem = value_problem(key, value_of(el))
        if problem is None:
            continue
        reason, out_of_range = problem
        yield Hit(
            el,
            f"<{key.name}> of {owner} {reason}",
            severity=Severity.WARNING if out_of_range else None,
        )
