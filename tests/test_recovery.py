"""Files that are not well-formed XML but that the TinyXML-based consumers load: the XML
declaration or stray text they read past is blanked out and every rule checks the rest
(issue 24, 1); what only libxml2's recovery mode can read is checked and marked.

The fixtures in fixtures/recovered/ are cut down from PyBullet's own files
(bulletphysics/bullet3), which check_urdf and PyBullet load."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file, lint_text
from urdflint.engine import config
from urdflint.engine.linter import RECOVERED
from urdflint.model import optional
from urdflint.model.document import Document
from urdflint.model.finding import Finding, Severity

RECOVERED_MODELS = FIXTURES / "recovered"
W, E = Severity.WARNING, Severity.ERROR
LIMIT = "/robot/joint[@name='torso_to_rightleg']/limit"  # lower="-1.57." (X004)


def found(name: str, codes: tuple[str, ...]) -> list[tuple[str, str, int, Severity, bool]]:
    """(code, element, line, severity, marked as recovered) of the chosen codes, in order."""
    settings = config.from_mapping({"targets": ["gazebo-classic"], "select": list(codes)})
    path = RECOVERED_MODELS / name
    findings = lint_file(path, settings=settings)
    assert all(f.path == str(path) for f in findings)
    return [(f.code, f.element, f.line, f.severity, _marked(f)) for f in findings]


def _marked(finding: Finding) -> bool:
    return finding.message.endswith(RECOVERED)


# -- what TinyXML and TinyXML2 both read: a warning, the rest checked as they read it ---------


def test_declaration_version_0_0_is_a_warning_and_the_comma_is_found() -> None:
    # bike.urdf: check_urdf reports "Unable to parse component [0.07,] to a double"
    assert found("bike_declaration_version.urdf", ("X001", "X004")) == [
        ("X001", "/robot", 1, W, False),
        ("X004", "/robot/joint[@name='handlebar_to_frontwheel']/origin", 38, E, False),
    ]


def test_declaration_version_0_0_and_the_capsules_are_found() -> None:
    # humanoid.urdf: check_urdf reports "Unknown geometry type 'capsule'"
    assert found("humanoid_declaration_version.urdf", ("X001", "C003")) == [
        ("X001", "/robot", 1, W, False),
        ("C003", "/robot/link[@name='torso']/collision[1]/geometry/capsule", 15, W, False),
        ("C003", "/robot/link[@name='lwaist']/collision/geometry/capsule", 34, W, False),
    ]


def test_declaration_after_blank_lines_is_a_warning_and_the_limit_is_found() -> None:
    # biped2d_pybullet.urdf: check_urdf reports "lower value (-1.57.) is not a valid float"
    assert found("biped2d_late_declaration.urdf", ("X001", "X004")) == [
        ("X001", "/robot", 4, W, False),
        ("X004", LIMIT, 47, E, False),
    ]


def test_declaration_after_a_blank_line_and_the_four_meshes_are_found() -> None:
    visual = "/robot/link[@name='{}']/visual{}/geometry/mesh"
    assert found("diff_ring_late_declaration.urdf", ("X001", "C004")) == [
        ("X001", "/robot", 2, W, False),
        ("C004", visual.format("diff_ring", "[1]"), 22, E, False),
        ("C004", visual.format("diff_ring", "[2]"), 29, E, False),
        ("C004", visual.format("diff_spiderA", ""), 49, E, False),
        ("C004", visual.format("diff_sideA", ""), 69, E, False),
    ]


def test_the_x001_message_says_what_was_read_past() -> None:
    settings = config.from_mapping({"select": ["X001"]})
    (x001,) = lint_file(RECOVERED_MODELS / "bike_declaration_version.urdf", settings=settings)
    assert "Unsupported version '0.0'" in x001.message and "TinyXML2" in x001.message
    assert x001.message.endswith("the rest of the file was checked as they read it")
    assert x001.column == 1
    (x001,) = lint_file(RECOVERED_MODELS / "biped2d_late_declaration.urdf", settings=settings)
    assert "not at the very start of the file" in x001.message


# -- what only one of them reads: an error, the rest checked as that one reads it ------------


def test_declaration_after_a_comment_is_an_error_and_the_rest_is_checked() -> None:
    assert found("biped2d_declaration_after_comment.urdf", ("X001", "X004")) == [
        ("X001", "/robot", 4, E, False),
        ("X004", LIMIT, 43, E, False),
    ]


def test_stray_text_before_the_root_is_an_error_and_the_rest_is_checked() -> None:
    assert found("biped2d_stray_text.urdf", ("X001", "X004")) == [
        ("X001", "/robot", 1, E, False),
        ("X004", LIMIT, 43, E, False),
    ]


# -- what only libxml2's recovery reads: the rest checked and marked ---------------------------


def test_stray_text_after_the_root_is_recovered_and_marked() -> None:
    assert found("biped2d_trailing_text.urdf", ("X001", "X004")) == [
        ("X004", LIMIT, 43, E, True),
        ("X001", "/robot", 47, E, False),
    ]


def test_unclosed_tags_at_the_end_are_recovered_and_marked() -> None:
    assert found("biped2d_truncated.urdf", ("X001", "X004")) == [
        ("X004", LIMIT, 43, E, True),
        ("X001", "/robot", 45, E, False),
    ]


# -- a repaired tree is the file's own tree ------------------------------------------------


@pytest.mark.parametrize(
    "name",
    [
        "bike_declaration_version.urdf",
        "biped2d_late_declaration.urdf",
        "biped2d_declaration_after_comment.urdf",
        "biped2d_stray_text.urdf",
    ],
)
def test_repaired_tree_is_exact_and_not_recovered(name: str) -> None:
    source = (RECOVERED_MODELS / name).read_bytes()
    doc = Document(name, source)
    assert doc.ok and not doc.recovered and doc.problem is None and len(doc.repairs) == 1
    # the same file with the repaired line emptied by hand: the same tree, on the same lines
    lines = source.split(b"\n")
    lines[doc.repairs[0].line - 1] = b""
    by_hand = Document(name, b"\n".join(lines))
    assert by_hand.ok and not by_hand.repairs
    seen = [(el.tag, el.sourceline, dict(el.attrib)) for el in doc.robot.iter()]
    assert seen == [(el.tag, el.sourceline, dict(el.attrib)) for el in by_hand.robot.iter()]


def test_the_physics_rules_run_on_a_repaired_tree_not_on_a_recovered_one() -> None:
    if not optional.available("pinocchio"):
        pytest.skip("Pinocchio is not installed")
    # Pinocchio reads the file itself; its urdfdom (TinyXML2) ignores the version 0.0
    bike = RECOVERED_MODELS / "bike_declaration_version.urdf"
    found = lint_file(bike)
    assert "P001" not in {f.code for f in found}  # X004 is the cause, reported (issue 24, 3)
    assert any(f.code == "X004" and "0.07," in f.message and not _marked(f) for f in found)
    quiet = config.Settings(ignore=("X004",))
    (p001,) = [f for f in lint_file(bike, settings=quiet) if f.code == "P001"]
    assert "[0.07,]" in p001.message and not _marked(p001)
    codes = {f.code for f in lint_file(RECOVERED_MODELS / "biped2d_trailing_text.urdf")}
    assert not {c for c in codes if c.startswith("P")}


AXIS = """<?xml version="0.0"?>
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="continuous">
    <parent link="a"/>
    <child link="b"/>
    <axis xyz="0 0 2"/>
  </joint>
</robot>
"""


def test_fixes_apply_to_a_repaired_tree(tmp_path: Path) -> None:
    (j008,) = lint_text(AXIS, select=("J008",))
    assert j008.autofix is not None and j008.autofix.edits and not _marked(j008)
    path = tmp_path / "r.urdf"
    path.write_text(AXIS)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "fix", "--isolated", "--select", "J008", str(path)],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    text = path.read_text()
    assert '<axis xyz="0 0 1"/>' in text and text.startswith('<?xml version="0.0"?>\n')


def test_fixes_do_not_apply_to_a_recovered_tree() -> None:
    (j008,) = lint_text(AXIS.replace("0.0", "1.0") + "EOF\n", select=("J008",))
    assert _marked(j008) and j008.autofix is not None and not j008.autofix.edits


def test_a_warning_alone_does_not_fail_the_run(tmp_path: Path) -> None:
    for name in ("bike_declaration_version.urdf", "diff_ring_late_declaration.urdf"):
        shutil.copy(RECOVERED_MODELS / name, tmp_path / name)
    command = [sys.executable, "-m", "urdflint", "check", "--isolated", "--select", "X001"]
    proc = subprocess.run([*command, str(tmp_path)], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.count("warning X001") == 2, proc.stdout


# -- which declarations, texts and positions ------------------------------------------------

BODY = """<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>
</robot>
"""


@pytest.mark.parametrize(
    ("text", "severity", "line", "column", "words"),
    [
        ('<?xml version="2.0"?>\n' + BODY, W, 1, 1, "Unsupported version '2.0'"),
        ("<?xml version='0.0'?>\n" + BODY, W, 1, 1, "Unsupported version '0.0'"),
        ('<?xml version="0.0"\n  encoding="utf-8"?>\n' + BODY, W, 1, 1, "'0.0'"),
        ('\ufeff<?xml version="0.0"?>\n' + BODY, W, 1, 2, "'0.0'"),  # the BOM counts
        ('<?xml encoding="utf-8"?>\n' + BODY, W, 1, 1, "expecting version"),
        ('<?XML version="1.0"?>\n' + BODY, W, 1, 1, "Invalid PI name"),
        ('<?xml version="1.0"?>\n<?xml version="1.0"?>\n' + BODY, W, 2, 1, "second XML"),
        ('<?php x ?>\n  <?xml version="1.0"?>\n' + BODY, W, 2, 3, "very start"),
        ('<!-- é é -->  <?xml version="1.0"?>\n' + BODY, E, 1, 15, "after a comment"),
        (BODY.replace("\n", '\n<?xml version="1.0"?>', 1), E, 2, 1, "inside <robot>"),
        ("urdf\n" + BODY, E, 1, 1, "text 'urdf' before the root element"),
        ('<!-- c --> x <?xml version="1.0"?>' + BODY, E, 1, 12, "text 'x'"),
    ],
    ids=[
        "version-2",
        "single-quotes",
        "two-lines",
        "bom",
        "no-version",
        "upper-case",
        "second",
        "after-a-pi",
        "after-a-comment",
        "inside-robot",
        "stray-text",
        "text-then-declaration",
    ],
)
def test_what_is_blanked_out(text: str, severity, line: int, column: int, words: str) -> None:
    findings = lint_text(text, select=("X001", "J001"), targets=["gazebo-classic"])
    x001 = [f for f in findings if f.code == "X001"]
    assert (x001[0].severity, x001[0].line, x001[0].column) == (severity, line, column)
    assert words in x001[0].message
    (j001,) = [f for f in findings if f.code == "J001"]  # the rest was checked
    assert j001.line == text.count("\n", 0, text.index('<joint name="j"')) + 1
    assert not _marked(j001)


@pytest.mark.parametrize(
    "text",
    [
        '<?xml version="1.0" encoding="klingon"?>\n' + BODY,  # the bytes may not be UTF-8
        "robot name='r'>\n  <link name='a'/>\n</robot>\n",  # no <robot> once the text is gone
        '<?xml version="0.0"?>\n<sdf version="1.6"><model name="m"/></sdf>\n',  # not a robot
    ],
    ids=["unknown-encoding", "text-is-the-robot", "not-a-robot"],
)
def test_what_is_not_repaired(text: str) -> None:
    doc = Document("a.urdf", text.encode())
    assert doc.root is None and not doc.repairs and doc.problem is not None
    (x001,) = lint_text(text)
    assert x001.code == "X001" and x001.severity is E


def test_repairs_stop_after_a_bounded_number() -> None:
    text = '<?xml version="1.0"?>\n' * 5000 + BODY
    doc = Document("a.urdf", text.encode())
    assert doc.root is None and not doc.repairs
    assert [f.code for f in lint_text(text)] == ["X001"]


def test_a_repair_and_a_later_error_are_both_reported() -> None:
    text = '<?xml version="0.0"?>\n' + BODY.replace("</joint>", "</joint_>")
    doc = Document("a.urdf", text.encode())
    assert doc.recovered and len(doc.repairs) == 1 and doc.problem is not None
    findings = lint_text(text, select=("X001", "J001"))
    assert [(f.code, f.severity, f.line) for f in findings] == [
        ("X001", W, 1),
        ("J001", E, 5),
        ("X001", E, 5),
    ]
    assert _marked(findings[1])
