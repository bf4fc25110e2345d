"""The kinematic tree of a robot as a self-contained SVG, with its findings highlighted.

:func:`render_tree` draws links as boxes and joints as labelled edges (name and type),
laid out as a layered tree: each root at the top with its subtree below, several
roots side by side, every subtree as wide as its widest level needs. A link with a
second parent joint (a loop) keeps its first parent joint as its tree edge; the
others are drawn as dashed extra edges. A joint naming an undefined link points at
a dashed box. Links and joints with findings (matched through ``Finding.element``;
a ``<gazebo reference>`` block counts for the link or joint it names) are coloured
by their worst severity and carry a ``<title>`` tooltip listing the findings.

Every name comes from an untrusted file: all text is escaped, the output uses only
presentation attributes (no ``<style>``, scripts, links or external resources) and
is deterministic for a given document and findings. Pure Python.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdflint.model.finding import Finding, Severity

if TYPE_CHECKING:
    from urdflint.model.document import Document

FONT = "system-ui, -apple-system, Segoe UI, Roboto, Helvetica, Arial, sans-serif"
CHAR_W = 6.6  # estimated advance of an 11 px sans-serif character
BOX_H, PITCH, GAP, MARGIN = 28, 92, 14, 20
MAX_LABEL = 30  # characters shown in a box or on an edge; the tooltip has the full name
MAX_NODES = 2000  # past this a drawing is neither readable nor small
MAX_TIPS = 8  # findings listed in one tooltip
INK, MUTED, LINE, FRAME, ROOT_FILL = "#1d2939", "#667085", "#98a2b3", "#475467", "#f2f4f7"
COLOURS = {  # severity -> (stroke, fill, text)
    Severity.ERROR: ("#d92d20", "#fef3f2", "#b42318"),
    Severity.WARNING: ("#dc6803", "#fffaeb", "#b54708"),
    Severity.INFO: ("#1570ef", "#eff8ff", "#175cd3"),
}
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def esc(text: object) -> str:
    """Text safe inside an element or a quoted attribute (characters XML forbids replaced)."""
    value = _NOT_XML.sub("\ufffd", str(text))
    for raw, entity in (("&", "&amp;"), ("<", "&lt;"), (">", "&gt;"), ('"', "&quot;")):
        value = value.replace(raw, entity)
    return value.replace("'", "&#39;")


def _short(text: str) -> str:
    return text if len(text) <= MAX_LABEL else text[: MAX_LABEL - 1] + "…"


def _w(text: str, size: float = 11) -> float:
    return len(_short(text)) * CHAR_W * size / 11


def _n(value: float) -> str:
    return f"{value:.1f}".rstrip("0").rstrip(".")


@dataclass(eq=False)
class Node:
    key: str
    label: str
    kind: str  # "link", "missing" (named by a joint, never defined) or "unnamed"
    findings: list[Finding] = field(default_factory=list)
    parent_edge: Edge | None = None
    children: list[Node] = field(default_factory=list)
    x: float = 0.0
    depth: int = 0

    @property
    def width(self) -> float:
        return max(60.0, _w(self.label) + 24)


@dataclass(eq=False)
class Edge:
    name: str
    type: str
    parent: Node
    child: Node
    findings: list[Finding] = field(default_factory=list)

    @property
    def width(self) -> float:
        return max(_w(self.name), _w(self.type, 10)) + 16


def render_tree(doc: Document, findings: Iterable[Finding] = ()) -> str:
    """The document's kinematic tree as an SVG string (a one-line note when there is none)."""
    if not doc.ok:
        return _note("No kinematic tree: the file is not a usable <robot>.")
    if len(doc.links) > MAX_NODES or len(doc.joints) > MAX_NODES:
        size = max(len(doc.links), len(doc.joints))
        return _note(f"The robot has {size} links or joints; trees are drawn up to {MAX_NODES}.")
    nodes, edges = _graph(doc, list(findings))
    if not nodes:
        return _note("No kinematic tree: the robot has no links.")
    roots = _forest(nodes, edges)
    width, height = _layout(roots)
    return _draw(doc.robot.get("name") or "", nodes, edges, width, height)


# -- the graph ---------------------------------------------------------------------------


def _graph(doc: Document, findings: list[Finding]) -> tuple[list[Node], list[Edge]]:
    """Nodes (links in document order, then undefined names) and one edge per joint."""
    nodes: dict[str, Node] = {}
    owners: dict[str, list[Node | Edge]] = {}  # element path -> what its findings highlight
    for index, link in enumerate(doc.links):
        if link.name is None:
            node = Node(f"\0#{index}", "(unnamed link)", "unnamed")  # \0: never in a name
            nodes[node.key] = node
        else:
            node = nodes.setdefault(link.name, Node(link.name, link.name, "link"))
        owners.setdefault(doc.element_path(link.element), []).append(node)

    def end(name: str | None, role: str, index: int) -> Node:
        key = name if name is not None else f"\0{role}{index}"
        if key not in nodes:
            nodes[key] = Node(key, name if name is not None else f"(no {role})", "missing")
        return nodes[key]

    edges: list[Edge] = []
    for index, joint in enumerate(doc.joints):
        edge = Edge(
            joint.name if joint.name is not None else "(unnamed joint)",
            joint.type if joint.type is not None else "(no type)",
            end(joint.parent, "parent", index),
            end(joint.child, "child", index),
        )
        edges.append(edge)
        owners.setdefault(doc.element_path(joint.element), []).append(edge)
    for block in doc.gazebo:
        ref = block.get("reference")
        if ref in nodes and nodes[ref].kind == "link":
            named: list[Node | Edge] = [nodes[ref]]
        else:
            named = [e for e in edges if e.name == ref]
        if ref is not None and named:
            owners.setdefault(doc.element_path(block), []).extend(named)
    for finding in findings:
        for owner in dict.fromkeys(_owners(finding.element, owners)):  # a name defined twice
            owner.findings.append(finding)
    return list(nodes.values()), edges


def _owners(element: str, owners: dict[str, list[Node | Edge]]) -> list[Node | Edge]:
    """What the longest registered prefix of ``element`` (whole path steps) names."""
    best: list[Node | Edge] = []
    cuts = [i for i, ch in enumerate(element) if ch == "/" and i > 0] + [len(element)]
    for cut in cuts:
        best = owners.get(element[:cut], best)
    return best


def _forest(nodes: list[Node], edges: list[Edge]) -> list[Node]:
    """Pick each node's tree edge (its first parent joint, loops cut); return the roots."""
    for edge in edges:
        if edge.child.parent_edge is None and edge.parent is not edge.child:
            edge.child.parent_edge = edge
    order = {node.key: i for i, node in enumerate(nodes)}
    state: dict[str, int] = {}  # 1: on the current walk up, 2: done
    for node in nodes:
        walk: list[Node] = []
        current: Node | None = node
        while current is not None and current.key not in state:
            state[current.key] = 1
            walk.append(current)
            current = current.parent_edge.parent if current.parent_edge else None
        if current is not None and state[current.key] == 1:  # the walk closed a cycle
            cycle = walk[walk.index(current) :]
            min(cycle, key=lambda n: order[n.key]).parent_edge = None
        for seen in walk:
            state[seen.key] = 2
    for edge in edges:
        if edge.child.parent_edge is edge:
            edge.parent.children.append(edge.child)
    return [node for node in nodes if node.parent_edge is None]


# -- the layout --------------------------------------------------------------------------


def _preorder(roots: list[Node]) -> list[Node]:
    out: list[Node] = []
    stack = list(reversed(roots))
    while stack:
        node = stack.pop()
        out.append(node)
        for child in reversed(node.children):
            child.depth = node.depth + 1
            stack.append(child)
    return out


def _layout(roots: list[Node]) -> tuple[float, float]:
    """A tidy tree: each subtree's contour (its left and right extent per level) is packed
    against its left sibling's, parents centred over their first and last child; the roots'
    trees side by side. Returns the drawing's size."""
    order = _preorder(roots)
    contours: dict[Node, list[tuple[float, float]]] = {}
    offsets: dict[Node, float] = {}  # a child's x relative to its parent's
    for node in reversed(order):
        half = max(node.width, node.parent_edge.width if node.parent_edge else 0.0) / 2
        if not node.children:
            contours[node] = [(-half, half)]
            continue
        first = node.children[0]
        if len(node.children) == 1:  # a chain: reuse the child's contour (linear, not quadratic)
            offsets[first] = 0.0
            contour = contours.pop(first)
            contour.insert(0, (-half, half))
            contours[node] = contour
            continue
        packed, shifts = list(contours.pop(first)), [0.0]
        for child in node.children[1:]:
            theirs = contours.pop(child)
            common = min(len(packed), len(theirs))
            shift = max(packed[k][1] - theirs[k][0] for k in range(common)) + GAP
            shifts.append(shift)
            for k in range(common):
                packed[k] = (packed[k][0], theirs[k][1] + shift)
            packed.extend((lo + shift, hi + shift) for lo, hi in theirs[common:])
        middle = (shifts[0] + shifts[-1]) / 2
        for child, shift in zip(node.children, shifts, strict=True):
            offsets[child] = shift - middle
        contours[node] = [(-half, half)] + [(lo - middle, hi - middle) for lo, hi in packed]
    x = float(MARGIN)
    for root in roots:
        contour = contours[root]
        root.x = x - min(lo for lo, _ in contour)
        x = root.x + max(hi for _, hi in contour) + 3 * GAP
    for node in order:
        for child in node.children:
            child.x = node.x + offsets[child]
    depth = max(node.depth for node in order)
    return x - 3 * GAP + MARGIN + 8, 2 * MARGIN + depth * PITCH + BOX_H  # 8: badge overhang


def _top(node: Node) -> float:
    return MARGIN + node.depth * PITCH


# -- drawing -----------------------------------------------------------------------------


def _worst(findings: list[Finding]) -> Severity | None:
    return max((f.severity for f in findings), default=None)


def _marks(findings: list[Finding]) -> str:
    """``data-`` attributes naming the worst severity and the codes."""
    worst = _worst(findings)
    if worst is None:
        return ""
    codes = " ".join(sorted({f.code for f in findings}))
    return f' data-severity="{worst}" data-codes="{esc(codes)}"'


def _tip(what: str, findings: list[Finding]) -> str:
    ordered = sorted(findings, key=lambda f: (-f.severity, f.line, f.code))
    lines = [what] + [f"{f.code} {f.severity}: {f.message}" for f in ordered[:MAX_TIPS]]
    if len(ordered) > MAX_TIPS:
        lines.append(f"… and {len(ordered) - MAX_TIPS} more")
    return f"<title>{esc(chr(10).join(lines))}</title>"


def _link(node: Node) -> str:
    worst = _worst(node.findings)
    stroke, fill, ink = COLOURS[worst] if worst else (FRAME, "#ffffff", INK)
    if node.parent_edge is None and not worst:
        fill = ROOT_FILL
    w, y = node.width, _top(node)
    x = node.x - w / 2
    dash = ' stroke-dasharray="4 3"' if node.kind != "link" else ""
    style = ' font-style="italic"' if node.kind != "link" else ""
    what = {
        "link": f"link {node.label!r}",
        "missing": f"link {node.label!r} is not defined",
        "unnamed": "a <link> without a name",
    }[node.kind]
    root = ' data-root="true"' if node.parent_edge is None else ""
    parts = [
        f'<g class="link" data-link="{esc(node.label)}" data-kind="{node.kind}"'
        f"{root}{_marks(node.findings)}>",
        _tip(what, node.findings),
        f'<rect x="{_n(x)}" y="{_n(y)}" width="{_n(w)}" height="{BOX_H}" rx="5" fill="{fill}" '
        f'stroke="{stroke}" stroke-width="{2 if worst else 1.2}"{dash}/>',
        f'<text x="{_n(node.x)}" y="{_n(y + 18)}" text-anchor="middle" fill="{ink}"{style}>'
        f"{esc(_short(node.label))}</text>",
    ]
    if worst:
        count = str(len(node.findings)) if len(node.findings) < 100 else "99+"
        cx, r = x + w, 8 if len(count) < 3 else 10
        parts.append(
            f'<circle cx="{_n(cx)}" cy="{_n(y)}" r="{r}" fill="{stroke}" stroke="#ffffff"/>'
            f'<text x="{_n(cx)}" y="{_n(y + 3.5)}" text-anchor="middle" font-size="9" '
            f'font-weight="700" fill="#ffffff">{count}</text>'
        )
    return "".join(parts) + "</g>"


def _route(edge: Edge) -> tuple[str, float, float]:
    """The edge's path and the centre-top of its label: a tree edge drops from its parent's
    bus into the child; extra edges bulge out right of both boxes; a self-joint loops."""
    parent, child = edge.parent, edge.child
    if child.parent_edge is edge:  # its own part: the drop from the parent's bus
        y0, y1 = _top(parent) + BOX_H + 12, _top(child)
        return f"M{_n(child.x)} {_n(y0)}V{_n(y1)}", child.x, y1 - 38
    x0, y0 = parent.x + parent.width / 2, _top(parent) + BOX_H / 2
    x1, y1 = child.x + child.width / 2, _top(child) + BOX_H / 2
    if parent is child:
        y0, y1 = y0 - 6, y0 + 6
    bend = max(x0, x1) + 56
    path = f"M{_n(x0)} {_n(y0)}C{_n(bend)} {_n(y0)} {_n(bend)} {_n(y1)} {_n(x1)} {_n(y1)}"
    return path, (x0 + x1 + 6 * bend) / 8 + edge.width / 2 - 8, (y0 + y1) / 2 - 15


def _joint(edge: Edge) -> str:
    worst = _worst(edge.findings)
    stroke, fill, ink = COLOURS[worst] if worst else (LINE, "#ffffff", INK)
    parent, child = edge.parent, edge.child
    tree = child.parent_edge is edge
    path, lx, ly = _route(edge)
    w = edge.width
    dash = "" if tree else ' stroke-dasharray="6 4"'
    extra = "" if tree else ' data-extra="true"'
    what = f"{edge.type} joint {edge.name!r}: {edge.parent.label!r} → {edge.child.label!r}"
    if not tree:
        what += " (not part of the tree: a second parent or a loop)"
    return (
        f'<g class="joint" data-joint="{esc(edge.name)}" data-type="{esc(edge.type)}" '
        f'data-parent="{esc(parent.label)}" data-child="{esc(child.label)}"'
        f"{extra}{_marks(edge.findings)}>"
        f"{_tip(what, edge.findings)}"
        f'<path d="{path}" fill="none" stroke="{stroke}" stroke-width="{2 if worst else 1.2}"'
        f"{dash}/>"
        f'<rect x="{_n(lx - w / 2)}" y="{_n(ly)}" width="{_n(w)}" height="30" rx="6" '
        f'fill="{fill}" stroke="{stroke}" stroke-width="{1.5 if worst else 1}"/>'
        f'<text x="{_n(lx)}" y="{_n(ly + 13)}" text-anchor="middle" fill="{ink}" '
        f'font-weight="600">{esc(_short(edge.name))}</text>'
        f'<text x="{_n(lx)}" y="{_n(ly + 25)}" text-anchor="middle" font-size="10" '
        f'fill="{MUTED}">{esc(_short(edge.type))}</text></g>'
    )


def _open(width: float, height: float, label: str) -> str:
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {_n(width)} {_n(height)}" '
        f'width="{_n(width)}" height="{_n(height)}" font-family="{FONT}" font-size="11" '
        f'role="img" aria-label="{esc(label)}"><title>{esc(label)}</title>'
        f'<rect width="{_n(width)}" height="{_n(height)}" fill="#ffffff"/>'
    )


def _draw(name: str, nodes: list[Node], edges: list[Edge], width: float, height: float) -> str:
    links = sum(1 for n in nodes if n.kind != "missing")
    label = f"Kinematic tree of robot {name!r}: {links} links, {len(edges)} joints"
    by_severity = sorted(edges, key=lambda e: _worst(e.findings) or 0)  # coloured on top
    for edge in edges:  # extra edges and their labels may reach past the tree
        if edge.child.parent_edge is not edge:
            width = max(width, _route(edge)[1] + edge.width / 2 + MARGIN)
    return "".join(
        [
            _open(width, height, label),
            f'<path class="buses" d="{"".join(_bus(n) for n in nodes)}" fill="none" '
            f'stroke="{LINE}" stroke-width="1.2"/>',
            '<g class="links">',
            *(_link(n) for n in nodes),
            '</g><g class="joints">',
            *(_joint(e) for e in by_severity),
            "</g></svg>",
        ]
    )


def _bus(node: Node) -> str:
    """The shared, neutral part of a parent's tree edges: down from its box, then across."""
    if not node.children:
        return ""
    y = _top(node) + BOX_H
    xs = [node.x] + [child.x for child in node.children]
    return f"M{_n(node.x)} {_n(y)}V{_n(y + 12)}M{_n(min(xs))} {_n(y + 12)}H{_n(max(xs))}"


def _note(message: str) -> str:
    width = _w(message) * 1.2 + 2 * MARGIN
    return (
        _open(width, 60, message)
        + f'<text x="{MARGIN}" y="34" fill="{MUTED}">{esc(message)}</text></svg>'
    )
