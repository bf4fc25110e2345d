"""Pinocchio refuses the model, or builds it but reads something else than the file says.

## What it does
Builds the robot with Pinocchio (`pinocchio.buildModelFromXML`, fixed base) and
reports:

- a **refusal**, as a sentence naming the joint, link or material: urdfdom's
  reason ("Joint [x] is of type REVOLUTE but it does not specify limits"), or
  Pinocchio's own checks, which name no joint ("Some components of
  min_dry_friction are greater than max_dry_friction" becomes "joint 'x' has
  friction -1 in its `<dynamics>`"). C++ source locations are removed. When a
  static error explains the refusal (a missing `<limit>`, a negative effort, a
  duplicate name...), the message cites it.
- a **misread**: Pinocchio builds the model, but not the one written. An
  `<inertial>` that urdfdom cannot read (a malformed or missing value: X004,
  X005, X008, I012) leaves the link with a zero inertia tensor, and with no
  mass when `<mass>` or the inertial origin is at fault; a zero axis on a
  revolute, continuous or prismatic joint (J007) gives a joint that cannot
  move. The message says which link or joint and cites the static finding.
- a link with two parent joints or a kinematic loop (S005): the model is not
  handed to Pinocchio at all. urdfdom does not notice it; Pinocchio 4.1 then
  refuses the model ("Model does not have any body named X"), builds it
  without one of the joints, or crashes the process (a link that is its own
  parent). The message names the S005 finding.

When a static finding explains the refusal or the misread, P001 is a
robot-level finding that cites it (that finding already points at the element);
otherwise it sits on the element Pinocchio names.

A model that Pinocchio builds and reads as written is not reported, even when
other rules report errors on it (P001 does not repeat them): Pinocchio ignores
`<mimic>` targets, accepts negative masses and inverted limits, and so on.

A model over 2,000 links or 200 links deep is not handed to Pinocchio either
(its parser takes minutes, or overflows the stack and crashes the process); that
is a **warning**, since it is urdflint's limit, not a defect. Real robots have
at most a hundred links, 21 deep.

## Why is this bad?
Every Pinocchio-based tool (Crocoddyl, TSID, Pink, placo, HPP, example-robot-data
users) fails on a refused file, usually with a bare "The XML stream does not
contain a valid URDF model" and the reason only on stderr. A misread one loads
without a word and computes wrong dynamics. Either way urdflint cannot verify the
total mass (P003) or the centre of mass (P004).

## How to fix
Fix the element the message names, or the static finding it cites. For
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
    if not doc.links:
        return  # S011 reports the robot without links; Pinocchio's refusal adds nothing
    physics = doc.physics
    if physics.built or physics.missing or physics.reason is None:
        return
    if physics.limited:
        yield Hit(
            None,
            physics.reason,
            fix="Check the physics of a smaller model; real robots are far below these limits.",
            severity=Severity.WARNING,
        )
        return
    found = physics.blocker
    if found is None:
        yield Hit(physics.element, physics.reason)
        return
    # the static finding already points at the element: P001 speaks for the whole model
    yield Hit(None, physics.reason, fix=f"Fix the {found.code} finding ({found.where}).")
