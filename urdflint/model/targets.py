"""The consumers a model is meant for.

A target changes the messages and severities of target rules (G002, J004,
J012, ...) and the effects findings carry (:mod:`urdflint.model.effects`), never whether
the model is structurally valid. ``all`` selects every target.
"""

from __future__ import annotations

TARGETS: dict[str, str] = {
    "gazebo-classic": "Gazebo Classic (gazebo 9/11, sdformat 9): URDF colours are ignored, "
    "links without mass are dropped silently",
    "gz-sim": "Gazebo Sim (Fortress and later, sdformat >= 11.2): URDF colours become SDF "
    "materials, massless links are dropped with a warning",
    "mujoco": "MuJoCo's URDF import: STL and OBJ meshes only (no Collada), inertia must "
    "satisfy A + B >= C, transmissions are ignored, mimic becomes an equality constraint",
    "drake": "Drake's URDF parser (pydrake): invalid inertias are replaced with a warning, "
    "inverted limits abort the process, <calibration> and friction are warned about",
    "pybullet": "PyBullet's URDF loader: invalid inertias are loaded as written (or zeroed "
    "with URDF_USE_INERTIA_FROM_FILE), a missing <inertial> becomes 1 kg, two roots crash",
    "isaac": "Isaac Sim's URDF importer (PhysX): links without mass get it from collision "
    "density, unknown package paths lose their meshes, mimic joints are converted",
    "pinocchio": "Pinocchio's URDF parser (urdfdom): kinematics and dynamics as written, "
    "a second root or a missing link refuses the model",
    "ros": "ROS: urdfdom (robot_state_publisher), KDL (kdl_parser) and MoveIt's RobotModel: "
    "kinematics only, KDL ignores the root link's inertia",
}
DEFAULT_TARGETS: tuple[str, ...] = ("gazebo-classic",)
ALL = "all"

LABELS: dict[str, str] = {
    "gazebo-classic": "Gazebo Classic",
    "gz-sim": "Gazebo Sim",
    "mujoco": "MuJoCo",
    "drake": "Drake",
    "pybullet": "PyBullet",
    "isaac": "Isaac Sim",
    "pinocchio": "Pinocchio",
    "ros": "ROS (KDL, MoveIt)",
}

# The --confirm engine that shows what a target does (None: not runnable here, the
# prediction follows the consumer's source and documentation).
ENGINE: dict[str, str | None] = {
    "gazebo-classic": "sdformat",
    "gz-sim": "sdformat",
    "mujoco": "mujoco",
    "drake": "drake",
    "pybullet": "pybullet",
    "isaac": None,
    "pinocchio": "pinocchio",
    "ros": None,
}

# Where each target's effects come from (a rule's page says it beside each one).
BASIS: dict[str, str] = {
    "gazebo-classic": "observed with sdformat 12.3; Classic's sdformat 9 converts alike",
    "gz-sim": "observed with sdformat 12.3",
    "mujoco": "observed with MuJoCo 4.0",
    "drake": "observed with Drake 1.51",
    "pybullet": "observed with PyBullet 3.2.7",
    "isaac": "from the importer's source, Isaac Sim 5.1",
    "pinocchio": "observed with Pinocchio 4.1",
    "ros": "from the source of urdfdom, kdl_parser and MoveIt",
}


def validate(names: list[str] | tuple[str, ...]) -> tuple[str, ...]:
    """Check target names (``all`` expands to every target); raises ``ValueError`` naming
    the unknown one."""
    found: list[str] = []
    for name in names:
        if name == ALL:
            found.extend(TARGETS)
        elif name in TARGETS:
            found.append(name)
        else:
            known = ", ".join(TARGETS)
            raise ValueError(f"unknown target {name!r} (known: {known}, {ALL})")
    return tuple(dict.fromkeys(found))


def ordered(names: frozenset[str] | tuple[str, ...]) -> tuple[str, ...]:
    """``names`` in the canonical order of :data:`TARGETS`."""
    return tuple(t for t in TARGETS if t in names)


def gazebo_label(targets: frozenset[str]) -> str:
    """'Gazebo Classic', 'Gazebo Sim' or 'Gazebo' when both are selected."""
    gazebos = [LABELS[t] for t in ("gazebo-classic", "gz-sim") if t in targets]
    return gazebos[0] if len(gazebos) == 1 else "Gazebo"


GAZEBO: tuple[str, ...] = ("gazebo-classic", "gz-sim")
