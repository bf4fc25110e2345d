"""The Pinocchio view (urdflint/physics.py) and the P rules: mass, COM, DOF, pre-checks, gates."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.engine import config, linter, physics
from urdflint.model.document import Document

pin = pytest.importorskip("pinocchio")
np = pytest.importorskip("numpy")

BOX = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'


def link(name: str, mass: float | None, xyz: str = "0 0 0.5") -> str:
    if mass is None:
        return f'  <link name="{name}"/>\n'
    return (
        f'  <link name="{name}">\n    <inertial>\n      <origin xyz="{xyz}"/>\n'
        f'      <mass value="{mass}"/>\n      {BOX}\n    </inertial>\n  </link>\n'
    )


def joint(
    name: str, kind: str, parent: str, child: str, xyz: str = "0 0 1", extra: str = ""
) -> str:
    limit = (
        '<limit lower="-3" upper="3" effort="10" velocity="1"/>'
        if kind in ("revolute", "prismatic")
        else ('<limit effort="10" velocity="1"/>' if kind == "continuous" else "")
    )
    axis = '<axis xyz="0 1 0"/>' if kind != "fixed" else ""
    return (
        f'  <joint name="{name}" type="{kind}">\n    <origin xyz="{xyz}"/>\n'
        f'    <parent link="{parent}"/>\n    <child link="{child}"/>\n    {axis}{limit}{extra}\n'
        "  </joint>\n"
    )


def robot(*parts: str, name: str = "r") -> str:
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "".join(parts) + "</robot>\n"


# The RRBot layout (gazebo_ros_demos): link "world", a fixed joint to link1, two revolute joints.
RRBOT = robot(
    link("world", None),
    joint("fixed", "fixed", "world", "link1", "0 0 0"),
    link("link1", 1.0, "0 0 1"),
    joint("joint1", "continuous", "link1", "link2", "0 0.1 1.95"),
    link("link2", 1.0, "0 0 0.45"),
    joint("joint2", "revolute", "link2", "link3", "0 0.1 0.9"),
    link("link3", 1.0, "0 0 0.45"),
    name="rrbot",
)

# A free-floating robot: the root link carries mass, a leg hangs from a revolute joint.
FLOATING = robot(
    link("base", 5.0, "0.1 0 0"),
    joint("imu_joint", "fixed", "base", "imu", "0 0 0.1"),
    link("imu", 0.1, "0 0 0"),
    joint("hip", "revolute", "base", "thigh", "0.2 0 0"),
    link("thigh", 2.0, "0 0 -0.2"),
    joint("knee", "prismatic", "thigh", "shin", "0 0 -0.4"),
    link("shin", 1.0, "0 0 -0.2"),
    name="floater",
)

MIMIC = robot(
    link("palm", 0.5, "0 0 0"),
    joint("finger1", "revolute", "palm", "f1", "0.05 0 0"),
    link("f1", 0.1, "0 0 0.05"),
    joint(
        "finger2",
        "revolute",
        "palm",
        "f2",
        "-0.05 0 0",
        '<mimic joint="finger1" multiplier="-1" offset="0.1"/>',
    ),
    link("f2", 0.1, "0 0 0.05"),
    name="gripper",
)


def doc_of(text: str, **expect: object) -> Document:
    settings = config.Settings()
    if expect:
        settings = replace(settings, expect=replace(settings.expect, **expect))
    return Document("test.urdf", text.encode(), settings=settings)


def free_flyer(text: str, q: dict[str, float] | None = None) -> tuple[float, np.ndarray]:
    """An independent computation: free-flyer root at identity, Pinocchio's own functions."""
    model = pin.buildModelFromXML(text, pin.JointModelFreeFlyer())
    data = model.createData()
    config_ = pin.neutral(model)
    for name, value in (q or {}).items():
        j = model.joints[model.getJointId(name)]
        if j.nq == 2:
            config_[j.idx_q : j.idx_q + 2] = [math.cos(value), math.sin(value)]
        else:
            config_[j.idx_q] = value
    return pin.computeTotalMass(model), pin.centerOfMass(model, data, config_)


def lint(text: str, tmp_path: Path, *args: str) -> list:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    settings = config.Settings(select=("P",))
    return linter.lint_path(path, str(path), settings).findings


# -- mass and COM -----------------------------------------------------------------------------


def test_fixed_to_world_robot_naive_total_is_wrong_urdflint_is_right() -> None:
    naive = pin.computeTotalMass(pin.buildModelFromXML(RRBOT))
    assert naive == pytest.approx(2.0)  # link1 is welded to the root and sits on the universe
    result = doc_of(RRBOT).physics
    assert result.built and result.naive_mass == pytest.approx(2.0)
    assert result.mass == pytest.approx(3.0, rel=1e-12)
    total, com = free_flyer(RRBOT)
    assert result.mass == pytest.approx(total, rel=1e-12)
    assert np.allclose(result.com, com, atol=1e-12)
    assert result.universe_links == ["world", "link1"]
    assert result.dof == 2 and result.root == "world"
    assert result.link_masses == pytest.approx({"world": 0, "link1": 1, "link2": 1, "link3": 1})


def test_p002_names_the_welded_link_as_info_when_expectations_are_set(tmp_path: Path) -> None:
    assert [f for f in lint(RRBOT, tmp_path) if f.code == "P002"] == []  # no expectation: silent
    path = tmp_path / "rrbot.urdf"
    path.write_text(RRBOT)
    for expect in ({"mass": 3.0}, {"com": (0.0, 0.0, 1.0)}):
        settings = replace(
            config.Settings(select=("P002",)), expect=replace(config.Expect(), **expect)
        )
        (finding,) = linter.lint_path(path, str(path), settings).findings
        assert finding.severity.name == "INFO" and finding.element == "/robot"
        assert "'link1' (1 kg, welded to the root link 'world')" in finding.message
        assert "2 kg, not the URDF's 3 kg" in finding.message


def test_free_floating_robot_counts_its_root_link() -> None:
    result = doc_of(FLOATING).physics
    total, com = free_flyer(FLOATING)
    assert result.mass == pytest.approx(8.1) and result.mass == pytest.approx(total)
    assert result.naive_mass == pytest.approx(3.0)
    assert np.allclose(result.com, com, atol=1e-12)
    assert result.universe_links == ["base", "imu"]


def test_com_at_a_given_configuration() -> None:
    q = {"hip": 0.7, "knee": 0.05}
    result = doc_of(FLOATING, q=q).physics
    _, com = free_flyer(FLOATING, q)
    assert np.allclose(result.com, com, atol=1e-12)
    assert not np.allclose(result.com, doc_of(FLOATING).physics.com)
    assert result.q == q


def test_continuous_joint_position_is_cos_sin() -> None:
    result = doc_of(RRBOT, q={"joint1": 1.2}).physics
    _, com = free_flyer(RRBOT, {"joint1": 1.2})
    assert np.allclose(result.com, com, atol=1e-12)


def test_mimic_joint_follows_its_leader_and_is_not_a_dof() -> None:
    result = doc_of(MIMIC, q={"finger1": 0.3}).physics
    assert result.dof == 1 and result.mimics == {"finger2": ("finger1", -1.0, 0.1)}
    assert result.q == pytest.approx({"finger1": 0.3, "finger2": -0.2})
    _, com = free_flyer(MIMIC, {"finger1": 0.3, "finger2": -0.2})
    assert np.allclose(result.com, com, atol=1e-12)
    neutral = doc_of(MIMIC).physics
    _, com0 = free_flyer(MIMIC, {"finger2": 0.1})  # the offset applies at the neutral position
    assert np.allclose(neutral.com, com0, atol=1e-12)


def test_q_problems_are_findings_not_crashes(tmp_path: Path) -> None:
    path = tmp_path / "g.urdf"
    path.write_text(MIMIC)
    settings = config.Settings(select=("P004",))
    settings = replace(settings, expect=replace(settings.expect, q={"finger2": 1, "fingr1": 1}))
    found = linter.lint_path(path, str(path), settings).findings
    messages = " | ".join(f.message for f in found)
    assert len(found) == 2 and all(f.severity.name == "ERROR" for f in found)
    assert (
        "sets revolute joint 'finger2', which mimics 'finger1'; set 'finger1' instead" in messages
    )
    assert "names joint 'fingr1', which the model does not have" in messages
    typo = next(f for f in found if "fingr1" in f.message)
    assert typo.fix == "Did you mean joint 'finger1'?"


def test_fixed_and_floating_joints_cannot_be_set() -> None:
    text = robot(
        link("base", 1.0),
        joint("float", "floating", "base", "body"),
        link("body", 1.0),
        joint("weld", "fixed", "body", "tool"),
        link("tool", 1.0),
    )
    result = doc_of(text, q={"float": 1.0, "weld": 1.0}).physics
    assert result.built and result.dof == 6
    assert sorted(p.joint for p in result.q_problems) == ["float", "weld"]
    assert "6 degrees of freedom" in next(
        p.message for p in result.q_problems if p.joint == "float"
    )


# -- guards -----------------------------------------------------------------------------------


def test_negative_mass_never_yields_nan(tmp_path: Path) -> None:
    text = FLOATING.replace('<mass value="2.0"/>', '<mass value="-2.0"/>')
    result = doc_of(text, com=(0.0, 0.0, 0.0)).physics
    assert (
        result.built
        and result.com is None
        and "'thigh' (-2 kg) has negative mass" in result.com_problem
    )
    assert not math.isnan(result.mass)
    path = tmp_path / "neg.urdf"
    path.write_text(text)
    settings = replace(
        config.Settings(select=("P004",)), expect=replace(config.Expect(), com=(0, 0, 0))
    )
    (finding,) = linter.lint_path(path, str(path), settings).findings
    assert "cannot be checked: link 'thigh' (-2 kg) has negative mass" in finding.message


def test_zero_total_mass_has_no_com() -> None:
    text = robot(link("base", None), joint("j", "revolute", "base", "arm"), link("arm", 0.0))
    result = doc_of(text).physics
    assert result.built and result.com is None and result.com_problem == "the total mass is 0 kg"


def test_refusal_cites_the_static_error_behind_it(tmp_path: Path) -> None:
    text = RRBOT.replace('effort="10" velocity="1"/>', 'effort="-1" velocity="1"/>', 1)
    result = doc_of(text).physics
    assert not result.built and not result.misread
    assert result.blocker is not None and result.blocker.code == "J010"
    (finding,) = [f for f in lint(text, tmp_path) if f.code == "P001"]
    assert finding.element == "/robot"  # J010 points at the <limit>; P001 cites it
    assert finding.severity.name == "ERROR"
    assert finding.message == (
        "Pinocchio refuses the model: joint 'joint1' has effort -1 in its <limit>, and Pinocchio "
        "uses the range -effort..effort, so min_effort > max_effort "
        "(see J010 non-positive-effort-or-velocity on line 21)"
    )
    assert "J010" in (finding.fix or "")


def test_kinematic_loops_are_never_handed_to_pinocchio(monkeypatch, tmp_path: Path) -> None:
    # pin 4.1 refuses some, builds others without a joint, and crashes on a self-parent
    calls: list[str] = []
    monkeypatch.setattr(pin, "buildModelFromXML", lambda *a, **k: calls.append("called"))
    text = RRBOT.replace(
        "</robot>",
        '<joint name="x" type="fixed"><parent link="world"/><child link="link2"/></joint></robot>',
    )
    result = doc_of(text).physics
    assert calls == [] and not result.built and result.blocker is not None
    assert result.blocker.code == "S005"
    (finding,) = [f for f in lint(text, tmp_path) if f.code == "P001"]
    assert calls == [] and finding.element == "/robot"
    assert "not given to Pinocchio because of S005 kinematic-loop" in finding.message


@pytest.mark.parametrize(
    ("change", "code", "words"),
    [
        (
            ('<mass value="1.0"/>', '<mass value="1,0"/>'),
            "X004",
            "Pinocchio misreads link 'link1': urdfdom cannot read its <inertial>, so Pinocchio "
            "holds the link with 0 kg and a zero inertia tensor (X004 on line 13",
        ),
        (
            ('<mass value="1.0"/>', "<mass/>"),
            "I012",
            "holds the link with 0 kg and a zero inertia tensor (I012 on line 13",
        ),
        (
            ('ixy="0" ', ""),
            "I012",
            "holds the link with 1 kg and a zero inertia tensor (I012 on line 14",
        ),
        (
            ('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>'),
            "J007",
            "Pinocchio misreads joint 'joint1': it builds the joint about the zero axis, so the "
            "joint cannot move (its entry of the mass matrix is 0; J007 on line 21",
        ),
    ],
)
def test_misread_models_are_built_and_reported(
    tmp_path: Path, change: tuple[str, str], code: str, words: str
) -> None:
    text = RRBOT.replace(*change, 1)
    result = doc_of(text).physics
    assert not result.built and result.misread
    assert result.blocker is not None and result.blocker.code == code
    (finding,) = [f for f in lint(text, tmp_path) if f.code == "P001"]
    assert words in finding.message and finding.severity.name == "ERROR"


def test_static_errors_pinocchio_reads_correctly_do_not_block(tmp_path: Path) -> None:
    # S008: a <mimic> naming no joint; Pinocchio ignores <mimic>, urdflint builds it as a joint
    text = MIMIC.replace('<mimic joint="finger1"', '<mimic joint="nothing"')
    result = doc_of(text).physics
    assert result.built and result.blocker is None and result.dof == 1
    assert [f for f in lint(text, tmp_path) if f.code == "P001"] == []
    planar = RRBOT.replace('type="continuous"', 'type="planar"', 1).replace(
        '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>', 1
    )  # Pinocchio ignores a planar axis
    assert doc_of(planar).physics.built


def test_defects_in_visuals_do_not_block() -> None:
    visual = (
        '<visual><geometry><box size="1 x 1"/></geometry>'
        '<material name="m"><color rgba="2 0 0 1"/></material></visual>'
    )
    text = RRBOT.replace("</inertial>\n  </link>", "</inertial>\n" + visual + "\n  </link>", 1)
    assert "1 x 1" in text
    assert doc_of(text).physics.built


def test_pinocchio_refusal_is_translated_and_names_the_element(monkeypatch) -> None:
    monkeypatch.setattr(physics, "BLOCKING", ())  # let urdfdom itself see the missing <limit>
    text = RRBOT.replace('<limit lower="-3" upper="3" effort="10" velocity="1"/>', "", 1)
    doc = doc_of(text)
    result = doc.physics
    assert not result.built and result.blocker is None
    assert result.reason == (
        "Pinocchio refuses the model: "
        "joint [joint2] is of type REVOLUTE but it does not specify limits"
    )
    assert result.element is doc.joint_map["joint2"].element


def test_pinocchio_own_checks_name_the_joint(tmp_path: Path) -> None:
    text = RRBOT.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/><dynamics friction="-2"/>', 1)
    (finding,) = [f for f in lint(text, tmp_path) if f.code == "P001"]
    assert finding.element == "/robot/joint[@name='joint1']/dynamics"
    assert "joint 'joint1' has friction -2 in its <dynamics>" in finding.message


def test_messages_drop_source_locations() -> None:
    captured = (
        "Error:   Joint [a] is of type REVOLUTE but it does not specify limits\n"
        "         at line 607 in /project/urdfdom/urdf_parser/src/joint.cpp\n"
        "Error:   joint xml is not initialized correctly\n"
        "         at line 243 in /project/urdfdom/urdf_parser/src/model.cpp\n"
        "Error:   Joint [a] is of type REVOLUTE but it does not specify limits\n"
    )
    assert physics.messages(captured) == [
        "Joint [a] is of type REVOLUTE but it does not specify limits",
        "joint xml is not initialized correctly",
    ]
    doc = doc_of(RRBOT)
    sentence, element = physics.translate(
        doc,
        "The XML stream does not contain a valid URDF model.",
        captured.replace("[a]", "[joint1]"),
    )
    assert ".cpp" not in sentence and "at line" not in sentence
    assert element is doc.joint_map["joint1"].element


def test_robot_without_links_is_refused_in_a_sentence(tmp_path: Path) -> None:
    doc = Document("r.urdf", b'<robot name="r"/>')
    assert doc.physics.reason == "Pinocchio refuses the model: no link elements found in urdf file"
    assert lint('<robot name="r"/>', tmp_path) == []  # P001 leaves it to S011 (not selected)


def test_unparsable_document_is_not_built() -> None:
    result = Document("x.urdf", b"<robot").physics
    assert not result.built and "X001" in (result.reason or "")


def test_pinocchio_output_does_not_leak(capfd: pytest.CaptureFixture[str]) -> None:
    text = RRBOT.replace(
        "</inertial>\n  </link>", "</inertial><visual><geometry/></visual></link>", 1
    )
    assert doc_of(text).physics.built
    out, err = capfd.readouterr()
    assert out == "" and err == ""


# -- expectations and the CLI gate -----------------------------------------------------------


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    path = tmp_path / "arm.urdf"
    path.write_text((FIXTURES / "models" / "example_arm.urdf").read_text())
    return path


def arm_mass() -> float:
    doc = Document("a.urdf", (FIXTURES / "models" / "example_arm.urdf").read_bytes())
    return doc.physics.mass


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    code = main(list(args))
    out, _ = capsys.readouterr()
    return code, out


def test_expect_mass_flag_gates_ci(capsys, arm: Path, tmp_path: Path) -> None:
    total = arm_mass()
    assert run(capsys, "check", "--isolated", "--expect-mass", f"{total}", str(arm))[0] == 0
    edited = tmp_path / "edited.urdf"
    edited.write_text(arm.read_text().replace('<mass value="2.0"/>', '<mass value="2.5"/>', 1))
    code, out = run(capsys, "check", "--isolated", "--expect-mass", f"{total}", str(edited))
    assert code == 1
    assert f"the total mass is {total + 0.5:.6g} kg, expected {total:.6g} kg ±" in out
    assert "(2 %)" in out and "0.5 kg too heavy" in out
    assert run(capsys, "check", "--isolated", "--expect-mass", f"{total}±0.6", str(edited))[0] == 0
    assert run(capsys, "check", "--isolated", "--expect-mass", f"{total}±20%", str(edited))[0] == 0


def test_expect_table_in_pyproject_gates_ci(capsys, arm: Path, tmp_path: Path) -> None:
    doc = Document("a.urdf", arm.read_bytes())
    com = ", ".join(repr(c) for c in doc.physics.com)
    (tmp_path / "pyproject.toml").write_text(
        f"[tool.urdflint.expect]\nmass = {doc.physics.mass}\nmass-tolerance = 0.01\n"
        f"com = [{com}]\ncom-tolerance = 0.001\n"
    )
    assert run(capsys, "check", str(arm))[0] == 0
    arm.write_text(arm.read_text().replace('<mass value="2.0"/>', '<mass value="2.2"/>', 1))
    code, out = run(capsys, "check", str(arm))
    assert code == 1 and "P003" in out and "P004" in out
    assert "m away" in out and "m ± 0.001 m" in out


def test_expect_com_flag_with_q(capsys, arm: Path) -> None:
    doc = Document("a.urdf", arm.read_bytes())
    x, y, z = doc.physics.com
    assert run(capsys, "check", "--isolated", "--expect-com", f"{x},{y},{z}", str(arm))[0] == 0
    joint_name = "elbow"
    code, out = run(
        capsys,
        "check",
        "--isolated",
        "--expect-com",
        f"{x},{y},{z}±0.0001",
        "--q",
        f"{joint_name}=1.0",
        str(arm),
    )
    assert code == 1 and f"at {joint_name}=1" in out


def test_json_has_a_models_object(capsys, arm: Path) -> None:
    _, out = run(capsys, "check", "--isolated", "--format", "json", str(arm))
    data = json.loads(out)
    model = data["models"][str(arm)]
    assert set(model) == {"name", "root", "links", "joints", "dof", "mass", "com"}
    assert model["name"] == "example_arm" and model["mass"] == pytest.approx(arm_mass())
    assert len(model["com"]) == 3 and isinstance(model["dof"], int)


def test_json_model_is_null_when_not_built(capsys, tmp_path: Path) -> None:
    path = tmp_path / "bad.urdf"
    path.write_text(RRBOT.replace('effort="10"', 'effort="-10"', 1))
    code, out = run(capsys, "check", "--isolated", "--format", "json", str(path))
    assert code == 1 and json.loads(out)["models"] == {str(path): None}


@pytest.mark.parametrize(
    ("limit", "value", "words"), [("MAX_DEPTH", 2, "3 links deep"), ("MAX_LINKS", 3, "4 links")]
)
def test_models_too_large_for_pinocchio_are_a_warning(
    monkeypatch, tmp_path: Path, limit: str, value: int, words: str
) -> None:
    # Pinocchio's parser recurses per link (a 5,000-deep chain crashes the process) and is
    # quadratic in the joint count (20,000 links: two minutes); the real limits are 200 / 2,000.
    monkeypatch.setattr(physics, limit, value)
    calls: list[str] = []
    monkeypatch.setattr(pin, "buildModelFromXML", lambda *a, **k: calls.append("called"))
    (finding,) = [f for f in lint(RRBOT, tmp_path) if f.code == "P001"]
    assert calls == [] and finding.severity.name == "WARNING" and words in finding.message
    doc = doc_of(RRBOT, mass=3.0)  # an expectation that cannot be checked fails the gate
    settings = replace(doc.settings, select=("P",))
    found = linter.lint_document(doc, settings).findings
    (gate,) = [f for f in found if f.code == "P003"]
    assert gate.severity.name == "ERROR" and "3 kg cannot be checked" in gate.message
