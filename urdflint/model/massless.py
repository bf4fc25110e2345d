"""What every target does with a link that has no mass of its own (I001, I002, I013).

:func:`~urdflint.model.bodies.massless_verdict` judges Gazebo (lumping, dropped links) and
MuJoCo (inertia from geometry, refusals); this module adds the other targets and turns
the lot into per-target :class:`~urdflint.model.effects.Effect` values:

- PyBullet 3.2.7 (observed) gives a link without ``<inertial>`` mass 1 kg and a unit
  inertia ("No inertial data for link, using mass=1, localinertiadiagonal = 1,1,1") and
  loads a declared zero mass as written;
- Drake 1.51 and Pinocchio 4.1 (observed) load a massless moving link as written: its
  mass matrix is singular, forward dynamics fail or return NaN;
- Isaac Sim's importer (source: ``UrdfImporter.cpp``) computes a missing mass from the
  collision shapes at its ``density`` setting, or, without colliders, "assigning a small
  isotropic inertia matrix";
- ROS (robot_state_publisher, MoveIt) does not use masses.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from urdflint.model import effects as fx
from urdflint.model.bodies import (
    MOVABLE,
    Verdict,
    bodies,
    gazebo_verdict,
    massless_verdict,
    mujoco_verdict,
    selected,
)
from urdflint.model.effects import Effect
from urdflint.model.finding import Severity
from urdflint.model.targets import LABELS

if TYPE_CHECKING:
    from urdflint.model.document import Document

PYBULLET_GUESS = "PyBullet gives it mass 1 kg and a unit inertia"
SINGULAR = "with no mass: its joint's mass matrix is singular"


def moving(doc: Document, name: str) -> bool:
    """The link hangs from a movable joint and nothing welded to it has mass."""
    joint = doc.graph.parent_joint(name)
    if joint is None or joint.type not in MOVABLE:
        return False
    mass = bodies(doc).mass(name)
    return mass is None or mass <= 0


def others(doc: Document, name: str, declared: bool) -> dict[str, Effect]:
    """The effects on the targets other than Gazebo and MuJoCo. PyBullet keeps every link
    apart (no lumping): a moving link without ``<inertial>`` gets its 1 kg even when links
    welded to it have mass."""
    found: dict[str, Effect] = {}
    joint = doc.graph.parent_joint(name)
    if not declared and joint is not None and joint.type in MOVABLE:
        found["pybullet"] = fx.substituted(PYBULLET_GUESS)
    if not moving(doc, name):
        return found
    if declared:
        found["pybullet"] = fx.kept(f"PyBullet loads it {SINGULAR}")
    found["drake"] = fx.kept(f"Drake loads it {SINGULAR}")
    found["pinocchio"] = fx.kept(f"Pinocchio loads it {SINGULAR}")
    link = doc.link_map[name]
    if not declared:
        source = "its collision shapes at the importer's density" if link.collisions else None
        found["isaac"] = fx.substituted(
            f"Isaac Sim computes its mass from {source}"
            if source
            else "Isaac Sim assigns a small isotropic inertia"
        )
    return found


def effects(doc: Document, name: str, declared: bool) -> dict[str, Effect]:
    """Every selected target's effect for the massless link ``name``."""
    found = others(doc, name, declared)
    gazebo = gazebo_verdict(doc, name)
    if gazebo is not None:
        effect = (
            fx.dropped(gazebo.consequence)
            if gazebo.kind == "drop"
            else fx.ignored(gazebo.consequence)
        )
        found["gazebo-classic"] = found["gz-sim"] = effect
    mujoco = mujoco_verdict(doc, name, declared)
    if mujoco is not None:
        found["mujoco"] = (
            fx.refused(mujoco.consequence)
            if mujoco.kind == "refuse"
            else fx.substituted(mujoco.consequence)
        )
    return found


def verdict(doc: Document, name: str, declared: bool = True) -> Verdict | None:
    """:func:`massless_verdict` plus what PyBullet, Drake, Isaac Sim and Pinocchio do, when
    they are selected (warnings: they load the link, with a made-up or no mass)."""
    base = massless_verdict(doc, name, declared)
    chosen = selected(doc)
    extra = {t: e for t, e in others(doc, name, declared).items() if t in chosen}
    if not extra:
        return base
    parts = [base.consequence] if base is not None else []
    same = [t for t, e in extra.items() if e.consequence is fx.Consequence.AS_WRITTEN]
    for target, effect in extra.items():
        if target not in same:
            parts.append(effect.detail)
    if same:
        names = " and ".join(LABELS[t] for t in same)
        parts.append(f"{names} load{'s' if len(same) == 1 else ''} it {SINGULAR}")
    severity = max([Severity.WARNING] + ([base.severity] if base is not None else []))
    return Verdict(severity, "; ".join(parts), base.kind if base is not None else "")
