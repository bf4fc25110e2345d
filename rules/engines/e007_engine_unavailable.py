"""An engine named by `--confirm` is not installed here, so the model was not loaded in it.

## What it does
With `urdflint check --confirm ...` (or a `confirm` key in the configuration), notes once
per file and engine that the engine cannot run on this machine: its Python package is
not importable (mujoco, pybullet, pydrake, pinocchio), or, for sdformat, the
`sdformat12` development files or `g++` are missing or its probe did not compile (the
compiler's first error is given). It is an **info**: nothing was confirmed with that
engine, and nothing is wrong with the model. Without `--confirm` it does nothing.

## Why is this bad?
It is not a defect of the model: it says that a clean confirmation is not a confirmation
by that engine. `--matrix` shows the engine's column as "not installed". Baselines never
record it (like U004), so a baseline written where the engines are installed stays valid
where they are not.

## How to fix
Install the engine: the Python engines come with the `engines` extra (from a checkout,
`pip install -e '.[engines]'`: mujoco, pybullet, drake, pin); sdformat with
`apt-get install libsdformat-dev g++ pkg-config` (the probe is compiled on first use,
into `~/.cache/urdflint/`). Or leave the engine out of `--confirm`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import install, label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "E007",
    "engine-unavailable",
    Severity.INFO,
    fix="Install the engine, or leave it out of --confirm.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if not outcome.installed:
            why = f": {outcome.reason}, so it" if getattr(outcome, "reason", None) else ""
            yield Hit(
                None,
                f"{label(outcome.engine)}{why} is not installed: the model was not loaded in it",
                fix=install(outcome.engine),
                engine=outcome.engine,
            )
