"""Hover text and the outline: what the cursor is on, a link's inertia, the robot's mass.

Elements are found in the linted document by where they are written: their start tag in a
URDF, the xacro source map for a xacro file (also a macro file expanded by its entry).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from typing import Any

from lsprotocol import types as T

from urdflint.engine import registry
from urdflint.lsp import convert
from urdflint.lsp.extent import Text, nested
from urdflint.model import inertia
from urdflint.model.finding import Finding

START_TAG_RE = re.compile(r"""<([A-Za-z_][\w.:-]*)(?:"[^"]*"|'[^']*'|[^'">])*>""")


def tag_at(
    text: str, lines: list[str], pos: T.Position
) -> tuple[str, tuple[int, int], tuple[int, int]] | None:
    """The start tag under the cursor: its name, and the 1-based (line, column) where it
    starts and ends."""
    if pos.line >= len(lines):
        return None
    row = lines[pos.line]
    chars, count = 0, 0
    while chars < len(row) and count < pos.character:  # UTF-16 units -> code points
        count += 2 if ord(row[chars]) > 0xFFFF else 1
        chars += 1
    offset = sum(len(line) + 1 for line in lines[: pos.line]) + chars  # split on \n
    at = text.rfind("<", 0, offset + 1)
    match = START_TAG_RE.match(text, at) if at >= 0 else None
    if match is None or match.end() <= offset:
        return None
    return match.group(1), _line_column(text, at), _line_column(text, match.end() - 1)


def _line_column(text: str, offset: int) -> tuple[int, int]:
    return text.count("\n", 0, offset) + 1, offset - (text.rfind("\n", 0, offset) + 1) + 1


def element_at(doc: Any, path: str, line: int, column: int) -> Any:
    """The element of ``doc`` written at ``path:line:column``."""
    if doc is None or doc.root is None:
        return None
    for el in _named(doc):
        if doc.origin is None:
            if os.path.abspath(doc.path) == path and doc.start_of(el) == (line, column):
                return el
            continue
        origin = doc.origin(el, None)
        if (
            origin is not None
            and origin.exact
            and (origin.line, origin.column) == (line, column)
            and os.path.abspath(origin.path) == path
        ):
            return el
    return None


def _named(doc: Any) -> Iterator[Any]:
    yield doc.root
    for link in doc.links:
        yield link.element
    for joint in doc.joints:
        yield joint.element


def hover(doc: Any, findings: list[Finding], element: Any, tag: str) -> str | None:
    """Markdown: the rules of the findings on the tag, then the link's or robot's numbers."""
    parts = [_rule_text(f) for f in findings]
    if element is not None and tag == "link":
        parts.append(_link_text(doc, element, findings))
    elif element is not None and tag == "robot":
        parts.append(_robot_text(doc))
    elif element is not None and tag == "joint":
        parts.append(_joint_text(doc, element))
    text = "\n\n---\n\n".join(p for p in parts if p)
    return text or None


def _rule_text(finding: Finding) -> str:
    rule = registry.lookup(finding.code)
    head = f"**{finding.code} {finding.name}** ({finding.severity}): {finding.message}"
    if rule is None:
        return head
    body = [head, rule.summary]
    for heading in ("Why is this bad?", "How to fix"):
        section = rule.section(heading)
        if section:
            body.append(f"*{heading}* {section}")
    body.append(f"`urdflint explain {finding.code}`")
    return "\n\n".join(body)


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def _link_text(doc: Any, element: Any, findings: list[Finding]) -> str:
    name = element.get("name")
    found = inertia.read_inertial(element)
    if found is None:
        said = [f.code for f in findings if f.code in MASSLESS_RULES]
        if said:  # the rule's text above says what the targets do with it
            return f"**link `{name}`**: no `<inertial>` ({', '.join(said)} above)"
        return f"**link `{name}`**: no `<inertial>`; {_massless(doc, name)}"
    lines = [f"**link `{name}`**"]
    if found.mass is not None:
        lines.append(f"mass {_fmt(found.mass)} kg")
    if found.xyz is not None:
        lines.append("centre of mass " + " ".join(_fmt(v) for v in found.xyz) + " m (link frame)")
    if found.tensor is not None:
        ixx, iyy, izz, ixy, ixz, iyz = found.tensor
        lines.append(
            f"inertia ixx {_fmt(ixx)} iyy {_fmt(iyy)} izz {_fmt(izz)} "
            f"ixy {_fmt(ixy)} ixz {_fmt(ixz)} iyz {_fmt(iyz)} kg·m²"
        )
        moments = inertia.principal_moments(found.tensor)
        lines.append("principal moments " + " ".join(_fmt(m) for m in moments) + " kg·m²")
    return "  \n".join(lines)


MASSLESS_RULES = ("I001", "I013")  # the rules that judge a link without mass


def _massless(doc: Any, name: str | None) -> str:
    """What the selected targets do with a link that has no ``<inertial>`` and no I001 or
    I013 finding on it (ignored, or nothing lost): the verdict those rules work from."""
    from urdflint.model import bodies

    if doc is None or name is None or name not in doc.link_map:
        return "it has no mass"
    if name == "world" and name == doc.graph.root:
        return "the world frame (sdformat, MuJoCo and Drake weld the links fixed to it in place)"
    if name == doc.graph.root:
        b = bodies.bodies(doc)
        if bodies.selected(doc) & bodies.LUMPING and not b.mass(name):
            label = bodies.gazebo_label(doc.targets)
            return f"nothing welded to it has mass either, so {label} drops the whole model"
        return "a massless root link, as KDL wants it (the links fixed to it carry the mass)"
    verdict = bodies.massless_verdict(doc, name, declared=False)
    if verdict is None:
        return "nothing is lost in the selected targets (a frame merged into its parent)"
    return verdict.consequence


def _robot_text(doc: Any) -> str:
    lines = [
        f"**robot `{doc.root.get('name')}`**: {len(doc.links)} links, {len(doc.joints)} joints"
    ]
    physics = doc.physics
    if physics.built:
        lines.append(f"total mass {_fmt(physics.mass)} kg")
        if physics.com is not None:
            lines.append("centre of mass " + " ".join(_fmt(v) for v in physics.com) + " m")
            lines.append(f"(root link `{physics.root}` frame, zero pose; Pinocchio)")
    else:
        masses = [m for m in (_mass(link.element) for link in doc.links) if m is not None]
        lines.append(f"total mass {_fmt(sum(masses))} kg (sum of the links' masses)")
        lines.append(f"centre of mass: not computed ({physics.reason})")
    return "  \n".join(lines)


HOVER_COORDINATES = 64  # larger models: the hover gives the bound only, no search


def _joint_text(doc: Any, element: Any) -> str:
    """The joint's gravity load against its effort limit (Pinocchio installed only; the
    statics computed once per document, shared with the D rules)."""
    import importlib.util

    from urdflint.engine import statics
    from urdflint.model.values import fmt

    name = element.get("name")
    head = f"**joint `{name}`** ({element.get('type')})"
    if importlib.util.find_spec("pinocchio") is None or not doc.physics.built:
        return head
    found = statics.of(doc)
    if not found.ok or name not in found.joints:
        return head
    load = found.joints[name]
    unit = load.unit
    lines = [head, f"gravity load at most {load.bound:.3g} {unit} (bound)"]
    if len(found.joints) <= HOVER_COORDINATES:
        load = found.load(name)
        lines[1] = f"gravity load up to {load.needed:.3g} {unit} {statics.describe(found, load)}"
    if load.effort:
        margin = "" if load.margin is None else f", margin {load.margin:.3g}"
        proven = ", proven: its bound is within it" if load.proven else ""
        lines.append(f"effort limit {fmt(load.effort)} {unit}{margin}{proven}")
    if load.passive:
        lines.append("passive: no <transmission> or <ros2_control> command drives it")
    return "  \n".join(lines)


def _mass(element: Any) -> float | None:
    found = inertia.read_inertial(element)
    return found.mass if found is not None else None


def symbols(doc: Any, path: str, lines: list[str]) -> list[T.DocumentSymbol]:
    """The outline: for the robot's own file its kinematic tree (link > joint > link), for
    a file xacro includes the links and joints written in it, under the macros that write
    them."""
    if doc is None or doc.root is None:
        return []
    here = [(el, _where(doc, el, path)) for el in _named(doc)]
    placed = {id(el): at for el, at in here if at is not None}
    source = Text(lines)
    if doc.root is not None and id(doc.root) in placed and doc.origin is None:
        return [_tree(doc, placed, lines, source)]
    written: dict[tuple[int, int], T.DocumentSymbol] = {}
    for el, at in here:  # a macro called twice writes its elements twice: shown once (first)
        if at is not None and el is not doc.root and at not in written:
            written[at] = _symbol(el, at, lines, [], source=source)
    return nested(source, list(written.values()))


def _where(doc: Any, el: Any, path: str) -> tuple[int, int] | None:
    if doc.origin is None:
        return doc.start_of(el) if os.path.abspath(doc.path) == path else None
    origin = doc.origin(el, None)
    if origin is None or not origin.exact or os.path.abspath(origin.path) != path:
        return None
    return origin.line, origin.column


KINDS = {"robot": T.SymbolKind.Module, "link": T.SymbolKind.Class, "joint": T.SymbolKind.Field}


def _symbol(
    el: Any,
    at: tuple[int, int],
    lines: list[str],
    children: list[T.DocumentSymbol],
    detail: str | None = None,
    source: Text | None = None,
) -> T.DocumentSymbol:
    start = convert.position(lines, *at)
    row = lines[start.line] if start.line < len(lines) else ""
    head = T.Range(start, T.Position(start.line, convert.units(row.rstrip())))
    end = source.end(start.line, at[1] - 1) if source is not None else None
    whole = T.Range(start, end) if end is not None else head  # the element, end tag included
    detail = detail or (el.get("type") if el.tag == "joint" else None)
    name = el.get("name") or f"(unnamed {el.tag})"
    return T.DocumentSymbol(
        name, KINDS.get(str(el.tag), T.SymbolKind.Object), whole, head, detail, children=children
    )


def _tree(
    doc: Any, placed: dict[int, tuple[int, int]], lines: list[str], source: Text
) -> T.DocumentSymbol:
    """robot > link > the joints that hang children on it (flat: a 1,000-link chain is 1,000
    siblings, not 1,000 levels)."""
    by_parent: dict[str, list[Any]] = {}
    for joint in doc.joints:
        if id(joint.element) in placed:
            by_parent.setdefault(str(joint.parent), []).append(joint)
    links = []
    for name, link in doc.link_map.items():
        if id(link.element) not in placed:
            continue
        kids = [
            _symbol(j.element, placed[id(j.element)], lines, [], f"{j.type} -> {j.child}", source)
            for j in by_parent.get(name, [])
        ]
        links.append(_symbol(link.element, placed[id(link.element)], lines, kids, source=source))
    return _symbol(doc.root, placed[id(doc.root)], lines, links, source=source)
