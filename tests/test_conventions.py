"""The N family: REP naming conventions, run only with a profile (``--profile``, ``profile =``)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import fixture_settings, lint_file, lint_text
from urdflint.cli import main
from urdflint.engine import config, registry
from urdflint.model import conventions as N
from urdflint.model.document import Document
from urdflint.model.finding import Finding, Severity
from urdflint.model.inertia import rpy_matrix

RULES = {code: r for code, r in registry.load_rules().items() if code.startswith("N")}
PROFILES = ("mobile", "industrial", "humanoid")
# which profiles each rule runs for
RUNS_FOR = {
    "N001": {"mobile", "industrial", "humanoid"},
    "N002": {"mobile", "humanoid"},
    "N003": {"mobile", "humanoid"},
    "N004": {"mobile", "industrial", "humanoid"},
    "N005": {"industrial"},
    "N006": {"industrial"},
    "N007": {"industrial"},
    "N008": {"humanoid"},
}
# the profile under which each rule's good_no_profile.urdf would be reported
OPT_IN = {
    "N001": "mobile",
    "N002": "mobile",
    "N003": "mobile",
    "N004": "mobile",
    "N005": "industrial",
    "N006": "industrial",
    "N007": "industrial",
    "N008": "humanoid",
}


def rules_dir(code: str) -> Path:
    return FIXTURES / "rules" / code


def lint(path: Path, code: str, profile: str | None = "keep") -> list[Finding]:
    settings = fixture_settings(path)
    if profile != "keep":
        settings = config.Settings(**{**settings.__dict__, "profile": profile})
    return [f for f in lint_file(path, select=(code,), settings=settings) if f.code == code]


def one(path: Path, code: str) -> Finding:
    found = lint(path, code)
    assert len(found) == 1, found
    return found[0]


def test_the_family_is_the_one_the_table_describes() -> None:
    assert set(RULES) == set(RUNS_FOR)
    for rule in RULES.values():
        assert rule.severity in (Severity.INFO, Severity.WARNING), rule.code
        assert "REP" in rule.section("Why is this bad?"), rule.code
        assert "profile" in rule.section("What it does"), rule.code


@pytest.mark.parametrize("code", sorted(OPT_IN))
def test_every_rule_is_opt_in(code: str) -> None:
    path = rules_dir(code) / "good_no_profile.urdf"
    assert not path.with_suffix(".toml").exists()
    assert lint(path, code) == []
    assert lint(path, code, OPT_IN[code]), f"{code}: the no-profile fixture proves nothing"


@pytest.mark.parametrize("code", sorted(RUNS_FOR))
def test_rules_run_only_for_their_profiles(code: str) -> None:
    bad = sorted(rules_dir(code).glob("bad*.urdf"))
    assert bad
    for path in bad:
        for profile in PROFILES:
            found = lint(path, code, profile)
            if profile not in RUNS_FOR[code]:
                assert found == [], f"{code} ran for {profile} on {path.name}"
        assert lint(path, code, None) == []


def test_n001_names_the_root_and_the_rep_of_the_profile() -> None:
    found = one(rules_dir("N001") / "bad_mobile.urdf", "N001")
    assert (found.line, found.element) == (4, "/robot/link[@name='chassis']")
    assert found.severity is Severity.WARNING
    assert found.message.startswith("REP 105 (base_link) expects the robot's root body")
    assert "'chassis' has none" in found.message
    detached = one(rules_dir("N001") / "bad_detached.urdf", "N001")
    assert detached.message.startswith("REP 120 (base_link)")
    assert "'base_link' is not rigidly attached to the root link 'pelvis'" in detached.message


def test_n001_is_informational_for_the_draft_rep_199() -> None:
    found = one(rules_dir("N001") / "bad_industrial.urdf", "N001")
    assert found.severity is Severity.INFO
    assert found.message.startswith("REP 199 draft (base_link)")


def test_n002_names_the_frame_authority() -> None:
    found = lint(rules_dir("N002") / "bad.urdf", "N002")
    assert [(f.line, f.element) for f in found] == [
        (3, "/robot/link[@name='odom']"),
        (20, "/robot/link[@name='map']"),
    ]
    assert "REP 105 reserves 'odom'" in found[0].message
    assert "odometry source" in found[0].message
    assert "localization component" in found[1].message
    assert all(f.severity is Severity.WARNING for f in found)


def test_n003_mobile_reports_rotation_and_height() -> None:
    found = one(rules_dir("N003") / "bad_mobile.urdf", "N003")
    assert (found.line, found.element) == (10, "/robot/joint[@name='footprint_joint']")
    assert found.severity is Severity.INFO
    assert 'rotated rpy="0 0.2 0"' in found.message
    assert "0.05 m above 'base_link'" in found.message


def test_n003_mobile_reports_a_moving_footprint_and_humanoid_a_rigid_one() -> None:
    moving = one(rules_dir("N003") / "bad_moving.urdf", "N003")
    assert moving.element == "/robot/joint[@name='suspension']"
    assert "moves with respect to 'base_link'" in moving.message
    rigid = one(rules_dir("N003") / "bad_humanoid.urdf", "N003")
    assert rigid.message.startswith("REP 120 (Frame Authorities): on a humanoid")


def test_n004_says_what_rep_103_expects_and_what_the_file_has() -> None:
    found = lint(rules_dir("N004") / "bad.urdf", "N004")
    assert [(f.line, f.element) for f in found] == [
        (15, "/robot/joint[@name='camera_optical_joint']"),
        (27, "/robot/joint[@name='rgb_optical_joint']"),
    ]
    assert "rpy=\"-pi/2 0 -pi/2\" from the body frame 'camera_link'" in found[0].message
    assert found[0].message.endswith('here it is rpy="0 0 0"')
    assert found[1].message.endswith('here it is rpy="pi/2 0 pi/2"')
    assert "'camera_rgb_frame'" in found[1].message


def test_n005_lists_the_missing_frames_once() -> None:
    found = one(rules_dir("N005") / "bad.urdf", "N005")
    assert (found.line, found.element) == (3, "/robot/link[@name='base_link']")
    assert found.message.endswith("this robot has no 'base', 'flange'")


def test_n006_reports_the_moving_joint_and_the_geometry() -> None:
    found = lint(rules_dir("N006") / "bad.urdf", "N006")
    assert [(f.line, f.element) for f in found] == [
        (51, "/robot/link[@name='base']/visual"),
        (55, "/robot/joint[@name='flange-tool0']"),
    ]
    assert "'base' shall not have any geometry; it has a <visual>" in found[0].message
    assert "here its parent is revolute joint 'flange-tool0'" in found[1].message


def test_n007_names_the_axis_tool0_points_along() -> None:
    found = one(rules_dir("N007") / "bad.urdf", "N007")
    assert found.element == "/robot/joint[@name='flange-tool0']"
    assert found.message.endswith("here it points along 'flange''s +z")
    reversed_ = one(rules_dir("N007") / "bad_reversed.urdf", "N007")
    assert reversed_.message.endswith("'flange''s -x")


def test_n008_reports_differently_spelt_rep_120_frames() -> None:
    found = lint(rules_dir("N008") / "bad.urdf", "N008")
    assert {(f.element, f.message) for f in found} == {
        (
            "/robot/link[@name='left_sole_link']",
            "REP 120 names the left sole frame 'l_sole'; this robot calls it 'left_sole_link'",
        ),
        (
            "/robot/link[@name='rightGripper']",
            "REP 120 names the right gripper frame 'r_gripper'; this robot calls it 'rightGripper'",
        ),
    }


def test_profile_from_a_mapping_and_the_cli(capsys: pytest.CaptureFixture[str]) -> None:
    path = rules_dir("N002") / "good_no_profile.urdf"
    text = path.read_text()
    assert [f.code for f in lint_text(text, ("N002",), profile="mobile")] == ["N002"]
    assert lint_text(text, ("N002",)) == []
    assert main(["check", "--select", "N", str(path)]) == 0
    assert "no problems" in capsys.readouterr().out
    assert main(["check", "--select", "N", "--profile", "mobile", str(path)]) == 0  # a warning
    out = capsys.readouterr().out
    assert f"{path}:4:3: warning N002 reserved-frame-link: REP 105 reserves 'odom'" in out
    args = ["check", "--select", "N", "--fail-on", "warning", str(path)]
    assert main([*args, "--profile", "mobile"]) == 1
    assert main([*args, "--profile", "industrial"]) == 0
    assert main([*args]) == 0


# -- model helpers -------------------------------------------------------------------------


def test_named_accepts_prefixes_only_at_a_separator() -> None:
    assert N.named("tool0", "tool0")
    assert N.named("left_tool0", "tool0")
    assert N.named("${prefix}tool0", "tool0")
    assert N.named("ns/base_link", "base_link")
    assert not N.named("mytool0", "tool0")
    assert not N.named(None, "tool0")


def test_relative_composes_through_the_common_ancestor() -> None:
    doc = Document("t.urdf", (rules_dir("N004") / "good.urdf").read_bytes())
    pose = N.relative(doc, "camera_depth_frame", "camera_depth_optical_frame")
    assert pose is not None
    expected = rpy_matrix((-math.pi / 2, 0.0, -math.pi / 2))
    assert N.angle(expected, pose[0]) < 1e-6
    back = N.relative(doc, "camera_depth_optical_frame", "camera_depth_frame")
    assert back is not None and N.angle(pose[0], back[0]) > 1
    sibling = N.relative(doc, "camera_depth_frame", "camera_link_optical")
    assert sibling is not None
    arm = Document("a.urdf", (rules_dir("N006") / "bad.urdf").read_bytes())
    assert N.relative(arm, "flange", "tool0") is None  # across a revolute joint
    assert N.relative(arm, "flange", "tool0", rigid=False) is not None


def test_angles_print_as_multiples_of_pi() -> None:
    r = rpy_matrix((-math.pi / 2, 0.0, -math.pi / 2))
    assert N.fmt_angles(N.rpy_of(r)) == "-pi/2 0 -pi/2"
    assert N.fmt_angles((0.3, 0.0, math.pi)) == "0.3 0 pi"
    assert N.fmt_axis((0.0, 0.0, -1.0)) == "-z"
    assert N.fmt_axis((0.6, 0.8, 0.0)) == "(0.6 0.8 0)"
