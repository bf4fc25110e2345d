"""J: joints (limits, axes, origins, elements and types the consumers ignore or drop)."""

from urdflint.rules.joints import (  # noqa: F401
    j001_missing_limit,
    j002_calibration_ignored,
    j003_safety_controller_ignored,
    j004_dynamics_friction_ignored,
    j005_limit_ignored_for_type,
    j006_axis_ignored_for_type,
    j007_zero_axis,
    j008_non_unit_axis,
    j009_inverted_limits,
    j010_non_positive_effort_or_velocity,
    j011_missing_joint_origin,
    j012_unsupported_joint_type_for_target,
    j013_incomplete_joint_element,
    j014_mimic_of_fixed_joint,
    j015_limit_in_degrees,
    j017_mimic_not_enforced,
    j018_mimic_range_outside_limits,
)
