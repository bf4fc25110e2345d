"""X: the document itself (XML, root element, numbers, unknown elements)."""

from urdflint.rules.document import (  # noqa: F401
    x001_invalid_xml,
    x002_not_a_robot,
)
