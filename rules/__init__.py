"""The rule catalogue: one family per package, one module per rule.

Importing this package registers every rule (explicit imports, greppable).
"""

from urdflint.rules import (  # noqa: F401
    conventions,
    document,
    engines,
    gazebo,
    geometry,
    inertial,
    joints,
    meta,
    moveit,
    physics,
    ros2_control,
    structure,
    transmissions,
)
