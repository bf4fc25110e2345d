"""Inline suppressions: element scope, file scope, mandatory codes, unused reports."""

from __future__ import annotations

from tests.helpers import lint_text

BASE = """<?xml version="1.0"?>
<robot name="arm">
  {file}
  <link name="base_link"/>
  {before}
  <joint name="shoulder" type="revolute">{inline}
    <origin xyz="0 0 0.1"/>
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.00833" iyz="0" izz="0.00167"/>
    </inertial>
  </link>
</robot>
"""


def codes(
    file: str = "", before: str = "", inline: str = "", select=("J001", "J009", "U002", "U003")
) -> list[tuple[int, str]]:
    text = BASE.format(file=file, before=before, inline=inline)
    return [(f.line, f.code) for f in lint_text(text, select=select)]


def test_unsuppressed_baseline() -> None:
    assert codes() == [(6, "J001")]


def test_comment_before_element_suppresses_it() -> None:
    assert codes(before="<!-- urdflint: ignore[J001] limits come from the driver -->") == []


def test_names_and_several_codes_work() -> None:
    assert codes(before="<!-- urdflint: ignore[J011, missing-limit] -->") == []


def test_inline_comment_on_the_start_tag_line() -> None:
    assert codes(inline=" <!-- urdflint: ignore[J001] -->") == []


def test_suppression_covers_only_the_next_element() -> None:
    text = BASE.format(file="", before="", inline="").replace(
        '<link name="base_link"/>', '<!-- urdflint: ignore[J001] -->\n  <link name="base_link"/>'
    )
    found = [(f.code) for f in lint_text(text, select=("J001", "U002"))]
    assert sorted(found) == ["J001", "U002"]


def test_file_suppression() -> None:
    assert codes(file="<!-- urdflint: ignore-file[J001] -->") == []


def test_unused_suppression_is_reported() -> None:
    assert codes(before="<!-- urdflint: ignore[J009] -->") == [(5, "U002"), (6, "J001")]


def test_suppression_of_a_rule_that_did_not_run_is_not_judged() -> None:
    assert codes(before="<!-- urdflint: ignore[I002] -->") == [(6, "J001")]


def test_codes_are_mandatory() -> None:
    assert codes(before="<!-- urdflint: ignore -->") == [(5, "U003"), (6, "J001")]


def test_unknown_code_in_suppression() -> None:
    assert codes(before="<!-- urdflint: ignore[Q123] -->") == [(5, "U003"), (6, "J001")]


def test_ordinary_comments_are_ignored() -> None:
    assert codes(before="<!-- the shoulder joint: urdflint is great -->") == [(6, "J001")]
