"""Texts that must not contradict themselves (issue 23, 8).

- A finding's fix never recommends a mesh format its message says a target cannot load
  (C009 once said "Drake cannot load STL collision mesh" and then "Convert the mesh to STL").
  Checked on every rule's failing fixtures with every target selected at once, and C009's
  fixtures with each target alone.
- A "Did you mean X?" fix never offers the very name the message says is wrong.
- The editor's hover on a link without ``<inertial>`` says what I001 and I013 say: a massless
  root is what KDL wants, not "Gazebo drops the link".
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import fixture_settings
from urdflint.engine import config, linter
from urdflint.model.targets import TARGETS
from urdflint.sources.mesh_formats import FORMAT_NAMES

FORMATS = sorted(set(FORMAT_NAMES.values()) | {"VTK"}, key=len, reverse=True)
CANNOT_LOAD = re.compile(r"cannot load (?:the )?(\w+)")
DID_YOU_MEAN = re.compile(r"Did you mean (?:\w+ )?'([^']+)'")


def _bad_fixtures() -> list[Path]:
    """Every rule's failing fixtures but the E rules' (confirmed in engines; their fix
    sentences are about the engine, not the model)."""
    found = (FIXTURES / "rules").glob("*/bad*")
    return sorted(
        p for p in found if p.suffix in (".urdf", ".xacro") and not fixture_settings(p).confirm
    )


def _run(path: Path, targets: tuple[str, ...] | None = None) -> linter.Result:
    settings = fixture_settings(path)
    if targets is not None:
        settings = config.Settings(**{**settings.__dict__, "targets": targets})
    return linter.lint_path(path, str(path), settings)


def _named_formats(text: str) -> set[str]:
    return {name for name in FORMATS if re.search(rf"\b{re.escape(name)}\b", text)}


def _refused_formats(message: str) -> set[str]:
    return {m.group(1) for m in CANNOT_LOAD.finditer(message)} & set(FORMATS)


def test_the_format_patterns_read_the_c009_message() -> None:
    message = "Drake cannot load STL collision mesh 'box.stl' of link 'a' (Drake reads OBJ)"
    assert _refused_formats(message) == {"STL"}
    assert _named_formats("Convert the mesh to OBJ or glTF, which Drake reads") == {"OBJ", "glTF"}


@pytest.mark.parametrize("path", _bad_fixtures(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_no_fix_contradicts_its_message_with_every_target(path: Path) -> None:
    for finding in _run(path, tuple(TARGETS)).findings:
        fix = finding.fix or ""
        clash = _refused_formats(finding.message) & _named_formats(fix)
        assert not clash, f"{finding.code}: {finding.message!r} then {fix!r}"
        for suggested in DID_YOU_MEAN.findall(fix):
            wrong = re.findall(r"'([^']+)'", finding.message)
            assert suggested not in wrong[:1], f"{finding.code}: {finding.message!r} then {fix!r}"


@pytest.mark.parametrize("target", sorted(TARGETS))
def test_c009_s_fix_names_only_formats_the_target_reads(target: str) -> None:
    seen = 0
    for path in sorted((FIXTURES / "rules" / "C009").glob("bad*.urdf")):
        for finding in _run(path, (target,)).findings:
            if finding.code != "C009":
                continue
            seen += 1
            named = _named_formats(finding.fix or "")
            assert named, finding.fix
            assert not named & _refused_formats(finding.message), (finding.message, finding.fix)
    if target in ("mujoco", "drake", "gazebo-classic", "gz-sim"):
        assert seen, f"no C009 fixture fails under {target}"


def test_drake_and_mujoco_together_are_told_obj() -> None:
    path = FIXTURES / "rules" / "C009" / "bad_drake.urdf"
    (finding,) = [f for f in _run(path, ("drake", "mujoco")).findings if f.code == "C009"]
    assert "Drake cannot load STL" in finding.message
    assert finding.fix == (
        "Convert the mesh to OBJ, which MuJoCo and Drake both read (for example with trimesh)."
    )


def _hover(result: linter.Result, name: str) -> str:
    """The hover text on link ``name``, with the findings on its start tag (as the server)."""
    from urdflint.lsp.describe import hover

    doc = result.document
    assert doc is not None
    element = doc.link_map[name].element
    here = [f for f in result.findings if f.line == element.sourceline]
    return hover(doc, here, element, "link") or ""


def test_hover_on_a_massless_root_welded_to_the_base_agrees_with_i013() -> None:
    path = FIXTURES / "rules" / "I013" / "good.urdf"  # base_footprint -> fixed -> base_link
    result = _run(path)
    assert not [f for f in result.findings if f.code in ("I001", "I013")]
    text = _hover(result, "base_footprint")
    assert "a massless root link, as KDL wants it" in text
    assert "drops" not in text


def test_hover_on_a_massless_model_s_root_points_at_i013() -> None:
    path = FIXTURES / "rules" / "J008" / "bad.urdf"  # no mass welded to the root
    result = _run(path)
    assert [f.code for f in result.findings if f.code in ("I001", "I013")] == ["I013"]
    assert "no `<inertial>` (I013 above)" in _hover(result, "base_link")
    ignored = config.Settings(**{**fixture_settings(path).__dict__, "ignore": ("I013",)})
    quiet = linter.lint_path(path, str(path), ignored)
    assert "drops the whole model" in _hover(quiet, "base_link")


@pytest.mark.parametrize(
    "path",
    sorted((FIXTURES / "rules" / "I001").glob("*.urdf"))
    + sorted((FIXTURES / "rules" / "I013").glob("*.urdf")),
    ids=lambda p: f"{p.parent.name}/{p.name}",
)
def test_hover_on_a_link_without_inertial_says_what_the_rules_say(path: Path) -> None:
    """With I001/I013 on the link, hover points at them; with the rules ignored, hover says
    "drops" exactly where the rule said it."""
    result = _run(path)
    base = fixture_settings(path)
    ignored = config.Settings(**{**base.__dict__, "ignore": (*base.ignore, "I001", "I013")})
    quiet = linter.lint_path(path, str(path), ignored)
    doc = result.document
    assert doc is not None
    for link in doc.links:
        if link.element.find("inertial") is not None:
            continue
        line = link.element.sourceline
        on = [f for f in result.findings if f.code in ("I001", "I013") and f.line == line]
        if on:
            assert f"({on[0].code} above)" in _hover(result, link.name)
        said = [  # on the link, or on the model's first moving link, naming it
            f for f in result.findings
            if f.code in ("I001", "I013") and (f in on or f"'{link.name}'" in f.message)
        ]  # fmt: skip
        text = _hover(quiet, link.name)
        drops = any("drops" in f.message and f"'{link.name}'" in f.message for f in said)
        assert ("drops" in text) == drops, f"{path.name} {link.name}: {text!r} / {said}"
