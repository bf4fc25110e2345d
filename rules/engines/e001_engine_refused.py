"""An engine named by `--confirm` refuses to load the model.

## What it does
With `urdflint check --confirm mujoco,pybullet,drake,pinocchio,sdformat` (or `all`), each
installed engine loads the model in its own process, and E001 reports every engine
that raised or refused instead of building it. The message is the engine's name and
the first line of its reason, as it printed it; the finding sits on the link or joint
the reason names (by line, as MuJoCo and Drake give it, or by name), else on `<robot>`:

- MuJoCo (`mujoco.MjModel.from_xml_path`) raises `ValueError` ("XML Error: URDF joint
  parent or child missing, Element 'joint', line 28").
- PyBullet (`pybullet.loadURDF`, fixed base) prints `b3Error[...]` lines and raises
  "Cannot load URDF file."; the message is the printed reason.
- Drake (`pydrake` `Parser(plant).AddModels`) raises `RuntimeError` with
  "FILE:LINE: error: ...".
- Pinocchio (`pinocchio.buildModelFromUrdf`) raises "does not contain a valid URDF
  model"; urdfdom's printed `Error:` line is the message.
- sdformat (Gazebo's URDF converter, `sdf::Root::Load` in a small compiled probe)
  returns errors, and Gazebo refuses a model whose load returned any: the first error
  sdformat or urdfdom printed is the message. sdformat 12.3 refuses a link whose inertia
  is invalid ("A link named arm has invalid inertia.": a negative mass or moment, a
  tensor that is not positive definite, moments that break the triangle inequality), a
  zero joint axis ("The norm of the xyz vector cannot be zero"), a link with two parents
  ("link with name[arm] already exists."), a `planar` or `floating` joint (it writes no
  joint, and the orphaned link's pose is "relative_to name[j1] ... does not match"),
  a model left without links (a root link without mass: "A model must have at least one
  link.") and whatever urdfdom refuses (two roots, an undefined link).

An engine that is not installed is not a refusal: E007 `engine-unavailable` notes it.
Without `--confirm`, or a `confirm` key in the configuration, E001 does nothing.

## Why is this bad?
The static rules describe the URDF specification and what urdfdom does; each engine has
its own parser, with its own rules and blind spots. A model your simulator refuses is
unusable there, whatever the linter says.

## How to fix
Fix the element the engine names. Most refusals also have a static finding (S, J, I
rules) on the same element that explains the cause. An engine that is not
installed is E007's note.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.engines.common import label, outcomes

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity


@rule(
    "E001",
    "engine-refused",
    Severity.ERROR,
    fix="Fix the element the engine names; a static finding there usually explains why.",
)
def check(doc: Document) -> Iterator[Hit]:
    for outcome in outcomes(doc):
        if outcome.installed and outcome.refusal is not None:
            reason = outcome.refusal
            yield Hit(
                reason.element,
                f"{label(outcome.engine)} refused the model: {reason.text}",
                engine=outcome.engine,
            )
