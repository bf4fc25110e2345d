"""An engine named by `--confirm` crashed, aborted or hung while loading the model.

## What it does
Each engine loads the model in its own process (`python -m urdflint.engines.probe`; for
sdformat a small compiled program that calls `sdf::Root::Load`), with a memory limit
(3 GiB of address space on POSIX) and a 60 s timeout. E005 reports a process that died by
a signal (a segmentation fault, an `abort()`), exited without reporting what it built, or
did not finish in time. For example PyBullet 3.2.7 prints "URDF file with multiple root
links found" and then dies with SIGSEGV on a model with two root links. The finding is on
`<robot>`; the message says how the process ended and the last error the engine printed.

Without `--confirm` E005 does nothing.

## Why is this bad?
The simulator, or the program that embeds it, dies with it: a crash in a training job
or a launch file, often without any message. Engines trust their input; a crash is a
defect of the model the engine did not diagnose.

## How to fix
Read the other findings on the model (E006 lists what the engine printed before dying,
S and J rules what is structurally wrong) and fix them; then run the check again.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "E005",
    "engine-crashed",
    Severity.ERROR,
    fix="Fix what the other findings report; engines crash on models they do not check.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if outcome.crash is not None:
            yield Hit(None, f"{label(outcome.engine)} crashed loading the model: the process "
                      f"{outcome.crash}", engine=outcome.engine)  # fmt: skip
