"""Will it tip over? The support polygon, D003 and the stability summary (issue 26 part 2).

The robots are the hand-built D003 fixtures (fixtures/rules/D003): a 0.6 x 0.4 m base of
20 kg on four 1 kg wheels (r = 0.1 m, contact lines at x = +-0.2 m, y = +-0.225..0.275 m,
the ground 0.15 m under the base origin) carrying a 16 kg arm. Every number below is
worked out by hand in the comments.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import fixture_settings
from urdflint.cli import main
from urdflint.engine import config, linter
from urdflint.model.document import Document
from urdflint.model.finding import Severity

pytest.importorskip("pinocchio")
pytest.importorskip("trimesh")

from urdflint.engine import stability
from urdflint.engine.stability_polygon import direction, hull, margin, shape_kind

D003 = FIXTURES / "rules" / "D003"
BASE = "/robot/link[@name='base_link']"
POLYGON = "(-0.2, -0.275), (0.2, -0.275), (0.2, 0.275), (-0.2, 0.275)"
WHEELS = ("front_left_wheel", "front_right_wheel", "rear_left_wheel", "rear_right_wheel")


def lint(path: Path, settings: config.Settings | None = None) -> list:
    settings = settings or fixture_settings(path)
    settings = replace(settings, select=("D003",))
    return linter.lint_path(path, str(path), settings).findings


def document(text: str, settings: config.Settings | None = None) -> Document:
    settings = settings or config.Settings()
    return Document("robot.urdf", text.encode(), settings=settings, base_dir=D003)


def analysed(path: Path, settings: config.Settings | None = None) -> stability.Stability:
    doc = linter.load(path, str(path), settings or fixture_settings(path))
    return stability.sample(doc)


# -- the zero pose --------------------------------------------------------------------------


def test_centre_of_mass_outside_at_spawn_is_an_error_with_margin_side_com_and_polygon() -> None:
    # COM x = (20*0 + 4*1*(+-0.2) + 16*(0.3 + 0.23)) / 40 = 0.212 m: 12 mm past x = 0.2 m;
    # z = (4*(-0.05) + 16*0.1) / 40 = 0.035 m, 0.185 m above the ground (z = -0.15 m)
    [finding] = lint(D003 / "bad.urdf")
    assert (finding.code, finding.severity, finding.line) == ("D003", Severity.ERROR, 6)
    assert finding.element == BASE and finding.path == str(D003 / "bad.urdf")
    assert finding.message == (
        "the centre of mass (0.212, 0, 0.035) m projects 12 mm outside the support polygon, "
        "towards +x (front): the robot falls at spawn (zero pose); the polygon "
        f"{POLYGON} m (root link 'base_link' frame, the ground 0.185 m under the centre of "
        "mass) spans the lowest collision points of 'front_left_wheel', 'front_right_wheel', "
        "'rear_left_wheel', 'rear_right_wheel'"
    )


def test_margin_and_tipping_angle_are_the_hand_computed_ones() -> None:
    bad = analysed(D003 / "bad.urdf").zero
    assert bad is not None
    assert math.isclose(bad.margin, -0.012, abs_tol=1e-9)
    assert math.isclose(bad.height, 0.185, abs_tol=1e-9)
    assert math.isclose(bad.tilt, math.degrees(math.atan(-0.012 / 0.185)), abs_tol=1e-9)  # type: ignore[arg-type]
    # the arm's mass 0.4 m ahead of the base: x = 16 * 0.4 / 40 = 0.16 m, 40 mm inside
    good = analysed(D003 / "good.urdf").zero
    assert good is not None
    assert math.isclose(good.margin, 0.04, abs_tol=1e-9)
    assert math.isclose(good.tilt, 12.2004687, abs_tol=1e-6)  # type: ignore[arg-type]
    assert good.direction == "+x (front)"


def test_the_same_arm_within_the_wheels_is_clean() -> None:
    assert lint(D003 / "good.urdf") == []


def test_the_centre_of_mass_is_pinocchios() -> None:
    path = D003 / "bad.urdf"
    doc = linter.load(path, str(path), config.Settings())
    zero = stability.analyse(doc).zero
    assert zero is not None
    assert all(
        math.isclose(a, b, abs_tol=1e-12) for a, b in zip(zero.com, doc.physics.com, strict=True)
    )


def test_a_configuration_given_with_q_is_checked_with_its_own_contacts() -> None:
    [finding] = lint(D003 / "bad_q.urdf")
    assert finding.severity is Severity.ERROR and finding.line == 5
    assert "projects 80 mm outside the support polygon, towards +x (front)" in finding.message
    assert "falls in the configuration given with --q (shoulder=1.571)" in finding.message


# -- reachable configurations ---------------------------------------------------------------


def test_an_arm_that_tips_only_when_extended_is_a_warning_with_the_configuration() -> None:
    # zero: x = 16 * 0.3 / 40 = 0.12 m (80 mm inside); shoulder = pi/2: x = 16 * 0.7 / 40
    [finding] = lint(D003 / "bad_reach.urdf")
    assert (finding.severity, finding.line, finding.element) == (Severity.WARNING, 5, BASE)
    assert finding.message.startswith(
        "at shoulder=1.571 the centre of mass (0.28, 0, 0.035) m leaves the support polygon "
        "by 80 mm towards +x (front): the robot tips over; the worst of "
    )
    assert "1 joint sampled within their limits (margin at the zero pose: 80 mm" in finding.message
    worst = analysed(D003 / "bad_reach.urdf").worst
    assert worst is not None and worst.values == {"shoulder": pytest.approx(math.pi / 2)}
    assert math.isclose(worst.margin, -0.08, abs_tol=1e-9)


def test_sampling_is_deterministic() -> None:
    first = analysed(D003 / "bad_reach.urdf")
    second = analysed(D003 / "bad_reach.urdf")
    assert (first.evaluated, first.worst) == (second.evaluated, second.worst)
    assert first.evaluated == 512 + 2 * 9  # the samples, then two passes of 9 values


def test_configurations_that_push_into_the_floor_are_left_out() -> None:
    # a 12 kg slider leaves the base's front at (0.4, 0, 0) along (1, 0, -1)/sqrt(2): the
    # COM x is x/3; past x = 0.6 m it would tip, but its box (0.1 m) is in the floor
    # (z - 0.05 < -0.15 - 0.01) from x = 0.51 m on: no reachable stance tips
    text = (D003 / "good.urdf").read_text()
    start = text.index('  <joint name="shoulder"')
    slider = """  <joint name="slider" type="prismatic">
    <origin xyz="0.4 0 0"/>
    <parent link="base_link"/>
    <child link="weight"/>
    <axis xyz="0.7071067811865476 0 -0.7071067811865476"/>
    <limit lower="0" upper="0.8" effort="100" velocity="1"/>
  </joint>
  <link name="weight">
    <inertial>
      <mass value="12"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
"""
    doc = document(text[:start] + slider)
    found = stability.sample(doc)
    assert found.zero is not None and math.isclose(found.zero.com[0], 0.4 * 12 / 36)
    assert found.worst is not None and found.worst.margin > 0
    assert found.worst.values["slider"] <= 0.11 * math.sqrt(2) + 1e-9


def test_a_legged_robot_gets_no_warning_for_leaning_out() -> None:
    # the reaching base standing on four feet: its legs move to keep it up
    text = (D003 / "bad_reach.urdf").read_text().replace("_wheel", "_foot")
    doc = document(text)
    found = stability.sample(doc)
    assert set(found.candidates.links.values()) == {"foot"}  # type: ignore[union-attr]
    assert found.worst is not None and found.worst.margin < 0
    assert [f for f in linter.lint_document(doc, doc.settings).findings if f.code == "D003"] == []


# -- the support ----------------------------------------------------------------------------


def test_two_wheels_on_one_axle_are_a_line_an_info_naming_the_caster() -> None:
    [finding] = lint(D003 / "bad_line.urdf")
    assert finding.severity is Severity.INFO and finding.element == BASE
    assert "touches the ground along a line, not a polygon" in finding.message
    assert "'caster' has no collision geometry" in finding.message


def test_a_robot_fixed_to_the_world_or_without_wheels_is_not_checked() -> None:
    text = (D003 / "bad.urdf").read_text()
    world = text.replace(
        '<robot name="tipping_base">',
        '<robot name="tipping_base">\n  <link name="world"/>\n  <joint name="fix" type="fixed">\n'
        '    <parent link="world"/>\n    <child link="base_link"/>\n  </joint>',
    )
    found = stability.analyse(document(world))
    assert not found.mobile and "'world'" in (found.reason or "")
    wheelless = stability.analyse(document(text.replace("_wheel", "_disc")
                                          .replace('"continuous"', '"fixed"')))  # fmt: skip
    assert not found.mobile and not wheelless.mobile
    assert lint(D003 / "good_contact_links.urdf") == []


def test_contact_links_from_the_configuration() -> None:
    # pads 0.1 m wide at x = +-0.25 m (edges at +-0.3 m); COM x = 16 * 0.83 / 38 = 0.3495 m
    path = D003 / "bad_contact_links.urdf"
    unknown, falls = lint(path)
    assert (unknown.severity, unknown.element, unknown.line) == (Severity.WARNING, "/robot", 7)
    assert "contact-links names link 'pad_5'" in unknown.message
    assert (falls.severity, falls.element, falls.line) == (Severity.ERROR, BASE, 8)
    assert "projects 49.5 mm outside the support polygon, towards +x (front)" in falls.message
    assert "'pad_1', 'pad_2', 'pad_3', 'pad_4'" in falls.message
    found = analysed(path)
    assert found.candidates is not None and found.candidates.configured
    assert math.isclose(found.zero.margin, 0.3 - 16 * 0.83 / 38, abs_tol=1e-9)  # type: ignore[union-attr]


def test_the_finding_of_a_xacro_base_sits_in_the_macro_file() -> None:
    [finding] = lint(D003 / "bad_macro.urdf.xacro")
    assert finding.path == str(D003 / "parts" / "mobile_base.xacro")
    assert (finding.line, finding.element, finding.severity) == (5, BASE, Severity.ERROR)
    assert [c.macro for c in finding.trace] == ["mobile_base"]
    assert "12 mm outside the support polygon" in finding.message


def test_stability_configuration_is_validated() -> None:
    settings = config.from_mapping({"stability": {"contact-links": ["a"], "samples": 10,
                                                  "contact-tolerance": 0.002}})  # fmt: skip
    assert settings.stability.contact_links == ("a",)
    assert (settings.stability.samples, settings.stability.contact_tolerance) == (10, 0.002)
    for bad, words in (
        ({"contact-link": []}, "unknown configuration key 'stability.contact-link'"),
        ({"contact-links": [1]}, "list of link names"),
        ({"samples": -1}, "whole number"),
        ({"contact-tolerance": "5mm"}, "number of metres"),
    ):
        with pytest.raises(config.ConfigError, match=words):
            config.from_mapping({"stability": bad})


# -- geometry -------------------------------------------------------------------------------


def test_polygon_helpers() -> None:
    square = hull([(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5), (1, 0.5)])
    assert square == [(0, 0), (1, 0), (1, 1), (0, 1)]
    assert margin(square, (0.5, 0.25)) == (0.25, (0.5, 0.0))
    assert margin(square, (1.5, 0.5)) == (-0.5, (1.0, 0.5))
    assert shape_kind(hull([(0, 0), (1, 0), (2, 0.0005)])) == "line"
    assert shape_kind([(0.0, 0.0)]) == "point"
    assert [direction(v) for v in ((1, 0), (1, 1), (0, -1), (-1, -0.2))] == [
        "+x (front)", "+x+y (front left)", "-y (right)", "-x (back)"]  # fmt: skip


# -- the summary ----------------------------------------------------------------------------


def test_summary_of_the_falling_base() -> None:
    path = D003 / "bad.urdf"
    data = stability.summary(linter.load(path, str(path), config.Settings()))
    assert data is not None
    reach = data.pop("reach")
    assert data == {
        "root": "base_link",
        "mobile": True,
        "reason": None,
        "contacts_from": "heuristic",
        "candidates": dict.fromkeys(WHEELS, "wheel"),
        "support": {
            "kind": "polygon",
            "polygon": [[-0.2, -0.275], [0.2, -0.275], [0.2, 0.275], [-0.2, 0.275]],
            "ground": -0.15,
            "contact_links": list(WHEELS),
            "lifted_mm": {},
            "below_mm": {},
        },
        "zero": {
            "q": {},
            "com": [0.212, 0.0, 0.035],
            "margin_mm": -12.0,
            "tipping_angle_deg": -3.71,
            "direction": "+x (front)",
            "com_height": 0.185,
        },
        "given": None,
        "worst": None,  # it already falls at the zero pose
        "seed": 0,
    }
    assert reach["links"] == ["arm"] and reach["link"] == "arm"
    json.dumps(reach)


def test_summary_reach_of_the_arm_is_the_hand_computed_maximum() -> None:
    # the arm box (0.1 x 0.1 x 0.8, from the shoulder at (0.3, 0, 0.1) up) turns about y in
    # [0, pi/2]: its corner (0.05, 0.05, 0.8) is at |p|^2 = 0.745 + 0.19 cos t + 0.47 sin t,
    # at most 0.745 + sqrt(0.19^2 + 0.47^2) at t = atan2(0.47, 0.19) = 1.186 rad
    path = D003 / "bad_reach.urdf"
    data = stability.summary(linter.load(path, str(path), config.Settings()))
    assert data is not None
    reach, worst = data["reach"], data["worst"]
    assert math.isclose(reach["max_distance"], math.sqrt(0.745 + math.hypot(0.19, 0.47)),
                        abs_tol=2e-4)  # fmt: skip
    assert reach["configurations"] == 1 + 512 + 2 * 9
    assert reach["bounds"]["upper"][2] == pytest.approx(0.1 + math.hypot(0.8, 0.05), abs=1e-3)
    assert worst["margin_mm"] == -80.0 and worst["q"] == {"shoulder": 1.570796}
    assert worst["tipping_angle_deg"] == round(math.degrees(math.atan(-0.08 / 0.185)), 2)
    assert data["zero"]["margin_mm"] == 80.0


def test_summary_of_a_fixed_base_arm_has_reach_and_no_support() -> None:
    path = FIXTURES / "models" / "example_arm.urdf"
    data = stability.summary(linter.load(path, str(path), config.Settings()))
    assert data is not None and data["mobile"] is False and data["support"] is None
    assert data["reach"]["max_distance"] > 0


def test_cli_check_reports_d003(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["check", "--isolated", "--select", "D003", "--format", "json",
                 str(D003 / "bad.urdf")])  # fmt: skip
    findings = json.loads(capsys.readouterr().out)["findings"]
    assert code == 1 and [(f["code"], f["line"]) for f in findings] == [("D003", 6)]


def test_info_statics_has_the_base_section(capsys: pytest.CaptureFixture[str]) -> None:
    path = str(D003 / "bad_reach.urdf")
    assert main(["info", "--isolated", "--statics", "--format", "json", path]) == 0
    sections = json.loads(capsys.readouterr().out)["statics"]["sections"]
    [base] = [s for s in sections if s["name"] == "base"]
    assert base["data"]["worst"]["margin_mm"] == -80.0
    assert main(["info", "--isolated", "--statics", path]) == 0
    out = capsys.readouterr().out
    assert "\nbase\n  contacts  front_left_wheel, front_right_wheel, rear_left_wheel" in out
    assert (
        "  zero pose com (0.12, 0, 0.195) m, margin 80 mm (inside, nearest edge +x (front))" in out
    )
    assert "at shoulder=1.571 (530 configurations of 1 joint, seed 0)" in out
