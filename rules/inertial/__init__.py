"""I: inertial properties (missing or impossible masses and tensors, placeholders, unit slips)."""

from urdflint.rules.inertial import (  # noqa: F401
    i001_missing_inertial,
    i002_non_positive_mass,
    i003_non_positive_moment,
    i004_inertia_not_positive_definite,
    i005_triangle_inequality,
    i006_placeholder_inertia,
    i007_inertia_geometry_mismatch,
    i008_com_outside_geometry,
    i009_extreme_mass_ratio,
    i010_tiny_inertial,
    i011_root_link_inertia,
    i012_incomplete_inertial,
    i013_massless_model,
)
