"""The consumers a model is meant for.

A target changes the messages and severities of target rules (G002, J004,
J012, ...), never whether the model is structurally valid.
"""

from __future__ import annotations

TARGETS: dict[str, str] = {
    "gazebo-classic": "Gazebo Classic (gazebo 9/11, sdformat 9): URDF colours are ignored, "
    "links without mass are dropped silently",
    "gz-sim": "Gazebo Sim (Fortress and later, sdformat >= 11.2): URDF colours become SDF "
    "materials, massless links are dropped with a warning",
    "mujoco": "MuJoCo's URDF import: STL and OBJ meshes only (no Collada), inertia must "
    "satisfy A + B >= C, transmissions are ignored, mimic becomes an equality constraint",
}
DEFAULT_TARGETS: tuple[str, ...] = ("gazebo-classic",)

LABELS: dict[str, str] = {
    "gazebo-classic": "Gazebo Classic",
    "gz-sim": "Gazebo Sim",
    "mujoco": "MuJoCo",
}


def validate(names: list[str] | tuple[str, ...]) -> tuple[str, ...]:
    """Check target names; raises ``ValueError`` naming the unknown one."""
    for name in names:
        if name not in TARGETS:
            known = ", ".join(TARGETS)
            raise ValueError(f"unknown target {name!r} (known: {known})")
    return tuple(dict.fromkeys(names))


def gazebo_label(targets: frozenset[str]) -> str:
    """'Gazebo Classic', 'Gazebo Sim' or 'Gazebo' when both are selected."""
    gazebos = [LABELS[t] for t in ("gazebo-classic", "gz-sim") if t in targets]
    return gazebos[0] if len(gazebos) == 1 else "Gazebo"


GAZEBO: tuple[str, ...] = ("gazebo-classic", "gz-sim")
