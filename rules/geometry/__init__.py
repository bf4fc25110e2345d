"""C: collision, visual and geometry (shapes, dimensions, collision models)."""

from urdflint.rules.geometry import (  # noqa: F401
    c001_missing_collision,
    c002_collision_same_as_visual_mesh,
    c003_invalid_geometry,
    c010_invalid_color,
)
