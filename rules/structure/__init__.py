"""S: structure (names, references, the kinematic tree, mimic joints, materials)."""

from urdflint.rules.structure import (  # noqa: F401
    s001_duplicate_link,
    s002_duplicate_joint,
    s003_undefined_link,
    s004_multiple_roots,
    s005_kinematic_loop,
    s006_invalid_joint_type,
    s007_missing_parent_or_child,
    s008_undefined_mimic_joint,
    s009_undefined_material,
    s010_duplicate_material,
    s011_no_links,
)
