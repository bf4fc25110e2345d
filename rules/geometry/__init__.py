"""C: collision, visual and geometry (shapes, dimensions, collision models, meshes)."""

from urdflint.rules.geometry import (  # noqa: F401
    c001_missing_collision,
    c002_collision_same_as_visual_mesh,
    c003_invalid_geometry,
    c004_mesh_not_found,
    c005_mesh_unreadable,
    c006_mesh_scale_suspicious,
    c007_collision_mesh_too_complex,
    c008_visual_stl_no_color,
    c009_unsupported_mesh_format,
    c010_invalid_color,
    c011_duplicate_geometry_name,
    c012_texture_not_found,
    c013_self_collision,
    c014_non_portable_mesh_path,
    c015_package_not_a_dependency,
    c016_path_case_mismatch,
    c017_duplicate_package,
    c018_mesh_without_volume,
)
