"""Pinocchio cannot build the model, or urdflint did not hand it a broken one.

## What it does
Builds the robot with Pinocchio (`pinocchio.buildModelFromXML`, fixed base) and
reports why it could not, as a sentence naming the joint, link or material:
urdfdom's refusal ("Joint [x] is of type REVOLUTE but it does not specify
limits"), or Pinocchio's own checks, which name no joint ("Some components of
min_dry_friction are greater than max_dry_friction" becomes "joint 'x' has
friction -1 in its `<dynamics>`"). C++ source locations are removed.

Before building, urdflint runs the static rules whose errors make urdfdom refuse
the model or read it wrongly (X003-X005, X008 and X009 errors, S001-S008, S010,
J001, J007, J010 and J013 errors, I012; see `urdflint/physics.py`). If one of them
fires, Pinocchio is not called and this finding names that finding (code, line)
instead: a robot with a link parented twice builds in Pinocchio with that link's
mass counted twice, and an incomplete `<inertial>` is dropped silently.

A model over 2,000 links or 200 links deep is not handed to Pinocchio either
(its parser takes minutes, or overflows the stack and crashes the process); that
is a **warning**, since it is urdflint's limit, not a defect. Real robots have
at most a hundred links, 21 deep.

## Why is this bad?
Every Pinocchio-based tool (Crocoddyl, TSID, Pink, placo, HPP, example-robot-data
users) fails on this file, usually with a bare "The XML stream does not contain a
valid URDF model" and the reason only on stderr. And without a model urdflint
cannot verify the total mass (P003) or the centre of mass (P004).

## How to fix
Fix the element the message names, or the static finding it cites first. For
Pinocchio's effort, velocity and friction checks, write the limits as
non-negative magnitudes: Pinocchio uses `-effort..effort`.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "P001",
    "pinocchio-rejects-model",
    Severity.ERROR,
    needs=("pinocchio",),
    fix="Fix the element the message names; Pinocchio reads the URDF through urdfdom.",
)
def check(doc: Document) -> Iterator[Hit]:
    physics = doc.physics
    if physics.built or physics.missing:
        return
    if physics.blocker is not None:
        found = physics.blocker
        yield Hit(
            None,
            physics.reason,
            fix=f"Fix the {found.code} finding first; urdflint builds the Pinocchio model only "
            "from documents that urdfdom reads as written.",
        )
        return
    if physics.limited:
        yield Hit(
            None,
            physics.reason,
            fix="Check the physics of a smaller model; real robots are far below these limits.",
            severity=Severity.WARNING,
        )
        return
    yield Hit(physics.element, physics.reason)
