"""T: transmissions (ros_control and legacy pr2_mechanism_model)."""

from urdflint.rules.transmissions import (  # noqa: F401
    t001_transmission_undefined_joint,
    t002_transmission_missing_interface,
    t003_invalid_mechanical_reduction,
    t004_unknown_transmission_element,
    t005_actuator_without_name,
)
