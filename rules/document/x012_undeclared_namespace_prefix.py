"""A namespace prefix is used without its `xmlns:` declaration.

## What it does
Reports, once per prefix, an element or attribute name with a prefix that no
`xmlns:prefix="..."` declares, such as `<drake:joint>` in a file without
`xmlns:drake`. The finding sits on the first use and counts the others. The rest
of the file is checked as usual: urdflint reads the prefixed names as extension
elements and attributes of their own namespace, as if it were declared.

## Why is this bad?
Strictly, such a file is not namespace-well-formed XML, and namespace-aware parsers
refuse it: lxml ("Namespace prefix drake on joint is not defined"), and with it
urdf_parser_py, and xacro ("unbound prefix"). yourdfpy falls back to its recover
mode. The TinyXML-based consumers do not care: they compare names as written, so
urdfdom (`check_urdf` 3.0.1 parses such a file), Pinocchio, sdformat (Gazebo),
PyBullet, MuJoCo and Drake load it, and Drake reads `<drake:joint>` and the other
`drake:` extensions by their literal name. So the file works where it was tested
and breaks in the first Python or xacro tool, which is why this is a warning.

## How to fix
Declare the prefix on `<robot>`: `xmlns:drake="http://drake.mit.edu"` for Drake's
extensions, `xmlns:xacro="http://www.ros.org/wiki/xacro"` for xacro.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, local_tag
from urdflint.model.finding import Severity
from urdflint.model.parsing import undeclared_uri

KNOWN = {"drake": "http://drake.mit.edu", "xacro": "http://www.ros.org/wiki/xacro"}


@rule("X012", "undeclared-namespace-prefix", Severity.WARNING)
def check(doc: Document) -> Iterator[Hit]:
    for prefix in doc.undeclared_prefixes:
        marker = "{" + undeclared_uri(prefix) + "}"
        uses = list(_uses(doc.robot, marker, prefix))
        if not uses:
            continue
        el, attribute = uses[0]
        name = attribute or f"<{local_tag(el)}>"
        others = len(uses) - 1
        more = f" (and {others} more use{'s' if others != 1 else ''})" if others else ""
        uri = KNOWN.get(prefix, "...")
        yield Hit(
            el,
            f"the namespace prefix {prefix!r} of {name} is not declared{more}; TinyXML-based "
            "parsers (urdfdom, PyBullet, MuJoCo, Drake) read the file, namespace-aware ones "
            "(lxml, urdf_parser_py, xacro) refuse it",
            fix=f'Declare it on <robot>: xmlns:{prefix}="{uri}".',
            attribute=attribute,
        )


def _uses(
    robot: etree._Element, marker: str, prefix: str
) -> Iterator[tuple[etree._Element, str | None]]:
    """Each element and attribute named with the undeclared prefix, in document order."""
    for el in robot.iter(etree.Element):
        if el.tag.startswith(marker):
            yield el, None
        for attr in el.attrib:
            if attr.startswith(marker):
                yield el, f"{prefix}:{attr[len(marker) :]}"
