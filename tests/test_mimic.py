"""J017 (a mimic a selected target does not enforce) and J018 (a mimic that maps the leader's
range outside the follower's limits): messages, effects per target, what exempts a follower."""

from __future__ import annotations

from pathlib import Path

from tests.conftest import FIXTURES
from urdflint.engine import config, linter

J017 = FIXTURES / "rules" / "J017"
J018 = FIXTURES / "rules" / "J018"


def lint(path: Path, code: str, targets: tuple[str, ...] = ("gazebo-classic",)) -> list:
    settings = config.Settings(select=(code,), targets=targets)
    return [f for f in linter.lint_path(path, str(path), settings).findings if f.code == code]


def test_the_message_names_every_selected_target_that_drops_the_mimic() -> None:
    (finding,) = lint(J017 / "bad.urdf", "J017", ("gazebo-classic", "mujoco", "pybullet"))
    assert finding.line == 39 and finding.element.endswith(
        "/joint[@name='right_finger_joint']/mimic"
    )
    assert finding.message == (
        "joint 'right_finger_joint' mimics 'left_finger_joint', but Gazebo Classic and PyBullet "
        "do not enforce the mimic: the follower moves on its own there"
    )
    effects = {target: effect.consequence.key for target, effect in finding.effects}
    assert effects == {
        "gazebo-classic": "tag ignored",
        "mujoco": "as written",
        "pybullet": "tag ignored",
    }
    assert str(finding.severity) == "warning"


def test_pinocchio_alone_is_info() -> None:
    (finding,) = lint(J017 / "bad.urdf", "J017", ("pinocchio", "drake"))
    assert str(finding.severity) == "info" and "but Pinocchio does not enforce" in finding.message


def test_a_mimic_plugin_or_a_transmission_drives_the_follower_in_gazebo(tmp_path: Path) -> None:
    assert lint(J017 / "good_plugin.urdf", "J017") == []
    (finding,) = lint(J017 / "good_plugin.urdf", "J017", ("gazebo-classic", "pybullet"))
    assert "but PyBullet does not enforce" in finding.message
    text = (
        (J017 / "bad.urdf")
        .read_text()
        .replace(
            "</robot>",
            '  <transmission name="t">\n'
            "    <type>transmission_interface/SimpleTransmission</type>\n"
            '    <joint name="right_finger_joint">\n'
            "      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>\n"
            '    </joint>\n    <actuator name="m"/>\n  </transmission>\n</robot>',
        )
    )
    path = tmp_path / "driven.urdf"
    path.write_text(text)
    assert lint(path, "J017") == []


def test_j018_names_the_mapped_range_and_the_limits() -> None:
    (finding,) = lint(J018 / "bad.urdf", "J018")
    assert finding.message == (
        "joint 'right_finger_joint' mimics 'left_finger_joint' (multiplier -1, offset 0): the "
        "leader's range [0, 0.04] maps to [-0.04, 0], outside the follower's limits [0, 0.04]"
    )
    (frozen,) = lint(J018 / "bad_zero.urdf", "J018")
    assert "with multiplier 0: it stays at the offset 0.01" in frozen.message
    assert frozen.line == 39
