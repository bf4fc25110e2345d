"""X: the document itself (XML, root, namespaces, numbers, unknown elements and attributes)."""

from urdflint.rules.document import (  # noqa: F401
    x001_invalid_xml,
    x002_not_a_robot,
    x003_missing_name,
    x004_invalid_number,
    x005_wrong_arity,
    x006_obsolete_gazebo_namespace,
    x007_unknown_element,
    x008_unexpanded_xacro,
    x009_unsupported_urdf_version,
    x010_xacro_expansion_failed,
    x011_xacro_library,
    x012_undeclared_namespace_prefix,
    x013_unknown_attribute,
    x014_unsafe_name,
    x015_repeated_element,
)
