"""A `<gazebo>` block uses a key that sdformat deprecated or no longer reads.

## What it does
Flags these children of `<gazebo>` blocks:
- `<cfmDamping>`: still read, but sdformat warns "cfmDamping is being deprecated by
  implicitSpringDamper";
- `<stopKp>`, `<stopKd>`, `<initialJointPosition>`: read by the Gazebo 1.x converter and
  dropped when sdformat was rewritten; today they are copied verbatim into the SDF
  `<joint>`, where SDF does not define them;
- `<canonicalBody>`: read and explicitly ignored ("do nothing with canonicalBody").

`<turnGravityOff>` is not flagged: it is still documented and converted (an SDF
`<gravity>` blob with the opposite value is the alternative).

## Why is this bad?
A removed key does nothing, silently: `<stopKp>1e6</stopKp>` leaves the joint stops at
ODE's defaults (ERP 0.2, CFM 0), so the model does not behave as its author tuned it.
A deprecated key works today and prints a warning on every spawn.

## How to fix
Replace `<cfmDamping>` by `<implicitSpringDamper>`; express joint-stop stiffness and
damping with `<stopErp>` and `<stopCfm>`; delete `<initialJointPosition>` and
`<canonicalBody>`.

`urdflint fix` renames `<cfmDamping>` to `<implicitSpringDamper>` (sdformat reads both the
same way), unless the joint's blocks already have an `<implicitSpringDamper>`. The other
keys have no automatic fix: their replacement is not a rename, or deleting them would hide
what the author meant.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules.gazebo.renaming import rename_key

from urdflint.engine.registry import Hit, rule
from urdflint.model import targets
from urdflint.model.document import Document
from urdflint.model.edits import Repair
from urdflint.model.finding import Severity
from urdflint.model.gazebo_spec import LEGACY, describe, keys_of

# Deprecated keys that sdformat reads exactly like their replacement: a rename fixes them.
RENAMED = {"cfmDamping": "implicitSpringDamper"}


@rule(
    "G005",
    "deprecated-gazebo-element",
    Severity.WARNING,
    fix="Replace the key by its current equivalent, or remove it.",
    targets=targets.GAZEBO,
    fixable="safe",
)
def check(doc: Document) -> Iterator[Hit]:
    for gazebo in doc.gazebo:
        owner = describe(doc, gazebo)
        for el in keys_of(gazebo):
            legacy = LEGACY.get(str(el.tag))
            if legacy is None:
                continue
            state, advice = legacy
            yield Hit(el, f"<{el.tag}> of {owner} is {state}", fix=advice, repair=_rename(doc, el))


def _rename(doc: Document, el: etree._Element) -> Repair | None:
    """Rename a deprecated key to its replacement (see :func:`rename_key`)."""
    return rename_key(doc, el, RENAMED.get(str(el.tag)))
