"""A moving link has no `<inertial>`: Gazebo drops it, MuJoCo makes up its mass or refuses it.

## What it does
Finds links without an `<inertial>` and judges them the way the selected
targets load them, after fixed-joint lumping.

Gazebo (`gazebo-classic`, `gz-sim`; sdformat's URDF converter):

- **error** when the link hangs from a movable joint (or a movable joint hangs
  below it) and neither it nor any link fixed to it has mass;
- **warning** when a massless link that is kept apart from its parent (fixed
  joint to `world`, or lumping disabled with `disableFixedJointLumping` or
  `preserveFixedJoint`) carries visuals or collisions;
- **info** when a link merged into its parent through a fixed joint has
  geometry but no mass.

MuJoCo (`mujoco`; its URDF import computes the inertia of a link without
`<inertial>` from its collision geometry, `inertiafromgeom="auto"`):

- **warning** when a moving link has collision geometry: MuJoCo makes up a mass
  for it at 1000 kg/m³;
- **error** when a moving link has no collision geometry (visuals are discarded)
  and nothing fixed to it has mass, or `<mujoco><compiler
  inertiafromgeom="false"/>` is set: MuJoCo refuses the model;
- **info** when a link under a fixed joint has collision geometry: MuJoCo gives
  it a made-up mass and fuses it into its parent.

With several targets the message names what each does and the severity is the
highest. When no link of the model has an `<inertial>` at all (a kinematics-only
description), one finding on the first moving link lists the links instead of
one finding per link.

Pure frames under fixed joints (sensor, tool and optical frames without
geometry) are not reported: every target merges them into their parent and
nothing is lost. A massless link whose fixed children carry mass is not reported
either: Gazebo, Pinocchio and MuJoCo lump that mass into it. Root links are
I013's (a massless root costs Gazebo the whole model).

## Why is this bad?
- Gazebo (sdformat's URDF converter) drops a link without mass together with
  its parent joint and its whole subtree. sdformat before 9.10.1, 12.7.2 and
  13.5.0 does it without a word (and also drops masses up to 1e-6 kg), so in
  Gazebo Classic a wheel or an arm simply disappears; newer versions print
  "urdf2sdf: link[X] has no <inertial> block defined. Please ensure this link
  has a valid mass to prevent any missing links or joints in the resulting SDF
  model." and still drop it (`CreateSDF` in `parser_urdf.cc`).
- MuJoCo (4.0, observed) gives a moving link without `<inertial>` the mass of
  its collision geometry at 1000 kg/m³ (a 10 cm cube weighs 1 kg), which is
  rarely the part's; with no collision geometry it refuses the model: "mass and
  inertia of moving bodies must be larger than mjMINVAL". A collision mesh it computes
  no volume for ("mesh volume is too small", an OBJ whose first object is flat) it
  refuses with or without an `<inertial>`: C018.
- Pinocchio (4.1, observed) loads a massless moving link with a zero inertia:
  the joint-space mass matrix is singular and `aba` returns NaN.
- PyBullet (3.2.7, observed) warns "No inertial data for link, using mass=1,
  localinertiadiagonal = 1,1,1" and gives the link 1 kg.

## How to fix
Add an `<inertial>` with the link's real mass, centre of mass and inertia
tensor (CAD tools export them). A link that is only a frame should hang from a
`fixed` joint. For the root link, KDL wants no inertia: keep a massless root
(for example `base_footprint`) and fix the real base link, with its mass, to
it.

`urdflint fix --unsafe-fixes` inserts, as the first child of a link that hangs
from a moving joint, an `<inertial>` computed from its collision geometry as a
solid of uniform density (in a kinematics-only model, one in each such link).
The density is the `density` option, 1000 kg/m³ by default (MuJoCo's, water's),
or `--density` on the command line; the fix says the mass it gives. Links
without usable collision geometry (none, or a mesh that cannot be read) get no
fix. The mass is a guess from the density: check it.

```toml
[rules.I001]
density = 2700  # aluminium
```
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from urdflint.rules import consequences as K
from urdflint.rules.inertial import refit

from urdflint.engine.registry import Hit, rule
from urdflint.model import massless
from urdflint.model.bodies import (
    LUMPING,
    MOVABLE,
    Verdict,
    gazebo_verdict,
    mujoco_verdict,
    selected,
)
from urdflint.model.document import Document
from urdflint.model.edits import InsertChild, Operation, Repair
from urdflint.model.effects import single
from urdflint.model.finding import Severity
from urdflint.model.targets import gazebo_label
from urdflint.model.values import fmt
from urdflint.sources.inertia_from_geometry import (
    NOISE,
    NOISE_METRES,
    Estimate,
    geometry_inertial,
    inertial_xml,
    number_text,
)

SHOWN = 3


@rule(
    "I001",
    "missing-inertial",
    Severity.ERROR,
    fix="Add an <inertial> with the link's real mass, centre of mass and inertia.",
    effects=single(K.MISSING_INERTIAL),
    options={"density": 1000.0},
    fixable="unsafe",
)
def check(doc: Document, opts: dict[str, Any]) -> Iterator[Hit]:
    density = float(opts["density"])
    found: dict[str, Verdict] = {}
    for name, link in doc.link_map.items():
        if link.inertial is not None or not doc.graph.parent_joints.get(name):
            continue
        verdict = massless.verdict(doc, name, declared=False)
        if verdict is not None:
            found[name] = verdict
    if len(found) > 1 and all(link.inertial is None for link in doc.links):
        yield _kinematics_only(doc, found, density)
        return
    for name, verdict in found.items():
        yield Hit(
            doc.link_map[name].element,
            f"link '{name}' has no <inertial>, so {verdict.consequence}",
            severity=verdict.severity,
            effects=massless.effects(doc, name, declared=False),
            repair=_repair(doc, [name], density),
        )


def _kinematics_only(doc: Document, found: dict[str, Verdict], density: float) -> Hit:
    """One finding for a model where no link has an ``<inertial>``."""
    moving = [n for n in found if (j := doc.graph.parent_joint(n)) and j.type in MOVABLE]
    first = (moving or list(found))[0]
    parts: list[str] = []
    if selected(doc) & LUMPING:
        gazebo = {n: gazebo_verdict(doc, n) for n in found}
        label = gazebo_label(doc.targets)
        if dropped := [n for n, v in gazebo.items() if v is not None and v.kind == "drop"]:
            parts.append(f"{label} drops {_links(dropped)} with their joints")
        if merged := [n for n, v in gazebo.items() if v is not None and v.kind == "merge"]:
            parts.append(f"{label} merges {_links(merged)} as geometry without mass")
    if "mujoco" in selected(doc):
        mujoco = {n: mujoco_verdict(doc, n, declared=False) for n in found}
        kinds = {n: v.kind for n, v in mujoco.items() if v is not None}
        if refused := [n for n, k in kinds.items() if k == "refuse"]:
            parts.append(f"MuJoCo refuses the model for {_links(refused)} (moving, no mass)")
        if made_up := [n for n, k in kinds.items() if k in ("infer", "fuse")]:
            parts.append(f"MuJoCo makes up the mass of {_links(made_up)} from collision geometry")
    return Hit(
        doc.link_map[first].element,
        "no link has an <inertial> (a kinematics-only model?), so " + "; ".join(parts),
        severity=max(v.severity for v in found.values()),
        fix="Add an <inertial> to every link that moves, or use the model only where "
        "dynamics do not matter (RViz, kinematics).",
        repair=_repair(doc, list(found), density),
    )


def _repair(doc: Document, names: list[str], density: float) -> Repair | None:
    """``<inertial>`` elements computed from the collision geometry of the moving links among
    ``names`` at ``density`` kg/m³ (none for a link without usable collision geometry)."""
    if not (density > 0 and math.isfinite(density)):
        return None
    operations: list[Operation] = []
    made: dict[str, Estimate] = {}
    left: list[str] = []
    for name in names:
        joint = doc.graph.parent_joint(name)
        if joint is None or joint.type not in MOVABLE:
            continue
        estimate = geometry_inertial(doc, name, density=density)
        if estimate is None:
            left.append(name)
            continue
        made[name] = estimate
        xml = inertial_xml(estimate, "  ", "\n")
        operations.append(InsertChild(doc.link_map[name].element, xml))
    if not made:
        return None
    at = f"at {fmt(density)} kg/m³"
    if len(made) == 1:
        ((name, e),) = made.items()
        text = f"insert an <inertial> computed from {refit.source(e)} {at}: {_mass(e)}"
    else:
        each = [f"'{n}' {fmt(e.mass)} kg ({e.method})" for n, e in made.items()]
        if len(each) > SHOWN:
            each = [*each[:SHOWN], f"{len(each) - SHOWN} more"]
        total = fmt(sum(e.mass for e in made.values()))
        text = (
            f"insert <inertial> elements computed from the collision geometry {at} in "
            f"{len(made)} links, {total} kg in all: {', '.join(each)}"
        )
    if left:
        text += f" ({_links(left)} without usable collision geometry left as they are)"
    return Repair("unsafe", text, tuple(operations))


def _mass(estimate: Estimate) -> str:
    """``3 kg, centre of mass 0 0 0.15`` (rounding noise shown as 0, as it is written)."""
    floor = max(NOISE_METRES, NOISE * max(abs(v) for v in estimate.com))
    com = " ".join(number_text(0.0 if abs(v) <= floor else v) for v in estimate.com)
    return f"{fmt(estimate.mass)} kg, centre of mass {com}"


def _links(names: list[str]) -> str:
    """``link 'a'``, ``links 'a' and 'b'``, ``links 'a', 'b', 'c' and 4 more``."""
    quoted = [f"'{n}'" for n in names]
    if len(names) > SHOWN:
        listed = ", ".join(quoted[:SHOWN]) + f" and {len(names) - SHOWN} more"
    else:
        listed = ", ".join(quoted[:-1]) + " and " + quoted[-1] if len(quoted) > 1 else quoted[0]
    return f"link{'s' if len(names) > 1 else ''} {listed}"
