"""R: ros2_control blocks (`<ros2_control>` hardware, joints, sensors, GPIOs, interfaces)."""

from urdflint.rules.ros2_control import (  # noqa: F401
    r001_misplaced_ros2_control,
    r002_invalid_ros2_control_hardware,
    r003_malformed_ros2_control_element,
    r004_ros2_control_undefined_joint,
    r005_ros2_control_mimic_joint,
    r006_duplicate_ros2_control_interface,
    r007_invalid_ros2_control_interface_param,
    r008_misspelt_ros2_control_interface,
    r009_ros2_control_transmission_joint,
)
