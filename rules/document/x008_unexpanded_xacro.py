"""The file still contains xacro: `xacro:` elements or `${...}`/`$(...)` in values.

## What it does
Reports, once per element, every element of the xacro language (the `xacro:`
prefix or the `http://www.ros.org/wiki/xacro` namespace) and every other
element whose attribute values or text contain `${...}` or `$(...)`, anywhere
in the file, `<gazebo>` blocks included. Comments are not read.

Severity depends on what the leftover does:
- **error** for everything that changes the model: includes, macro calls,
  `xacro:if`/`unless`, `insert_block`, `element`/`attribute`, and any
  `${...}`/`$(...)` in a value. Their content is missing or wrong as written.
- **warning** for inert declarations (`xacro:property`, `xacro:arg`,
  `xacro:macro` definitions) left in an otherwise expanded file: every URDF
  parser ignores them, so the model is what it says, but the file was not
  produced by a clean xacro run (typically hand-edited output).
- **one warning per file** when expressions appear only in names and
  references (`name`, `link`, `joint`, `reference`), as in a `.urdf` template
  such as `name="${namespace}base_link"` that a launch file runs through xacro:
  loaded as it is, the model is consistent but every frame is literally named
  `${namespace}base_link`. The finding sits on the first such element and
  counts the others.

## Why is this bad?
URDF parsers do not run xacro. urdfdom, Gazebo, MuJoCo, Drake, PyBullet and
Pinocchio ignore unknown elements silently, so an unexpanded
`<xacro:include>` or macro call simply drops the links, joints or sensors it
would have produced, and a link inside `<xacro:if>` disappears. A value such as
`xyz="${l/2} 0 0"` fails to parse: urdfdom ("Unable to parse component [${l/2}]
to a double") refuses the model when it is in a joint and otherwise drops the
inertial, visual or collision it is in (X004 explains what each loses), and
`filename="$(find pkg)/m.stl"` names no file. The model that loads is not the
one the author wrote.

## How to fix
Run xacro and check the result: `xacro robot.urdf.xacro > robot.urdf`
(ROS 2: `ros2 run xacro xacro ...`; or `pip install xacro`), or lint the
`.xacro` source through urdflint's xacro support. Delete leftover
`xacro:property`/`xacro:arg` lines from hand-edited generated files.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, local_tag
from urdflint.model.finding import Severity
from urdflint.model.schema import describe, is_xacro
from urdflint.model.values import has_xacro

INERT = frozenset({"property", "arg", "macro"})
NAME_ATTRS = frozenset({"name", "link", "joint", "reference"})
EXPAND = "the file must be expanded with xacro first"
# a value or a text with a $ (a superset: _expression decides), by the parent of either
EXPRESSIONS = etree.XPath(
    "descendant::*/@*[contains(., '$')]/.. | descendant::*/text()[contains(., '$')]/.."
)
COMMENT_RE = re.compile(rb"<!--.*?-->", re.S)
NAMESPACED = etree.XPath("descendant::*[namespace-uri() != '']")


@rule(
    "X008",
    "unexpanded-xacro",
    Severity.ERROR,
    fix="Expand the file with xacro (xacro robot.urdf.xacro > robot.urdf) and lint the output.",
)
def check(doc: Document) -> Iterator[Hit]:
    # what can be reported, found by libxml2 in one pass each: the elements that may hold
    # ${..} or $(..) in a value or a text, and the namespaced ones (xacro's among them)
    marked = set(_xpath(EXPRESSIONS, doc.robot)) if _expressions(doc.source) else set()
    spaced = b"xmlns" in doc.source or doc.undeclared_prefixes  # else no element has a URI
    wanted = _ancestors([*marked, *(_xpath(NAMESPACED, doc.robot) if spaced else [])])
    in_names: list[tuple[etree._Element, str]] = []
    stack = [doc.robot] if wanted else []
    while stack:
        node = stack.pop()
        for el in node:
            if not isinstance(el.tag, str):
                continue
            if el.tag[0] == "{" and is_xacro(el):
                yield _xacro_element(el)  # its subtree is reported with it
                continue
            if el in wanted:
                stack.append(el)  # only where something to report lies below
            where = _expression(el) if el in marked else None
            if where is None:
                continue
            if _only_in_names(el):
                in_names.append((el, where))
            else:
                yield Hit(el, f"{where} holds an unexpanded xacro expression; {EXPAND}")
    if in_names:
        first, where = min(in_names, key=lambda pair: pair[0].sourceline or 0)
        others = len(in_names) - 1
        more = f" (and {others} more name{'s' if others != 1 else ''})" if others else ""
        yield Hit(
            first,
            f"{where} holds an unexpanded xacro expression{more}; as URDF the frames are named "
            f"literally, so {EXPAND}",
            severity=Severity.WARNING,
        )


def _expressions(source: bytes) -> bool:
    """Whether the file may hold ``${..}`` or ``$(..)`` outside its comments."""
    if b"${" not in source and b"$(" not in source:
        return False
    if b"<![CDATA[" not in source:  # a CDATA section may hold a "<!--" that opens nothing
        source = COMMENT_RE.sub(b"", source)
    return b"${" in source or b"$(" in source


def _xpath(path: etree.XPath, robot: etree._Element) -> list[etree._Element]:
    return list(path(robot))  # type: ignore[arg-type]


def _ancestors(elements: list[etree._Element]) -> set[etree._Element]:
    """Every ancestor of ``elements``: where the walk must go to meet them in its order."""
    found: set[etree._Element] = set()
    for el in elements:
        node = el.getparent()
        while node is not None and node not in found:
            found.add(node)
            node = node.getparent()
    return found


def _only_in_names(el: etree._Element) -> bool:
    """True when every ``${..}``/``$(..)`` of ``el`` sits in a name or reference."""
    texts = [el.text, *(c.tail for c in el)]
    if any(t is not None and has_xacro(t) for t in texts):
        return False
    return all(etree.QName(a).localname in NAME_ATTRS for a, v in el.attrib.items() if has_xacro(v))


def _xacro_element(el: etree._Element) -> Hit:
    tag = local_tag(el)
    name = el.get("name")
    label = f"<{tag} name={name!r}>" if name is not None else f"<{tag}>"
    if etree.QName(el).localname in INERT:
        return Hit(
            el,
            f"leftover xacro declaration {label} is ignored by URDF parsers; "
            "the file should be expanded with xacro",
            severity=Severity.WARNING,
        )
    return Hit(el, f"unexpanded xacro element {label}; {EXPAND}")


def _expression(el: etree._Element) -> str | None:
    """Where ``el`` holds ``${..}``/``$(..)``, e.g. ``filename '$(find x)/m.stl' of ...``."""
    for attr, value in el.attrib.items():
        if has_xacro(value):
            target = f"<{local_tag(el)}>" if attr == "name" else describe(el)
            return f"{etree.QName(attr).localname}={value!r} of {target}"
    for text in [el.text] + [c.tail for c in el]:
        if text is not None and has_xacro(text):
            return f"the text {text.strip()!r} of {describe(el)}"
    return None
