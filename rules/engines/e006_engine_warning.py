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
- sdformat's `Warning [file:line]` console lines (`sdfwarn`), e.g. "urdf2sdf: revolute
  joint [elbow] with limits: lowStop[1] > highStop[-1], switching the two." or
  "Non-unique name[arm] detected 2 times in XML children of model". Its debug log
  (`sdfdbg`, which alone says that a massless link was "not modeled in sdf") is not read:
  E002 reports those links.

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
            yield Hit(
                warning.element,
                f"{label(outcome.engine)} warns: {warning.text}",
                engine=outcome.engine,
            )
