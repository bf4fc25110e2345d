"""``urdflint lsp`` driven over stdio as an editor drives it (pytest-lsp): diagnostics with
exact ranges on open and on change, in the macro file where a xacro defect is written, code
actions that fix or suppress, hover, the outline."""

from __future__ import annotations

import asyncio
import re
import shutil
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")

from lsprotocol import types as T  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402

from tests.conftest import FIXTURES  # noqa: E402

SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "urdflint", "lsp"])
J008 = FIXTURES / "rules" / "J008" / "bad.urdf"

MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="segment" params="name parent">
    <link name="${name}">
      <inertial>
        <mass value="0.5"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
      </inertial>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}"/>
      <axis xyz="1 1 0"/>
      <limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""
ENTRY = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find arm_description)/urdf/segment.xacro"/>
  <link name="base_link"/>
  <xacro:segment name="upper" parent="base_link"/>
  <xacro:segment name="lower" parent="upper"/>
</robot>
"""


async def start(client: LanguageClient, folder: Path) -> None:
    """Initialise a session as VS Code does, with ``folder`` as the workspace."""
    await client.initialize_session(
        T.InitializeParams(
            capabilities=pytest_lsp.client_capabilities("visual-studio-code"),
            root_uri=folder.as_uri(),
            workspace_folders=[T.WorkspaceFolder(folder.as_uri(), "work")],
        )
    )


@pytest_lsp.fixture(config=SERVER)
async def client(lsp_client: LanguageClient, tmp_path: Path):
    await start(lsp_client, tmp_path)
    yield
    await lsp_client.shutdown_session()


async def published(client: LanguageClient, uri: str, before: object) -> None:
    """Wait until the server publishes ``uri``'s diagnostics anew (an analysis publishes every
    file it reaches, one notification each, maybe several in one read: poll, do not count)."""

    async def wait() -> None:
        while client.diagnostics.get(uri) is before:
            await asyncio.sleep(0.01)

    await asyncio.wait_for(wait(), 60)


async def opened(
    client: LanguageClient, path: Path, text: str | None = None, wait_for: Path | None = None
) -> str:
    uri = path.as_uri()
    shown = (wait_for or path).as_uri()
    before = client.diagnostics.get(shown)
    client.text_document_did_open(
        T.DidOpenTextDocumentParams(
            T.TextDocumentItem(uri, "xml", 1, path.read_text() if text is None else text)
        )
    )
    await published(client, shown, before)
    return uri


async def changed(client: LanguageClient, uri: str, text: str, version: int = 2) -> None:
    before = client.diagnostics.get(uri)
    client.text_document_did_change(
        T.DidChangeTextDocumentParams(
            T.VersionedTextDocumentIdentifier(version, uri),
            [T.TextDocumentContentChangeWholeDocument(text)],
        )
    )
    await published(client, uri, before)


def codes(client: LanguageClient, uri: str) -> list[tuple[str | int | None, int, int, int]]:
    return [
        (d.code, d.range.start.line, d.range.start.character, d.range.end.character)
        for d in client.diagnostics.get(uri, [])
    ]


def apply(text: str, edits: list[T.TextEdit]) -> str:
    lines = text.split("\n")
    offsets = [sum(len(line) + 1 for line in lines[:i]) for i in range(len(lines))]
    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character))[::-1]:
        start = offsets[edit.range.start.line] + edit.range.start.character
        end = offsets[edit.range.end.line] + edit.range.end.character
        text = text[:start] + edit.new_text + text[end:]
    return text


@pytest.mark.asyncio
async def test_open_a_broken_file_then_fix_it_in_the_buffer(client: LanguageClient, tmp_path):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    uri = await opened(client, path)
    # the <axis .../> start tags on lines 7, 20, 33 (1-based), indented by 4
    assert [c for c in codes(client, uri) if c[0] == "J008"] == [
        ("J008", 6, 4, 23),
        ("J008", 19, 4, 23),
        ("J008", 32, 4, 25),
    ]
    first = next(d for d in client.diagnostics[uri] if d.code == "J008")
    assert first.severity == T.DiagnosticSeverity.Warning
    assert first.source == "urdflint"
    text = path.read_text().replace('xyz="1 1 0"', 'xyz="1 0 0"')
    await changed(client, uri, text)  # the unsaved buffer, not the file
    assert [c[1] for c in codes(client, uri) if c[0] == "J008"] == [19, 32]


@pytest.mark.asyncio
async def test_code_actions_fix_and_suppress(client: LanguageClient, tmp_path):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    uri = await opened(client, path)
    diagnostic = next(d for d in client.diagnostics[uri] if d.code == "J008")
    actions = await client.text_document_code_action_async(
        T.CodeActionParams(
            T.TextDocumentIdentifier(uri),
            diagnostic.range,
            T.CodeActionContext([diagnostic]),
        )
    )
    assert actions is not None
    titles = [a.title for a in actions if isinstance(a, T.CodeAction)]
    assert titles[0].startswith("Fix J008: ")
    assert titles[1] == "Suppress J008 (non-unit-axis) with a comment"
    fix = actions[0]
    assert isinstance(fix, T.CodeAction) and fix.edit and fix.edit.document_changes
    change = fix.edit.document_changes[0]
    assert isinstance(change, T.TextDocumentEdit)
    fixed = apply(path.read_text(), list(change.edits))  # type: ignore[arg-type]
    assert '<axis xyz="0.707107 0.707107 0"/>' in fixed.split("\n")[6]
    await changed(client, uri, fixed)
    assert [c[1] for c in codes(client, uri) if c[0] == "J008"] == [19, 32]

    second = next(d for d in client.diagnostics[uri] if d.code == "J008")
    assert second.range.start.line == 19
    actions = await client.text_document_code_action_async(
        T.CodeActionParams(
            T.TextDocumentIdentifier(uri), second.range, T.CodeActionContext([second])
        )
    )
    suppress = (actions or [])[-1]
    assert isinstance(suppress, T.CodeAction) and suppress.edit and suppress.edit.changes
    quiet = apply(fixed, suppress.edit.changes[uri])
    assert quiet.split("\n")[19] == "    <!-- urdflint: ignore[J008] non-unit-axis -->"
    await changed(client, uri, quiet, 3)
    assert [c[1] for c in codes(client, uri) if c[0] == "J008"] == [33]


@pytest.fixture
def package(tmp_path: Path) -> Path:
    root = tmp_path / "arm_description"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>arm_description</name>'
        "<version>0.1.0</version><description>arm</description>"
        '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n'
    )
    (root / "urdf" / "segment.xacro").write_text(MACRO)
    (root / "urdf" / "arm.urdf.xacro").write_text(ENTRY)
    return root


@pytest.mark.asyncio
async def test_a_macro_file_open_alone_shows_the_defects_written_in_it(
    client: LanguageClient, package: Path
):
    macro = package / "urdf" / "segment.xacro"
    uri = await opened(client, macro)
    # the axis inside the macro, line 13: once, although the entry calls the macro twice
    assert [c for c in codes(client, uri) if c[0] == "J008"] == [("J008", 12, 6, 25)]
    related = client.diagnostics[uri][0].related_information or []
    assert any("in macro `segment`, called here" in r.message for r in related)
    await changed(client, uri, MACRO.replace('xyz="1 1 0"', 'xyz="0 0 1"'))
    assert [c for c in codes(client, uri) if c[0] == "J008"] == []


@pytest.mark.asyncio
async def test_the_entry_file_puts_diagnostics_in_the_macro_file(
    client: LanguageClient, package: Path
):
    entry, macro = package / "urdf" / "arm.urdf.xacro", package / "urdf" / "segment.xacro"
    await opened(client, entry, wait_for=macro)
    macro_uri = macro.as_uri()
    assert [c for c in codes(client, macro_uri) if c[0] == "J008"] == [("J008", 12, 6, 25)]


@pytest.mark.asyncio
async def test_hover_on_a_link_the_robot_and_a_finding(client: LanguageClient, tmp_path):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    uri = await opened(client, path)

    async def hover(line: int, character: int) -> str:
        found = await client.text_document_hover_async(
            T.HoverParams(T.TextDocumentIdentifier(uri), T.Position(line, character))
        )
        assert found is not None and isinstance(found.contents, T.MarkupContent)
        return found.contents.value

    link = await hover(11, 10)  # <link name="link1">
    assert "**link `link1`**" in link and "mass 0.5 kg" in link
    assert "principal moments 0.001 0.001 0.001" in link
    robot = await hover(2, 3)
    assert "4 links, 3 joints" in robot and "total mass 1.5 kg" in robot
    axis = await hover(6, 8)
    assert axis.startswith("**J008 non-unit-axis** (warning)")
    assert "`urdflint explain J008`" in axis


@pytest.mark.asyncio
async def test_outline_is_the_link_and_joint_tree(client: LanguageClient, tmp_path):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    uri = await opened(client, path)
    found = await client.text_document_document_symbol_async(
        T.DocumentSymbolParams(T.TextDocumentIdentifier(uri))
    )
    assert found is not None
    (robot,) = found
    assert isinstance(robot, T.DocumentSymbol) and robot.name == "j008_bad"
    links = robot.children or []
    assert [s.name for s in links] == ["base_link", "link1", "link2", "link3"]
    shoulder = (links[0].children or [])[0]
    assert (shoulder.name, shoulder.detail) == ("shoulder", "revolute -> link1")
    assert shoulder.range.start == T.Position(4, 2)
    # the whole element, end tag included (breadcrumbs inside a joint); the name: its tag
    assert shoulder.range.end == T.Position(10, 10)  # after </joint>
    assert shoulder.selection_range.start == shoulder.range.start
    assert shoulder.selection_range.end.line == 4
    assert links[0].range.end == T.Position(3, 26)  # <link name="base_link"/>
    assert robot.range.end.line > links[-1].range.end.line


def test_an_element_s_end_skips_comments_and_counts_nested_tags() -> None:
    from urdflint.lsp.extent import Text

    lines = [
        '<robot name="r"><link name="a"> <!-- </link> -->',
        '  <visual><geometry><box size="1 1 1"/></geometry></visual>',
        '</link><link name="b" a=">"/>',
        "</robot>",
    ]
    text = Text(lines)
    assert text.end(0, 16) == T.Position(2, 7)
    assert text.end(2, 7) == T.Position(2, 29)
    assert text.end(0, 0) == T.Position(3, 8)
    assert Text(["<robot>", "  <link>"]).end(1, 2) is None  # half typed


def test_a_suppression_goes_right_before_an_element_that_does_not_start_its_line() -> None:
    from urdflint.lsp import convert
    from urdflint.model.finding import Finding, Severity

    lines = ['  <joint name="j" type="fixed"><axis xyz="0 0 0"/>', "  </joint>"]
    finding = Finding("a.urdf", 1, 33, "J006", "ignored-axis", Severity.INFO, "m", "/robot")
    edit = convert.suppression(lines, "file:///a.urdf", finding)
    (change,) = (edit.changes or {})["file:///a.urdf"]
    assert change.range.start == T.Position(0, 31)  # the <axis> moves to a line of its own
    assert change.new_text == "\n    <!-- urdflint: ignore[J006] ignored-axis -->\n    "
    finding = Finding("a.urdf", 1, 3, "J006", "ignored-axis", Severity.INFO, "m", "/robot")
    (change,) = (convert.suppression(lines, "file:///a.urdf", finding).changes or {})[
        "file:///a.urdf"
    ]
    assert change.range.start == T.Position(0, 0)
    assert change.new_text == "  <!-- urdflint: ignore[J006] ignored-axis -->\n"


@pytest.mark.asyncio
async def test_a_half_typed_file_is_a_finding_not_a_crash(client: LanguageClient, tmp_path):
    path = tmp_path / "typing.urdf"
    text = '<?xml version="1.0"?>\n<robot name="r">\n  <link name="a">\n  <joint\n'
    path.write_text(text)
    uri = await opened(client, path)
    (broken,) = [d for d in client.diagnostics[uri] if d.code == "X001"]
    assert broken.severity == T.DiagnosticSeverity.Error
    await changed(
        client, uri, '<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"/>\n</robot>\n'
    )
    assert "X001" not in [d.code for d in client.diagnostics[uri]]


@pytest.mark.asyncio
async def test_a_macro_file_included_by_another_macro_file(client: LanguageClient, package: Path):
    urdf = package / "urdf"
    (urdf / "arm_macro.xacro").write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find arm_description)/urdf/segment.xacro"/>\n'
        '  <xacro:macro name="arm" params="parent">\n'
        '    <xacro:segment name="upper" parent="${parent}"/>\n'
        "  </xacro:macro>\n</robot>\n"
    )
    (urdf / "arm.urdf.xacro").write_text(
        '<?xml version="1.0"?>\n<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find arm_description)/urdf/arm_macro.xacro"/>\n'
        '  <link name="base_link"/>\n  <xacro:arm parent="base_link"/>\n</robot>\n'
    )
    uri = await opened(client, urdf / "segment.xacro")
    assert [c for c in codes(client, uri) if c[0] == "J008"] == [("J008", 12, 6, 25)]


def _suppressed(text: str, finding) -> str:  # type: ignore[no-untyped-def]
    from urdflint.lsp import convert

    lines = convert.lines_of(text)
    (change,) = (convert.suppression(lines, "file:///x.urdf", finding).changes or {})[
        "file:///x.urdf"
    ]
    start = change.range.start
    line = lines[start.line]
    joined = line[: start.character] + change.new_text + line[start.character :]
    return "\n".join([*lines[: start.line], joined, *lines[start.line + 1 :]])


SUPPRESSIBLE = sorted((FIXTURES / "rules").glob("*/bad*.urdf"))


@pytest.mark.parametrize("path", SUPPRESSIBLE, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_suppressing_any_finding_keeps_the_file_and_removes_exactly_it(path: Path) -> None:
    """The suppress action on every finding of an element in every rule fixture: the file
    still parses, and exactly what such a comment hides is gone: that code on that element
    and inside it (findings at attributes comment their element; an element that shares its
    line moves to a line of its own) (issue 23, 1)."""
    from collections import Counter

    from urdflint.engine import linter
    from urdflint.engine.config import Settings

    text = path.read_text()

    def findings(data: str) -> Counter[tuple[str, str, str]]:
        found = linter.lint_bytes(data.encode(), str(path), Settings(), base_dir=path.parent)
        return Counter(  # messages that cite a line: one more after the comment's line
            (f.code, f.element, re.sub(r"line \d+", "line N", f.message))
            for f in found.findings
            if f.path == str(path)
        )

    before = linter.lint_bytes(text.encode(), str(path), Settings(), base_dir=path.parent)
    everything = findings(text)
    if any(code == "X001" for code, _, _ in everything):
        return  # a file that does not parse: nothing to anchor a comment to
    for finding in before.findings:
        if finding.path != str(path) or finding.element == "/robot":
            continue  # robot-level findings (the file, its declaration): issue 23 goes on
        after = findings(_suppressed(text, finding))
        assert ("X001", "/robot") not in {(c, e) for c, e, _ in after}, finding.code
        # what a comment before the element hides: the code there and inside it (README)
        hidden = Counter(
            {
                key: n
                for key, n in everything.items()
                if key[0] == finding.code
                and (key[1] == finding.element or key[1].startswith(finding.element + "/"))
            }
        )
        where = (finding.code, finding.line, finding.column)
        assert after - everything == Counter(), where  # nothing new
        gone = (finding.code, finding.element, re.sub(r"line \d+", "line N", finding.message))
        assert after[gone] < everything[gone], where  # that finding is gone
        for key, n in everything.items():  # the rest stays, but what the comment may hide
            assert (after[key] <= n) if key in hidden else (after[key] == n), (where, key)


def test_a_defect_seen_through_two_entries_is_one_diagnostic_with_both_calls(tmp_path) -> None:
    """A macro file included by two robots: its defect is shown once, naming the most
    instances, with the macro calls of both robots as related locations (issue 23, 2)."""
    pytest.importorskip("xacro")
    from urdflint.lsp.analysis import Analyzer

    (tmp_path / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="arm" params="side">\n'
        '    <link name="${side}_upper"/>\n'
        '    <link name="${side}_lower"/>\n'
        '    <joint name="${side}_elbow" type="revolute">\n'
        '      <parent link="${side}_upper"/><child link="${side}_lower"/>\n'
        '      <axis xyz="0 0 0"/>\n'
        '      <limit lower="-1" upper="1" effort="1" velocity="1"/>\n'
        "    </joint>\n"
        "  </xacro:macro>\n"
        "</robot>\n"
    )
    head = '<robot name="{}" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    include = '  <xacro:include filename="arm.xacro"/>\n  <link name="base"/>\n'
    (tmp_path / "two.urdf.xacro").write_text(
        head.format("two") + include + '  <xacro:arm side="l"/>\n  <xacro:arm side="r"/>\n'
        '  <joint name="jl" type="fixed"><parent link="base"/><child link="l_upper"/></joint>\n'
        '  <joint name="jr" type="fixed"><parent link="base"/><child link="r_upper"/></joint>\n'
        "</robot>\n"
    )
    (tmp_path / "one.urdf.xacro").write_text(
        head.format("one") + include + '  <xacro:arm side="m"/>\n'
        '  <joint name="jm" type="fixed"><parent link="base"/><child link="m_upper"/></joint>\n'
        "</robot>\n"
    )
    analyzer = Analyzer([tmp_path])
    for entry in ("two.urdf.xacro", "one.urdf.xacro"):
        analyzer.analyse(str(tmp_path / entry))
    per_entry = [
        [f for f in a.findings.get(str(tmp_path / "arm.xacro"), []) if f.code == "J007"]
        for a in analyzer.analyses.values()
    ]
    assert [len(found) for found in per_entry] == [1, 1]  # each entry sees it
    (j007,) = [f for f in analyzer.findings_for(str(tmp_path / "arm.xacro")) if f.code == "J007"]
    assert j007.line == 7
    assert "l_elbow" in j007.message and "r_elbow" in j007.message
    calls = {(Path(c.path).name, c.line) for c in j007.trace}
    assert ("two.urdf.xacro", 4) in calls and ("one.urdf.xacro", 4) in calls


def test_a_macro_file_s_outline_is_its_macros_with_what_each_writes(tmp_path) -> None:
    """A macro file (through the robot that includes it): its links and joints under the
    macro that writes them, once each even when the macro is called twice (issue 23, 3)."""
    pytest.importorskip("xacro")
    from urdflint.lsp.analysis import Analyzer
    from urdflint.lsp.describe import symbols

    macro = tmp_path / "arm.xacro"
    macro.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="arm" params="side">\n'
        '    <link name="${side}_upper"/>\n'
        '    <link name="${side}_lower"/>\n'
        '    <joint name="${side}_elbow" type="fixed">\n'
        '      <parent link="${side}_upper"/><child link="${side}_lower"/>\n'
        "    </joint>\n"
        "  </xacro:macro>\n"
        '  <xacro:macro name="tool" params="">\n'
        '    <link name="tool"/>\n'
        "  </xacro:macro>\n"
        "</robot>\n"
    )
    robot = tmp_path / "two.urdf.xacro"
    robot.write_text(
        '<robot name="two" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="arm.xacro"/>\n  <link name="base"/>\n'
        '  <xacro:arm side="l"/>\n  <xacro:arm side="r"/>\n  <xacro:tool/>\n'
        '  <joint name="jl" type="fixed"><parent link="base"/><child link="l_upper"/></joint>\n'
        '  <joint name="jr" type="fixed"><parent link="base"/><child link="r_upper"/></joint>\n'
        '  <joint name="jt" type="fixed"><parent link="base"/><child link="tool"/></joint>\n'
        "</robot>\n"
    )
    analyzer = Analyzer([tmp_path])
    analyzer.analyse(str(robot))
    covering = analyzer.document_for(str(macro))
    assert covering is not None
    lines = macro.read_text().split("\n")
    outline = symbols(covering[0], str(macro), lines)
    assert [(s.name, s.detail) for s in outline] == [
        ("arm", "xacro:macro"),
        ("tool", "xacro:macro"),
    ]
    arm, tool = outline
    assert [s.name for s in arm.children or []] == ["l_upper", "l_lower", "l_elbow"]
    assert [s.name for s in tool.children or []] == ["tool"]
    assert (arm.range.start.line, arm.range.end.line) == (1, 7)
