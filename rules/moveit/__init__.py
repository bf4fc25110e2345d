"""M: MoveIt, the robot's SRDF checked against its URDF."""

from urdflint.rules.moveit import (  # noqa: F401
    m001_srdf_unreadable,
    m002_srdf_robot_name_mismatch,
    m003_group_unknown_member,
    m004_chain_reversed,
    m005_unknown_group,
    m006_end_effector_parent,
    m007_virtual_joint_not_root,
    m008_passive_joint_invalid,
    m009_collision_pair_unknown_link,
    m010_group_state_unknown_joint,
    m011_group_state_out_of_limits,
)
