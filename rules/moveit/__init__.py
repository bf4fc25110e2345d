"""M: MoveIt, the robot's SRDF checked against its URDF."""
