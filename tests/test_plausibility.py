"""J015 limit-in-degrees and X014 unsafe-name (J016 missing-joint-damping was not built)."""

from __future__ import annotations

from urdflint.rules.joints.j015_limit_in_degrees import degree_bound, degree_velocity

from tests.helpers import lint_text
from urdflint.engine import config, linter, registry
from urdflint.model.finding import Severity

INERTIAL = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
)


def arm(limit: str, kind: str = "revolute", joint: str = "elbow", child: str = "forearm") -> str:
    return (
        f'<robot name="r">\n  <link name="base">{INERTIAL}</link>\n'
        f'  <joint name="{joint}" type="{kind}">\n'
        f'    <parent link="base"/><child link="{child}"/><axis xyz="0 0 1"/>\n'
        f'    {limit}\n  </joint>\n  <link name="{child}">{INERTIAL}</link>\n</robot>\n'
    )


def found(text: str, code: str, **settings: object) -> list:
    return [f for f in lint_text(text, (code,), **settings) if f.code == code]


# -- J015 --------------------------------------------------------------------------------


def test_degree_thresholds() -> None:
    assert degree_bound(180.0) and degree_bound(-90.0) and degree_bound(13.0)
    assert not degree_bound(12.5)  # below 4 pi: multi-turn joints (ANYmal 3 pi, ABB 400 deg)
    assert not degree_bound(1e16) and not degree_bound(1000.0) and not degree_bound(1100.0)
    assert degree_velocity(180.0) and degree_velocity(90.0) and degree_velocity(720.0)
    assert not degree_velocity(100.0) and not degree_velocity(1000.0)  # placeholders
    assert not degree_velocity(52.4) and not degree_velocity(205.0)


def test_degree_bounds_are_one_warning_with_the_conversion() -> None:
    hits = found(arm('<limit lower="-90" upper="180" effort="1" velocity="2"/>'), "J015")
    assert [(h.line, h.element, h.severity) for h in hits] == [
        (5, "/robot/joint[@name='elbow']/limit", Severity.WARNING)
    ]
    assert hits[0].message == (
        "revolute joint 'elbow' has lower -90 and upper 180 rad (28.6 turns): degrees "
        "(then lower=-1.5708, upper=3.1416), or a joint that turns freely and should be "
        "continuous"
    )


def test_degree_velocity_is_reported_on_revolute_only() -> None:
    hits = found(arm('<limit lower="-1" upper="1" effort="1" velocity="180"/>'), "J015")
    assert [h.line for h in hits] == [5]
    assert "180°/s is 3.1416 rad/s" in hits[0].message
    wheel = arm('<limit effort="1" velocity="180"/>', kind="continuous")
    assert found(wheel, "J015") == []
    slide = arm('<limit lower="0" upper="90" effort="1" velocity="180"/>', kind="prismatic")
    assert found(slide, "J015") == []


def test_plausible_limits_are_quiet() -> None:
    for limit in (
        '<limit lower="-9.42477796077" upper="9.42477796077" effort="80" velocity="7.5"/>',
        '<limit lower="-6.9813" upper="6.9813" effort="80" velocity="100"/>',
        '<limit lower="-1e16" upper="1e16" effort="80" velocity="1000"/>',
    ):
        assert found(arm(limit), "J015") == []


def test_wheels_get_no_degree_repair() -> None:
    text = arm('<limit lower="-180" upper="180" effort="1" velocity="2"/>', joint="wheel1_joint")
    settings = config.Settings(select=("J015",))
    result = linter.lint_bytes(text.encode(), "test.urdf", settings)
    assert [f.code for f in result.findings] == ["J015"]
    assert registry.lookup("J015") is not None
    assert [f.autofix for f in result.findings] == [None]
    degrees = arm('<limit lower="-180" upper="180" effort="1" velocity="2"/>')
    other = linter.lint_bytes(degrees.encode(), "test.urdf", settings).findings
    assert [f.autofix is not None for f in other] == [True]


# -- X014 --------------------------------------------------------------------------------


def named(link: str, joint: str = "j") -> str:
    return (
        f'<robot name="r">\n  <link name="base">{INERTIAL}</link>\n'
        f'  <joint name="{joint}" type="fixed"><parent link="base"/><child link="{link}"/>'
        f'</joint>\n  <link name="{link}">{INERTIAL}</link>\n</robot>\n'
    )


def test_spaces_and_punctuation_are_warnings() -> None:
    hits = found(named("upper arm", joint="joint#2"), "X014")
    assert [(h.line, h.element, h.severity) for h in hits] == [
        (3, "/robot/joint[@name='joint#2']", Severity.WARNING),
        (4, "/robot/link[@name='upper arm']", Severity.WARNING),
    ]
    assert hits[0].message.startswith("joint name 'joint#2' contains '#'")
    assert hits[1].message.startswith("link name 'upper arm' contains a space")


def test_dots_and_dashes_only_for_isaac_in_one_note() -> None:
    text = named("link_4.0", joint="joint_6-flange")
    assert found(text, "X014") == []
    hits = found(text, "X014", targets=["isaac"])
    assert [(h.line, h.element, h.severity) for h in hits] == [
        (3, "/robot/joint[@name='joint_6-flange']", Severity.INFO)
    ]
    assert hits[0].message.startswith(
        "2 link and joint names are not USD identifiers (first: 'joint_6-flange', 'link_4.0')"
    )


def test_clean_names_and_xacro_leftovers_are_quiet() -> None:
    assert found(named("r2/left_arm", joint="j_1"), "X014") == []
    assert found(named("${prefix}arm"), "X014") == []
