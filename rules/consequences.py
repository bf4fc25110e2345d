"""What each target does with the defects the rules report (the rules' ``effects``).

Observed, by loading planted defects in four robots (``bench/engine_agreement.py``; the
same probes ``--confirm`` runs): MuJoCo 4.0.0, PyBullet 3.2.7 (loaded with
``URDF_USE_INERTIA_FROM_FILE``), Drake 1.51.1, Pinocchio 4.1.0 (its bundled urdfdom), and
sdformat 12.3 (Gazebo's URDF converter; Gazebo Sim uses it, Gazebo Classic uses sdformat
9, whose converter behaves the same for these defects).

From source, not run here:

- Isaac Sim: the C++ URDF importer ``isaacsim.asset.importer.urdf`` 2.4.30 (Isaac Sim
  5.1, ``isaac-sim/IsaacSim`` v5.1.0: ``UrdfParser.cpp``, ``KinematicChain.cpp``,
  ``UrdfImporter.cpp``, ``ImportHelpers.cpp``). Isaac Sim 6 replaced it with a stricter
  Python importer.
- ROS: urdfdom (``ros/urdfdom`` rolling, ``link.cpp``, ``joint.cpp``, ``model.cpp``), which
  robot_state_publisher and MoveIt parse with first (what urdfdom refuses, neither
  starts on), then kdl_parser 2.11 (``kdl_parser.cpp``, robot_state_publisher's tree) and
  MoveIt's ``RobotModel`` (``moveit2`` ``moveit_core/robot_model``).
"""

from __future__ import annotations

from urdflint.model.effects import (
    Consequence,
    Effect,
    changed,
    crash,
    dropped,
    ignored,
    kept,
    limits_changed,
    no_geometry,
    refused,
    substituted,
    unlimited,
    warns,
)
from urdflint.model.finding import Severity

NO_JOINT = "the URDF converter writes no joint for it"
RELATIVE_TO = (
    " and sdformat 12 then refuses the child's pose (\"relative_to name[...] ... does not "
    'match a nested model, link, joint, or frame name")'
)
URDFDOM = "urdfdom refuses it: robot_state_publisher and MoveIt do not start"
SDF = "sdformat's URDF parser (urdfdom) refuses it"
INFO = Severity.INFO


def gazebo(effect: Effect) -> dict[str, Effect]:
    """The same effect for Gazebo Classic and Gazebo Sim (one URDF converter)."""
    return {"gazebo-classic": effect, "gz-sim": effect}


# -- structure --------------------------------------------------------------------------

TWO_PARENTS: dict[str, Effect] = {
    **gazebo(substituted("sdformat lumps the child welded to both parents: mass counted twice")),
    "mujoco": refused('"URDF body has multiple parents"'),
    "drake": kept("Drake builds both joints: a kinematic loop"),
    "pybullet": crash("segmentation fault"),
    "isaac": kept("both joints are authored, a loop PhysX may not resolve"),
    "pinocchio": changed("urdfdom keeps one parent joint, the other is silently ignored"),
    "ros": changed("urdfdom keeps the last parent joint; KDL drops the other silently"),
}

LOOP: dict[str, Effect] = {
    **gazebo(refused('urdfdom: "No root link found"')),
    "pinocchio": refused('urdfdom: "No root link found"'),
    "ros": refused(f'{URDFDOM} ("No root link found")'),
}

SECOND_ROOT: dict[str, Effect] = {
    **gazebo(refused('urdfdom: "Two root links found"')),
    "mujoco": changed("the orphan is welded to the world"),
    "drake": kept("the orphan becomes a free body"),
    "pybullet": crash('segmentation fault after "URDF file with multiple root links found"'),
    "isaac": dropped("only the tree of the alphabetically first root is imported"),
    "pinocchio": refused('"Failed to find root link: Two root links found"'),
    "ros": refused(f'{URDFDOM} ("Two root links found")'),
}

UNDEFINED_LINK: dict[str, Effect] = {
    **gazebo(refused(SDF)),
    "mujoco": refused('"URDF joint parent or child missing"'),
    "drake": refused('"Could not find link named ..."'),
    "pybullet": refused('"Cannot find child link for joint"'),
    "isaac": crash("an uncaught std::out_of_range (map::at) while parsing"),
    "pinocchio": refused('"Failed to build tree: child link [...] not found"'),
    "ros": refused(URDFDOM),
}

DUPLICATE_LINK: dict[str, Effect] = {
    **gazebo(refused(SDF)),
    "mujoco": refused('"repeated URDF name"'),
    "drake": refused('"Body names must be unique within a given model"'),
    "pybullet": refused('"Link name is not unique"'),
    "isaac": dropped("the later definition is silently ignored"),
    "pinocchio": refused("\"link '...' is not unique\""),
    "ros": refused(URDFDOM),
}

DUPLICATE_JOINT: dict[str, Effect] = {
    **gazebo(refused(SDF)),
    "mujoco": kept("MuJoCo loads both joints"),
    "drake": refused('"Frame names must be unique within a given model"'),
    "pybullet": crash("segmentation fault"),
    "isaac": changed("the later definition is silently ignored"),
    "pinocchio": refused("\"joint '...' is not unique\""),
    "ros": refused(URDFDOM),
}

UNKNOWN_JOINT_TYPE: dict[str, Effect] = {
    **gazebo(refused(SDF)),
    "mujoco": refused('"invalid joint type in URDF joint definition"'),
    "drake": refused('"has unrecognized type"'),
    "pybullet": refused(),
    "isaac": refused("\"*** Unknown joint type '...'\""),
    "pinocchio": refused('"Joint [...] has no known type [...]"'),
    "ros": refused(URDFDOM),
}

# -- inertia ----------------------------------------------------------------------------

BAD_TENSOR: dict[str, Effect] = {
    **gazebo(refused('sdformat: "invalid inertia" (when the lumped body keeps it)')),
    "mujoco": refused('"inertia must have positive eigenvalues" or "A + B >= C"'),
    "drake": substituted("warns and uses a small isotropic inertia instead"),
    "pybullet": substituted('"Bad inertia tensor properties, setting inertia to zero"'),
    "isaac": kept("the tensor is diagonalised and written to PhysX unchecked"),
    "pinocchio": kept("builds the model with the tensor as written"),
    "ros": kept("KDL keeps the tensor; robot_state_publisher does not use it", INFO),
}

# A zero principal moment with A + B >= C (a rod, a point mass), observed on a moving link:
# sdformat, Drake and PyBullet load it, MuJoCo refuses (lumping.degenerate: welded links).
DEGENERATE_TENSOR: dict[str, Effect] = {
    **gazebo(kept("sdformat accepts a zero principal moment while A + B >= C holds")),
    "mujoco": refused(
        '"inertia must have positive eigenvalues", or for a point mass "mass and inertia of '
        'moving bodies must be larger than mjMINVAL"'
    ),
    "drake": kept("accepts a zero principal moment"),
    "pybullet": kept("loads the tensor as written"),
    "isaac": kept("the tensor is diagonalised and written to PhysX unchecked"),
    "pinocchio": kept("builds the model with the tensor as written"),
    "ros": kept("KDL keeps the tensor; robot_state_publisher does not use it", INFO),
}

NEGATIVE_MASS: dict[str, Effect] = {
    **gazebo(refused('sdformat: "invalid inertia"')),
    "mujoco": refused('"mass and inertia of moving bodies must be larger than mjMINVAL"'),
    "drake": substituted("warns \"condition 'mass > 0' failed\" and uses 1 kg"),
    "pybullet": kept("loads the negative mass"),
    "isaac": kept("the negative mass is written to PhysX"),
    "pinocchio": kept("the total mass and centre of mass come out wrong"),
    "ros": kept("robot_state_publisher does not use masses", INFO),
}

ROOT_INERTIA: dict[str, Effect] = {
    "ros": ignored(
        'kdl_parser warns "The root link ... has an inertia specified in the URDF, but KDL '
        'does not support a root link with an inertia" and drops it'
    ),
}

WORLD_INERTIA: dict[str, Effect] = {
    **gazebo(dropped("the link named world is the world: its <inertial> is dropped")),
    "drake": dropped("Drake's world body takes no <inertial>: ignored with a warning"),
    "ros": ignored("kdl_parser ignores the root link's inertia"),
}

MASSLESS_MODEL: dict[str, Effect] = gazebo(
    refused(
        'sdformat drops the massless root and every link: "A model must have at least one link"'
    )
)

# -- joints -----------------------------------------------------------------------------

INVERTED_LIMITS: dict[str, Effect] = {
    **gazebo(limits_changed('sdformat warns "lowStop > highStop, switching the two"')),
    "mujoco": unlimited("the joint is built without a range"),
    "drake": crash("aborts: \"condition 'pos_lower_limits <= pos_upper_limits' failed\""),
    "pybullet": unlimited('PyBullet reads lower > upper as "no limit"'),
    "isaac": kept("the inverted range is written to PhysX"),
    "pinocchio": kept("keeps the inverted range"),
    "ros": kept("urdfdom keeps it; MoveIt's bounds then admit no position"),
}

EQUAL_LIMITS: dict[str, Effect] = {
    "mujoco": unlimited('"joint has equal lower and upper limits, limit ignored"'),
}

ZERO_AXIS: dict[str, Effect] = {
    **gazebo(refused('sdformat: "norm of axis cannot be zero"')),
    "mujoco": refused('"axis too small in joint"'),
    "drake": refused('"axis is zero.  Don\'t do that."'),
    "pybullet": kept("the joint has no direction of motion"),
    "isaac": changed("the joint is realigned to an arbitrary axis with a warning"),
    "pinocchio": kept("a joint about no axis"),
    "ros": kept("KDL normalises it to NaN: robot_state_publisher publishes NaN transforms"),
}

NON_UNIT_AXIS: dict[str, Effect] = {
    "isaac": changed("the axis is not normalised: it snaps to X, Y or Z or turns the wrong way"),
}
NON_UNIT_PRISMATIC: dict[str, Effect] = {
    **NON_UNIT_AXIS,
    "ros": changed("MoveIt does not normalise a prismatic axis: motion scales with its length"),
}

NO_LIMIT: dict[str, Effect] = {
    **gazebo(refused(f'{SDF}: "does not specify limits"')),
    "mujoco": kept("the joint is built unlimited"),
    "drake": kept("the joint is built unlimited"),
    "pybullet": refused('"Joint is of type REVOLUTE but it does not specify limits"'),
    "isaac": unlimited("lower and upper default to -FLT_MAX and FLT_MAX"),
    "pinocchio": refused('"is of type REVOLUTE but it does not specify limits"'),
    "ros": refused(URDFDOM),
}

NO_EFFORT_OR_VELOCITY: dict[str, Effect] = {
    **gazebo(refused(SDF)),
    "isaac": refused('"*** effort not specified for limit" (or velocity)'),
    "pinocchio": refused("urdfdom: a <limit> needs effort and velocity"),
    "ros": refused(URDFDOM),
}

NEGATIVE_EFFORT: dict[str, Effect] = {
    "mujoco": kept("uses the absolute value"),
    "isaac": changed("a non-positive limit becomes an unlimited drive"),
    "pinocchio": refused('"Some components of min_effort are greater than max_effort"'),
    "ros": kept("MoveIt uses the absolute value of a negative velocity"),
}

ZERO_EFFORT_OR_VELOCITY: dict[str, Effect] = {
    "isaac": changed("a zero limit becomes an unlimited drive"),
    "ros": changed("MoveIt reads a zero velocity limit as unlimited"),
}

PLANAR: dict[str, Effect] = {
    **gazebo(refused(f"{NO_JOINT}{RELATIVE_TO}")),
    "isaac": refused("the importer has no planar joint (its README says so)"),
    "ros": changed("kdl_parser converts it to a fixed joint: robot_state_publisher never moves it"),
}

FLOATING: dict[str, Effect] = {
    **gazebo(refused(f"{NO_JOINT}{RELATIVE_TO}")),
    "drake": warns("\"not supported by MultibodyPlant. Leaving '...' as a free body\"", INFO),
    "pybullet": Effect(
        Consequence.JOINT_CHANGED,
        '"joint unsupported, creating a fixed joint instead"',
        Severity.WARNING,
    ),
    "isaac": Effect(Consequence.JOINT_CHANGED, "no joint: the child is a free body", INFO),
    "ros": Effect(
        Consequence.JOINT_CHANGED,
        "kdl_parser converts it to a fixed joint: robot_state_publisher skips it",
        Severity.WARNING,
    ),
}
FLOATING_MUJOCO = refused('"free joint can only be used on top level"')

CALIBRATION: dict[str, Effect] = {
    **gazebo(ignored()),
    "mujoco": ignored(),
    "drake": ignored("\"The tag 'calibration' ... is currently unsupported and will be ignored\""),
    "pybullet": ignored(),
    "isaac": ignored(),
    "pinocchio": ignored(),
}

SAFETY_CONTROLLER: dict[str, Effect] = {
    **gazebo(ignored()),
    "mujoco": ignored(),
    "drake": ignored("\"The tag 'safety_controller' ... is currently unsupported\""),
    "pybullet": ignored(),
    "isaac": ignored(),
    "pinocchio": ignored(),
    "ros": kept("MoveIt narrows the joint's bounds to the soft limits", INFO),
}

MIMIC_DOF: dict[str, Effect] = {
    "mujoco": ignored(
        '"<mimic> on joint ... ignored; mimic requires revolute, continuous, or prismatic joints"',
        Severity.WARNING,
    ),
    "drake": refused('"Joint ... which has N DOF cannot mimic joint ... which has 1 DOF"'),
}

MIMIC_OF_FLOATING: dict[str, Effect] = {
    "mujoco": MIMIC_DOF["mujoco"],
    "drake": warns("Drake leaves a floating child as a free body: the mimic is not applied"),
}

MIMIC_UNDEFINED: dict[str, Effect] = {
    "mujoco": ignored('"<mimic> on joint ... ignored"', Severity.WARNING),
    "drake": refused("\"mimic element specifies joint '...' which does not exist\""),
    "ros": warns("urdfdom does not check it; MoveIt logs an error for the unknown joint"),
}

# -- document ---------------------------------------------------------------------------

INVALID_NUMBER: dict[str, Effect] = {
    "mujoco": refused('"XML Error: bad format in attribute"'),
    "drake": refused('"Expected single value for attribute"'),
    "pybullet": kept("reads the number it can (often 0)"),
    "isaac": changed("reads a valid prefix ('1.5abc' is 1.5) or falls back to a default"),
    "pinocchio": kept("loads it"),
    "ros": refused(f"{URDFDOM} (the whole value must be a number)"),
}

INVALID_MASS: dict[str, Effect] = {
    **INVALID_NUMBER,
    **gazebo(dropped("sdformat reads no mass, so it drops the link and its joint")),
    "isaac": substituted("a mass that is not a number counts as no mass"),
}

TINY_MASS: dict[str, Effect] = gazebo(
    dropped("sdformat before 12.7.2 counts it as zero and drops the link")
)

URDF_VERSION: dict[str, Effect] = {
    **gazebo(refused(f'{SDF}: "only version 1.0 is currently supported"')),
    "drake": ignored("\"The attribute 'version' ... will be ignored\"", INFO),
    "ros": refused(f"{URDFDOM} (\"Invalid 'version' specified\")"),
}

# -- geometry ---------------------------------------------------------------------------

DEGENERATE_SHAPE: dict[str, Effect] = {
    **gazebo(no_geometry("the shape is dropped without a message")),
    "mujoco": refused('"size 0 must be positive in geom"'),
    "drake": crash("aborts when the shape is registered with SceneGraph"),
    "pybullet": kept("builds the shape with the size as written"),
    "isaac": kept("a mirrored or flat collider"),
    "pinocchio": no_geometry("the geometry model drops it (logged)"),
    "ros": kept("MoveIt's geometric_shapes rejects a negative box size"),
}

MISSING_MESH: dict[str, Effect] = {
    **gazebo(no_geometry("Gazebo prints an error and shows nothing there")),
    "mujoco": refused('"Error opening file"'),
    "drake": refused("the mesh is read when it is registered with SceneGraph"),
    "pybullet": refused('"Could not parse collision element for Link"'),
    "isaac": no_geometry('"Failed to resolve mesh"; the shape is left out'),
    "pinocchio": refused('buildGeomFromUrdf: "Mesh ... could not be found"'),
    "ros": no_geometry("RViz draws nothing there, MoveIt has no collision shape"),
}

NEWER_URDF_VERSION: dict[str, Effect] = {
    **gazebo(refused("sdformat 12's urdfdom reads only version 1.0")),
    "drake": ignored("\"The attribute 'version' ... will be ignored\"", INFO),
    "ros": warns("urdfdom before 4.0 (ROS 2 Humble and older) refuses it", INFO),
}

# A moving link without <inertial> or with mass 0, and nothing welded to it with mass (the
# rules work the effects out per link: lumping, collision geometry, MuJoCo's static bodies;
# this is the typical case, for the rule's page).
MISSING_INERTIAL: dict[str, Effect] = {
    **gazebo(dropped("sdformat drops the link, its joint and the links below it")),
    "mujoco": substituted("inertia from its collision geometry at 1000 kg/m³ (refused without)"),
    "drake": kept("a massless body: its mass matrix is singular"),
    "pybullet": substituted('"No inertial data for link, using mass=1"'),
    "isaac": substituted('"No mass specified for link": PhysX computes it from the colliders'),
    "pinocchio": kept("a massless body: its mass matrix is singular"),
}

ZERO_MASS: dict[str, Effect] = {
    **gazebo(dropped("sdformat drops the link, its joint and the links below it")),
    "mujoco": refused('"mass and inertia of moving bodies must be larger than mjMINVAL"'),
    "drake": kept("a massless body: its mass matrix is singular"),
    "pybullet": kept("a massless body: its mass matrix is singular"),
    "pinocchio": kept("a massless body: its mass matrix is singular"),
}
