"""P: physics, computed with Pinocchio (needs the dynamics extra)."""

from urdflint.rules.physics import (  # noqa: F401
    p001_pinocchio_rejects_model,
    p002_mass_accounting,
    p003_expected_mass,
    p004_expected_com,
)
