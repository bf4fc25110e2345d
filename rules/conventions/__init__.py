"""N: naming conventions of REP 103/105/120/199, run only with a `profile`."""

from urdflint.rules.conventions import (  # noqa: F401
    n001_missing_base_link,
    n002_reserved_frame_link,
    n003_base_footprint_frame,
    n004_optical_frame_orientation,
    n005_missing_industrial_frame,
    n006_industrial_frame_attachment,
    n007_tool0_orientation,
    n008_humanoid_frame_name,
)
