"""An engine named by `--confirm` printed a warning while loading the model.

## What it does
Captures everything each engine printed while loading the model (C and C++ output
included: the engine runs in its own process, whose output is read) and reports each
distinct warning once, on the element it names by line or by name, else on `<robot>`:

- PyBullet's `b3Warning[...]` lines, e.g. "No inertial data for link, using mass=1,
  localinertiadiagonal = 1,1,1" (PyBullet replaces a missing `<inertial>`).
- Drake's warnings ("FILE:LINE: warning: ..."), e.g. a non-positive mass it cannot
  re-express as a central inertia.
- urdfdom's `Warning:` lines (Pinocchio), and MuJoCo's `WARNING:` lines (its
  `MUJOCO_LOG.TXT`).

Without `--confirm` E006 does nothing.

## Why is this bad?
A warning at load time is the engine telling you it read something else than the file
says, usually by replacing a value with a default. It scrolls past in a terminal and
is lost in a launch log.

## How to fix
Fix the element the warning names so that the engine reads the model as written.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "E006",
    "engine-warning",
    Severity.INFO,
    fix="Fix the element the warning names, so that the engine reads what the file says.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        for warning in outcome.warnings:
            yield Hit(warning.element, f"{label(outcome.engine)} warns: {warning.text}")
