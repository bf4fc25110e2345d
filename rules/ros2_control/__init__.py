"""R: ros2_control blocks (`<ros2_control>` hardware, joints, sensors, GPIOs, interfaces)."""
