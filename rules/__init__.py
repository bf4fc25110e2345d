"""The rule catalogue: one family per package, one module per rule.

Importing a family package registers its rules (explicit imports, greppable). The engine
imports only the families a run selects (``registry.load_rules``), so ``--select X`` never
pays for the Gazebo or geometry rules; ``PACKAGES`` maps each family letter to its package.
"""

PACKAGES: dict[str, str] = {
    "X": "document",
    "S": "structure",
    "I": "inertial",
    "C": "geometry",
    "G": "gazebo",
    "J": "joints",
    "T": "transmissions",
    "R": "ros2_control",
    "M": "moveit",
    "N": "conventions",
    "P": "physics",
    "D": "statics",
    "E": "engines",
    "U": "meta",
}
