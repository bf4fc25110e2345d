"""X015 repeated-element: the finding is on the later copy and names the first; each target's
effect (MuJoCo refuses, the others read the first copy), the xacro location in a macro, and
the fix that deletes the later copy (issue 29, 1)."""

from __future__ import annotations

from pathlib import Path

from tests.conftest import FIXTURES
from tests.helpers import lint_file, lint_text
from urdflint.cli import main
from urdflint.engine import config
from urdflint.model.finding import Finding, Severity

TRIFINGER = FIXTURES / "rules" / "X015" / "bad_trifinger.urdf"
BOX = '<box size="0.1 0.1 0.1"/>'
INERTIA = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'


def robot(arm: str = "", joint: str = "", head: str = "") -> str:
    """A base and an arm on a revolute joint, with ``arm`` and ``joint`` written inside."""
    return f"""<?xml version="1.0"?>
<robot name="r">{head}
  <link name="base"><collision><geometry>{BOX}</geometry></collision></link>
  <link name="arm">
    <inertial><mass value="1"/>{INERTIA}</inertial>
    {arm}
  </link>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
    {joint}
  </joint>
</robot>
"""


def x015(text: str, *targets: str) -> list[Finding]:
    return lint_text(text, select=("X015",), targets=list(targets) or ["gz-sim"])


def effects(finding: Finding) -> dict[str, str]:
    return {target: effect.consequence.key for target, effect in finding.effects}


def test_trifinger_s_second_inertial_is_the_finding_and_names_the_first() -> None:
    settings = config.Settings(targets=("mujoco", "gz-sim", "ros"), select=("X015",))
    (found,) = lint_file(TRIFINGER, settings=settings)
    assert (found.code, Path(found.path).name, found.line) == ("X015", TRIFINGER.name, 51)
    assert found.element == "/robot/link[@name='finger_tip_link']/inertial[2]"
    assert "second <inertial> (the first is on line 46)" in found.message
    assert found.severity is Severity.ERROR  # MuJoCo is a target: it refuses the model
    assert effects(found) == {"gz-sim": "tag ignored", "mujoco": "refused", "ros": "tag ignored"}
    assert found.autofix is not None and found.autofix.applicability == "unsafe"


def test_without_mujoco_differing_copies_warn_and_identical_ones_inform() -> None:
    (differ,) = x015(robot(f'<inertial><mass value="5"/>{INERTIA}</inertial>'))
    assert differ.severity is Severity.WARNING and "a second <inertial>" in differ.message
    (same,) = x015(robot(f'<inertial><mass value="1.0"/>{INERTIA}</inertial>'))
    assert same.severity is Severity.INFO and "an identical second <inertial>" in same.message
    assert effects(same) == {"gz-sim": "as written"}
    assert same.autofix is not None and same.autofix.applicability == "safe"
    (refused,) = x015(robot(f'<inertial><mass value="1.0"/>{INERTIA}</inertial>'), "mujoco")
    assert refused.severity is Severity.ERROR  # MuJoCo refuses identical copies too


def test_every_later_copy_is_reported_against_the_first() -> None:
    limits = [f'<limit lower="-{n}" upper="{n}" effort="10" velocity="1"/>' for n in (2, 3)]
    found = x015(robot(joint="\n    ".join(limits)), "mujoco")
    assert [f.element for f in found] == [
        "/robot/joint[@name='j']/limit[2]",
        "/robot/joint[@name='j']/limit[3]",
    ]
    assert ["second" in found[0].message, "third" in found[1].message] == [True, True]
    assert all("(the first is on line 10)" in f.message for f in found)


def test_a_visual_s_origin_counts_for_mujoco_only_when_it_keeps_visuals() -> None:
    visual = (
        f'<visual><origin xyz="0 0 1"/><origin xyz="0 0 2"/><geometry>{BOX}</geometry></visual>'
    )
    (discarded,) = x015(robot(visual), "mujoco")
    assert effects(discarded) == {"mujoco": "tag ignored"} and discarded.severity is Severity.INFO
    keep = '<mujoco><compiler discardvisual="false"/></mujoco>'
    (kept,) = x015(robot(visual, head=keep), "mujoco")
    assert effects(kept) == {"mujoco": "refused"} and kept.severity is Severity.ERROR


def test_copies_of_what_a_target_does_not_read_inform_there() -> None:
    twice = '<calibration rising="0.1"/><calibration rising="0.2"/>'
    (gazebo,) = x015(robot(joint=twice), "gz-sim", "mujoco")
    assert effects(gazebo) == {} and gazebo.severity is Severity.INFO
    (ros,) = x015(robot(joint=twice), "ros")
    assert effects(ros) == {"ros": "tag ignored"} and ros.severity is Severity.WARNING


def test_several_visuals_collisions_and_shapes_are_not_repeats() -> None:
    shapes = f'<collision><geometry>{BOX}<sphere radius="0.1"/></geometry></collision>'
    many = f"<visual><geometry>{BOX}</geometry></visual>" * 2 + shapes * 2
    found = lint_text(robot(many), select=("X015", "C003"), targets=["gz-sim"])
    assert {f.code for f in found} == {"C003"}  # two shapes in one <geometry>: C003's


def test_other_rules_report_only_the_first_copy() -> None:
    twice = '<safety_controller soft_lower_limit="-1" soft_upper_limit="1" k_position="1"/>' * 2
    found = lint_text(robot(joint=twice), select=("X015", "J003"), targets=["ros"])
    assert sorted((f.code, f.element) for f in found) == [
        ("J003", "/robot/joint[@name='j']/safety_controller[1]"),
        ("X015", "/robot/joint[@name='j']/safety_controller[2]"),
    ]


MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="finger" params="name parent">
    <link name="${name}_tip">
      <inertial>
        <mass value="0.031"/>
        <inertia ixx="5e-07" ixy="0" ixz="0" iyy="5e-07" iyz="0" izz="5e-07"/>
      </inertial>
      <inertial>
        <mass value="0.0092"/>
        <inertia ixx="1.55e-06" ixy="0" ixz="0" iyy="1.55e-06" iyz="0" izz="3.2e-07"/>
      </inertial>
      <xacro:default_inertial/>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}_tip"/>
      <axis xyz="1 0 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <xacro:macro name="default_inertial">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </xacro:macro>
</robot>
"""
ENTRY = """<?xml version="1.0"?>
<robot name="trifinger" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="fingers.xacro"/>
  <link name="base"/>
  <xacro:finger name="f0" parent="base"/>
  <xacro:finger name="f120" parent="base"/>
</robot>
"""


def write_xacro(folder: Path) -> Path:
    (folder / "fingers.xacro").write_text(MACRO)
    entry = folder / "trifinger.urdf.xacro"
    entry.write_text(ENTRY)
    return entry


def test_in_xacro_the_finding_is_at_the_macro_line_and_names_the_first_copy(tmp_path) -> None:
    entry = write_xacro(tmp_path)
    settings = config.Settings(targets=("mujoco",), select=("X015",))
    found = lint_file(entry, settings=settings)
    assert [(Path(f.path).name, f.line, f.element) for f in found] == [
        ("fingers.xacro", 9, "/robot/link[@name='f0_tip']/inertial[2]"),
        ("fingers.xacro", 9, "/robot/link[@name='f120_tip']/inertial[2]"),
        ("fingers.xacro", 23, "/robot/link[@name='f0_tip']/inertial[3]"),
        ("fingers.xacro", 23, "/robot/link[@name='f120_tip']/inertial[3]"),
    ]
    first = "(the first is on {}:5, in macro `finger` called from {}:{})"
    assert first.format(tmp_path / "fingers.xacro", entry, 5) in found[0].message
    assert first.format(tmp_path / "fingers.xacro", entry, 6) in found[1].message
    assert [c.macro for c in found[2].trace] == ["default_inertial", "finger"]


def test_the_fix_deletes_the_later_copy_in_the_macro_not_one_another_macro_writes(
    tmp_path, capsys
) -> None:
    entry = write_xacro(tmp_path)
    settings = config.Settings(targets=("mujoco",), select=("X015",))
    found = lint_file(entry, settings=settings)
    elsewhere = found[2]  # the third <inertial>, from macro default_inertial
    assert found[0].autofix is not None and not found[0].autofix.unavailable
    assert elsewhere.autofix is not None and elsewhere.autofix.unavailable == (
        "the later <inertial> is written in macro `default_inertial`, which may be called "
        "for other elements too: delete it by hand"
    )
    argv = ["fix", "--isolated", "--select", "X015", "--unsafe-fixes", "--exit-zero"]
    main([*argv, str(entry)])
    fixed = (tmp_path / "fingers.xacro").read_text()
    assert fixed == MACRO.replace(
        '      <inertial>\n        <mass value="0.0092"/>\n'
        '        <inertia ixx="1.55e-06" ixy="0" ixz="0" iyy="1.55e-06" iyz="0" izz="3.2e-07"/>\n'
        "      </inertial>\n",
        "",
    )
    assert entry.read_text() == ENTRY
    main([*argv, str(entry)])
    assert (tmp_path / "fingers.xacro").read_text() == fixed  # converged
    capsys.readouterr()
