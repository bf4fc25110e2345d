"""A link's mass is zero or negative.

## What it does
Reports `<mass value>` below zero (always an error) and mass zero where Gazebo
would drop the link, judged like I001: an error when the link hangs from a
movable joint and nothing fixed to it has mass, a warning for a massless root
link or a massless link kept apart from its parent, and info for a merged link
with geometry. A zero mass on a pure frame under a fixed joint (a common way to
write "this is only a frame") is not reported.

## Why is this bad?
- Negative mass is not physical: sdformat and gz-math refuse the link ("A link
  named X has invalid inertia"), MuJoCo refuses the model, Drake substitutes a
  made-up inertia with a warning, and Pinocchio computes a centre of mass of
  NaN.
- Zero mass makes Gazebo drop the link, its joint and its subtree (silently
  before sdformat 9.10.1, 12.7.2 and 13.5.0; "has a mass value of less than or
  equal to zero" after), and gives Pinocchio a singular mass matrix.

## How to fix
Write the link's real mass in kilograms. A link that is only a frame should
hang from a `fixed` joint.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.bodies import bodies, massless_verdict
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.values import fmt


@rule("I002", "non-positive-mass", Severity.ERROR, fix="Write the link's real mass in kilograms.")
def check(doc: Document) -> Iterator[Hit]:
    for name, inertial in bodies(doc).inertials.items():
        if inertial is None or inertial.mass is None or inertial.mass > 0:
            continue
        if inertial.mass < 0:
            message = f"link '{name}' has mass {fmt(inertial.mass)} kg"
            yield Hit(inertial.mass_element, message, attribute="value")
            continue
        verdict = massless_verdict(doc, name)
        if verdict is not None:
            yield Hit(
                inertial.mass_element,
                f"link '{name}' has mass 0 kg, so {verdict.consequence}",
                severity=verdict.severity,
                attribute="value",
            )
