"""G: Gazebo extensions (``<gazebo>`` blocks, materials, fixed-joint lumping, ros_control)."""

from urdflint.rules.gazebo import (  # noqa: F401
    g001_undefined_gazebo_reference,
    g002_urdf_color_ignored,
    g003_unknown_gazebo_material,
    g004_invalid_gazebo_value,
    g005_deprecated_gazebo_element,
    g006_unrecognized_gazebo_element,
    g007_gazebo_element_wrong_scope,
    g008_gazebo_reference_lumped,
    g009_missing_ros_control_plugin,
)
