"""The kinematic-tree SVG: well-formed, complete, highlighted, escaped, deterministic, fast."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import CORPUS, FIXTURES, corpus_models, needs_corpus
from urdflint.engine import linter
from urdflint.engine.config import Settings
from urdflint.model.document import Document
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.svg import MAX_NODES, esc, render_tree

SVG = "{http://www.w3.org/2000/svg}"
BROKEN = FIXTURES / "models" / "broken_arm.urdf"
MOMENTS = 'ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"'
INERTIAL = f'<inertial><mass value="1"/><inertia {MOMENTS}/></inertial>'


def parse(svg: str) -> etree._Element:
    root = etree.fromstring(svg.encode())
    assert root.tag == f"{SVG}svg"
    assert root.get("viewBox", "").startswith("0 0 ")
    return root


def groups(root: etree._Element, kind: str) -> dict[str, etree._Element]:
    return {g.get(f"data-{kind}"): g for g in root.iter(f"{SVG}g") if g.get("class") == kind}


def robot(body: str, name: str = "r") -> Document:
    return Document("t.urdf", f'<robot name="{name}">{body}</robot>'.encode())


def link(name: str) -> str:
    return f'<link name="{name}">{INERTIAL}</link>'


def joint(name: str, parent: str, child: str, kind: str = "fixed") -> str:
    ends = f'<parent link="{parent}"/><child link="{child}"/>'
    return f'<joint name="{name}" type="{kind}">{ends}</joint>'


def finding(element: str, code: str = "T001", severity: Severity = Severity.ERROR) -> Finding:
    return Finding("t.urdf", 1, 1, code, "test", severity, "a message", element)


def test_broken_arm_draws_every_link_and_joint_with_its_findings() -> None:
    result = linter.lint_path(BROKEN, str(BROKEN), Settings())
    doc = result.document
    assert doc is not None
    root = parse(render_tree(doc, result.findings))
    links, joints = groups(root, "link"), groups(root, "joint")
    assert set(links) == {lk.name for lk in doc.links} | {"hand"}  # 'hand' is not defined
    assert set(joints) == {j.name for j in doc.joints}
    assert links["hand"].get("data-kind") == "missing"
    assert links["base_footprint"].get("data-root") == "true"
    assert "data-severity" not in links["base_footprint"].attrib
    # I002/I005 on <inertial>, G003/G006 from <gazebo reference="upper_arm">
    assert links["upper_arm"].get("data-severity") == "error"
    assert links["upper_arm"].get("data-codes") == "G003 G006 I002 I005"
    assert links["base_link"].get("data-severity") == "warning"  # X007 beats info C001
    assert links["base_link"].get("data-codes") == "C001 X007"
    assert joints["shoulder"].get("data-codes") == "J001 J007"
    assert joints["wrist"].get("data-codes") == "S003 S006"
    assert joints["base_joint"].get("data-severity") is None
    brace = joints["forearm_brace"]  # forearm's second parent: an extra, dashed edge
    assert brace.get("data-extra") == "true" and brace.get("data-codes") == "S005"
    assert joints["elbow"].get("data-extra") is None
    tip = links["upper_arm"].find(f"{SVG}title").text
    assert tip.startswith("link 'upper_arm'\nI002 error: link 'upper_arm' has mass -1 kg")
    texts = {t.text for t in root.iter(f"{SVG}text")}
    assert {"upper_arm", "shoulder", "revolute", "revolut", "hand"} <= texts


def test_highlight_colours_follow_the_worst_severity() -> None:
    doc = robot(link("a") + link("b") + link("c") + joint("j", "a", "b") + joint("k", "a", "c"))
    found = [
        finding("/robot/link[@name='b']/inertial/mass", "I002", Severity.INFO),
        finding("/robot/link[@name='b']", "I003", Severity.WARNING),
        finding("/robot/joint[@name='k']/limit", "J009", Severity.ERROR),
        finding("/robot", "P001"),  # robot-level: no node
    ]
    root = parse(render_tree(doc, found))
    links, joints = groups(root, "link"), groups(root, "joint")
    assert links["b"].get("data-severity") == "warning"
    assert links["b"].find(f"{SVG}rect").get("stroke") == "#dc6803"
    assert joints["k"].get("data-severity") == "error"
    assert joints["k"].find(f"{SVG}path").get("stroke") == "#d92d20"
    assert links["a"].get("data-severity") is None and joints["j"].get("data-severity") is None


def test_prefix_matching_respects_path_steps() -> None:
    doc = robot(link("a") + link("ab") + joint("j", "a", "ab"))
    root = parse(render_tree(doc, [finding("/robot/link[@name='ab']/visual")]))
    links = groups(root, "link")
    assert links["ab"].get("data-codes") == "T001"
    assert links["a"].get("data-codes") is None


def test_gazebo_blocks_highlight_the_link_or_joint_they_name() -> None:
    doc = robot(
        link("a")
        + link("b")
        + joint("j", "a", "b", "continuous")
        + '<gazebo reference="b"><mu1>1</mu1></gazebo>'
        + '<gazebo reference="j"><implicitSpringDamper>1</implicitSpringDamper></gazebo>'
    )
    found = [
        finding("/robot/gazebo[@reference='b']/mu1", "G006", Severity.WARNING),
        finding("/robot/gazebo[@reference='j']", "G004", Severity.INFO),
    ]
    root = parse(render_tree(doc, found))
    assert groups(root, "link")["b"].get("data-codes") == "G006"
    assert groups(root, "joint")["j"].get("data-codes") == "G004"


HOSTILE = [
    "<script>alert(1)</script>",
    "a\"b'c",
    "x']/../link[@name='y",
    "]]><svg onload=alert(1)>",
    "&amp;<&>",
    "ünïcødé ✓ 🤖",
]


@pytest.mark.parametrize("name", HOSTILE)
def test_hostile_names_are_escaped(name: str) -> None:
    quoted = (
        name.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
    )
    doc = robot(
        link("base") + link(quoted) + joint(quoted, "base", quoted, "revolute"),
        name=quoted,
    )
    assert doc.ok and doc.links[1].name == name
    element = doc.element_path(doc.links[1].element)
    svg = render_tree(doc, [finding(element, "X007", Severity.WARNING)])
    root = parse(svg)
    tags = {etree.QName(el).localname for el in root.iter() if isinstance(el.tag, str)}
    assert tags <= {"svg", "title", "rect", "g", "text", "path", "circle"}
    assert not any(k.startswith("on") for el in root.iter() for k in el.attrib)
    assert "<script" not in svg and "<svg onload" not in svg
    assert groups(root, "link")[name].get("data-codes") == "X007"
    assert groups(root, "joint")[name].get("data-child") == name
    assert name[:20] in "".join(root.itertext())
    assert root.get("aria-label") == f"Kinematic tree of robot {name!r}: 2 links, 1 joints"


def test_escape_replaces_characters_xml_forbids() -> None:
    assert esc("a\x00b\x1f<'\"&") == "a\ufffdb\ufffd&lt;&#39;&quot;&amp;"
    value = esc("\x01\"'")
    parse(f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1 1" a="{value}" b=\'{value}\'/>')


def test_several_roots_side_by_side_and_layers_top_down() -> None:
    doc = robot(link("a") + link("b") + link("c") + link("d") + joint("j", "a", "b"))
    root = parse(render_tree(doc))
    rects = {n: g.find(f"{SVG}rect") for n, g in groups(root, "link").items()}
    x = {n: float(r.get("x")) for n, r in rects.items()}
    y = {n: float(r.get("y")) for n, r in rects.items()}
    assert [n for n, g in groups(root, "link").items() if g.get("data-root")] == ["a", "c", "d"]
    assert y["a"] == y["c"] == y["d"] < y["b"]
    assert x["a"] < x["c"] < x["d"]


def test_a_loop_without_a_root_is_still_drawn() -> None:
    doc = robot(
        link("a") + link("b") + joint("j", "a", "b") + joint("k", "b", "a") + joint("s", "b", "b")
    )
    root = parse(render_tree(doc))
    links, joints = groups(root, "link"), groups(root, "joint")
    assert set(links) == {"a", "b"} and links["a"].get("data-root") == "true"
    assert joints["j"].get("data-extra") is None
    assert joints["k"].get("data-extra") == joints["s"].get("data-extra") == "true"


def test_unnamed_and_dangling_elements() -> None:
    doc = robot(link("a") + "<link/>" + '<joint name="j" type="fixed"><parent link="a"/></joint>')
    root = parse(render_tree(doc))
    kinds = [g.get("data-kind") for g in root.iter(f"{SVG}g") if g.get("class") == "link"]
    assert kinds == ["link", "unnamed", "missing"]
    assert groups(root, "joint")["j"].get("data-child") == "(no child)"


def test_not_a_robot_and_empty_robot_give_a_note() -> None:
    for doc in (Document("t.urdf", b"<robot"), Document("t.urdf", b"<robot name='r'/>")):
        root = parse(render_tree(doc))
        assert "No kinematic tree" in "".join(root.itertext())


def test_huge_trees_are_refused_and_long_chains_do_not_recurse() -> None:
    many = "".join(link(f"l{i}") for i in range(MAX_NODES + 1))
    assert "trees are drawn up to" in render_tree(robot(many))
    unnamed = robot("<link/>" * 50_000)  # refused before any per-link work (bench/ times it)
    assert "trees are drawn up to" in render_tree(unnamed)
    chain = link("l0") + "".join(
        link(f"l{i}") + joint(f"j{i}", f"l{i - 1}", f"l{i}") for i in range(1, 1500)
    )
    root = parse(render_tree(robot(chain)))
    assert len(groups(root, "link")) == 1500


def test_a_name_defined_twice_counts_its_findings_once() -> None:
    doc = robot(link("a") + link("a") + link("b") + joint("j", "a", "b"))
    root = parse(render_tree(doc, [finding("/robot/link[@name='a']", "S001")]))
    group = groups(root, "link")["a"]
    assert group.get("data-codes") == "S001"
    assert group.find(f"{SVG}title").text.count("S001") == 1
    assert len(groups(root, "link")) == 2


def test_output_is_deterministic() -> None:
    result = linter.lint_path(BROKEN, str(BROKEN), Settings())
    assert result.document is not None
    again = linter.lint_path(BROKEN, str(BROKEN), Settings())
    assert again.document is not None
    assert render_tree(result.document, result.findings) == render_tree(
        again.document, reversed(again.findings)
    )


@needs_corpus
def test_a_corpus_humanoid_renders_compact() -> None:
    path = CORPUS / "eve_r3" / "model.urdf"
    doc = linter.load(path, str(path), Settings(select=("S", "J", "I", "X")))
    result = linter.lint_document(doc, Settings(select=("S", "J", "I", "X")))
    svg = render_tree(doc, result.findings)  # its speed is measured under bench/, not here
    root = parse(svg)
    assert len(svg) < 400_000
    assert len(groups(root, "link")) == len(doc.links) == 96
    width, height = (float(v) for v in root.get("viewBox").split()[2:])
    assert width < 5000 and height < 2500


@needs_corpus
@pytest.mark.parametrize("path", corpus_models(), ids=lambda p: Path(p).parent.name)
def test_every_corpus_robot_renders(path: Path) -> None:
    doc = linter.load(path, str(path), Settings())
    root = parse(render_tree(doc))
    assert set(groups(root, "link")) >= {lk.name for lk in doc.links}
    assert len(groups(root, "joint")) == len(doc.joint_map)
