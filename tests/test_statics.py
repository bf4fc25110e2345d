"""Statics: gravity torques against effort limits (D001, D002, ``info --statics``, hover).

The hand-computed fixture is a 2-link planar arm (``fixtures/rules/D001/good.urdf``): upper
arm m1 = 2 kg, l1 = 0.5 m, forearm m2 = 1 kg, l2 = 0.4 m, centres of mass at mid-length,
both joints about y with limits ±2 rad, a massless ``tool`` frame at the forearm's end.
Level and straight, the shoulder holds τ1 = g (m1 l1/2 + m2 (l1 + l2/2)) = 1.2 g and the
elbow τ2 = g m2 l2/2 = 0.2 g, the largest over the limits.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, corpus_models, needs_corpus
from tests.helpers import expectations, lint_file, lint_text
from urdflint.cli import main
from urdflint.engine import config, statics
from urdflint.engine.statics_settings import StaticsSettings
from urdflint.model.document import Document

pin = pytest.importorskip("pinocchio")

G = 9.81
D001 = FIXTURES / "rules" / "D001"
D002 = FIXTURES / "rules" / "D002"
ARM = D001 / "good.urdf"  # shoulder effort 15 N·m, elbow 5 N·m
ARM_TEXT = ARM.read_text(encoding="utf-8")
M1, L1, M2, L2 = 2.0, 0.5, 1.0, 0.4


def loads(text: str, **given: object) -> statics.Statics:
    doc = Document("arm.urdf", text.encode(), settings=config.Settings())
    return statics.compute(doc, StaticsSettings(**given))  # type: ignore[arg-type]


def exact(text: str, gravity: tuple[float, float, float], at: dict[str, float]) -> list[float]:
    """The generalized gravity Pinocchio computes on its own at ``at`` (the others at 0)."""
    import numpy as np

    model = pin.buildModelFromXML(text)
    model.gravity = pin.Motion(np.array(gravity), np.zeros(3))
    q = pin.neutral(model)
    for name, value in at.items():
        q[model.joints[model.getJointId(name)].idx_q] = value
    return [float(t) for t in pin.computeGeneralizedGravity(model, model.createData(), q)]


# -- the engine ---------------------------------------------------------------------------


def test_the_planar_arm_holds_its_hand_computed_torques_level_and_straight() -> None:
    found = loads(ARM_TEXT)
    shoulder, elbow = found.load("shoulder"), found.load("elbow")
    tau1 = G * (M1 * L1 / 2 + M2 * (L1 + L2 / 2))
    assert shoulder.needed == pytest.approx(tau1, rel=1e-12) and tau1 == pytest.approx(11.772)
    assert shoulder.at == {"shoulder": 0.0, "elbow": 0.0}
    assert elbow.needed == pytest.approx(G * M2 * L2 / 2, rel=1e-12)
    # the bound is reached (level and straight): proven for the shoulder, whose 15 N·m is above
    assert shoulder.bound == pytest.approx(tau1, rel=1e-12) and shoulder.proven
    assert elbow.bound == pytest.approx(G * M2 * L2 / 2, rel=1e-12) and elbow.proven
    assert shoulder.margin == pytest.approx(15 / tau1)


def test_a_payload_at_the_tool_adds_its_weight_at_full_reach() -> None:
    named, default = loads(ARM_TEXT, payload=2.0, payload_link="tool"), loads(ARM_TEXT, payload=2.0)
    assert default.tool == "tool"  # the end of the longest chain
    for found in (named, default):
        assert found.load("shoulder").needed == pytest.approx(G * (1.2 + 2 * (L1 + L2)), rel=1e-12)
        assert found.load("elbow").needed == pytest.approx(G * (0.2 + 2 * L2), rel=1e-12)


def test_a_wall_mounted_arm_with_gravity_along_x() -> None:
    """Shoulder limited to ±0.5 rad, gravity along the arm at rest: the worst is the shoulder
    at its limit and the forearm across gravity, elbow = π/2 - 0.5."""
    text = ARM_TEXT.replace(
        'lower="-2" upper="2" effort="15"', 'lower="-0.5" upper="0.5" effort="15"'
    )
    found = loads(text, gravity=(9.81, 0.0, 0.0))
    shoulder = found.load("shoulder")
    best = G * ((M1 * L1 / 2 + M2 * L1) * math.sin(0.5) + M2 * L2 / 2)
    assert shoulder.needed == pytest.approx(best, rel=1e-5)
    assert abs(shoulder.at["shoulder"]) == 0.5
    assert abs(shoulder.at["elbow"]) == pytest.approx(math.pi / 2 - 0.5, abs=0.01)
    # exact at the configuration stated: Pinocchio alone gives the same torque there
    tau = exact(text, (9.81, 0.0, 0.0), shoulder.at)
    assert abs(tau[0]) == pytest.approx(shoulder.needed, rel=1e-12)
    level = loads(text)  # the same arm on the floor: level at rest
    assert level.load("shoulder").needed == pytest.approx(G * 1.2, rel=1e-12)


def test_a_mimic_joint_follows_its_leader_and_is_not_judged() -> None:
    text = ARM_TEXT.replace('lower="-2" upper="2" effort="15"', 'lower="0.5" upper="1" effort="15"')
    elbow = '<limit lower="-2" upper="2" effort="5" velocity="2"/>'
    follower = (
        '<limit lower="-3" upper="3" effort="5" velocity="2"/>\n    <mimic joint="shoulder"/>'
    )
    text = text.replace(elbow, follower)
    found = loads(text)
    assert set(found.joints) == {"shoulder"}
    # the forearm turns twice as fast: at θ, its COM is at l1 cos θ + l2/2 cos 2θ
    best = max(
        G * ((M1 * L1 / 2 + M2 * L1) * math.cos(t) + M2 * L2 / 2 * math.cos(2 * t))
        for t in (0.5 + k * 0.5 / 1000 for k in range(1001))
    )
    assert found.load("shoulder").needed == pytest.approx(best, rel=1e-9)
    assert found.load("shoulder").at == {"shoulder": 0.5}


def test_the_search_is_deterministic() -> None:
    path = FIXTURES / "models" / "example_arm.urdf"
    first, second = (loads(path.read_text(encoding="utf-8")) for _ in range(2))
    for name in first.joints:
        a, b = first.load(name), second.load(name)
        assert (a.needed, a.at) == (b.needed, b.at)


# -- D001 and D002 ------------------------------------------------------------------------


def only(findings: list, code: str) -> object:
    (found,) = [f for f in findings if f.code == code]
    return found


def test_d001_is_on_the_effort_attribute_with_the_torque_and_the_configuration() -> None:
    path = D001 / "bad.urdf"
    found = only(lint_file(path, select=("D001",)), "D001")
    ((line, _, element),) = expectations(path)
    assert (found.path, found.line, found.element) == (str(path), line, element)
    text = path.read_text(encoding="utf-8").splitlines()[line - 1]
    assert text[found.column - 1 :].startswith('effort="10"')
    assert found.message == (
        "revolute joint 'shoulder' needs 11.8 N·m to hold what it carries against gravity at "
        "shoulder=0, elbow=0, above its effort limit 10 N·m"
    )
    assert str(found.severity) == "warning"
    effects = dict(found.effects)  # the targets inferred: Gazebo Sim and ROS
    assert "DART" in effects["gz-sim"].detail and "ros_control" in effects["ros"].detail


def test_d001_s_unsafe_fix_raises_the_effort_to_the_torque_needed_with_headroom() -> None:
    found = only(lint_file(D001 / "bad.urdf", select=("D001",)), "D001")
    fix = found.autofix
    assert fix is not None and fix.applicability == "unsafe"
    assert fix.description.startswith("raise the effort limit to 15 N·m (the 11.8 N·m")
    ((edit,),) = [fix.edits]
    assert edit.text == "15"  # 11.772 × 1.25 = 14.7, rounded up to two digits


def test_d001_inside_a_macro_sits_in_the_macro_file_with_the_call() -> None:
    entry, macro = D001 / "bad_macro.xacro", D001 / "parts" / "segment.xacro"
    found = only(lint_file(entry, select=("D001",)), "D001")
    ((line, _, element),) = expectations(macro)
    assert (Path(found.path).resolve(), found.line, found.element) == (
        macro.resolve(),
        line,
        element,
    )
    ((call),) = found.trace
    assert (call.macro, Path(call.path).name, call.line) == ("segment", "bad_macro.xacro", 19)
    assert "needs 11.8 N·m" in found.message and "effort limit 10 N·m" in found.message


def test_d001_with_a_payload_names_it() -> None:
    path = D001 / "bad_payload.urdf"
    found = only(lint_file(path, select=("D001",)), "D001")
    assert found.element == "/robot/joint[@name='elbow']/limit"
    assert "needs 9.81 N·m" in found.message and "(2 kg payload at 'tool')" in found.message


def test_d001_skips_proven_passive_and_effortless_joints_and_names_a_wrong_payload_link() -> None:
    weak = ARM_TEXT.replace('effort="15"', 'effort="10"')
    assert [f.code for f in lint_text(weak, select=("D001",))] == ["D001"]
    passive = weak.replace(
        "</robot>",
        '  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="elbow"><hardwareInterface>EffortJointInterface</hardwareInterface>'
        '</joint><actuator name="m"/></transmission>\n</robot>',
    )
    assert lint_text(passive, select=("D001",)) == []  # no actuator drives the shoulder
    unknown = lint_text(ARM_TEXT, select=("D001",), statics={"payload": "1@tol"})
    (found,) = unknown
    assert (found.element, str(found.severity)) == ("/robot", "error")
    assert "'tol'" in found.message and "tool" in (found.fix or "")


def test_d002_flags_a_placeholder_and_keeps_a_strong_but_plausible_effort() -> None:
    path = D002 / "bad.urdf"
    found = only(lint_file(path, select=("D002",)), "D002")
    ((line, _, element),) = expectations(path)
    assert (found.line, found.element, str(found.severity)) == (line, element, "info")
    assert found.message == (
        "revolute joint 'elbow' has effort 10000 N·m, 2548 times what its own load can need: "
        "gravity at most 1.96 N·m in any configuration, 1.96 N·m to accelerate it at 1 g; "
        "10000 looks like a placeholder"
    )
    # 1000 N·m on the shoulder: 42 times its 23.5 N·m, under the ratio of 50
    assert lint_file(D002 / "good.urdf", select=("D002",)) == []
    stricter = lint_text((D002 / "good.urdf").read_text(), select=("D002",),
                         rules={"D002": {"ratio": 40}})  # fmt: skip
    assert [f.element for f in stricter] == ["/robot/joint[@name='shoulder']/limit"]


# -- info --statics, options --------------------------------------------------------------


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    code = main(list(args))
    out, _ = capsys.readouterr()
    return code, out


def test_info_statics_text(capsys) -> None:
    code, out = run(capsys, "info", "--isolated", "--statics", str(ARM))
    assert code == 0
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("statics"))
    assert lines[start] == (
        "statics (Pinocchio; root link 'base_link' fixed, gravity 0 0 -9.81 m/s² in its frame, "
        "no payload)"
    )
    assert lines[start + 1].split() == [
        "joint",
        "type",
        "needs",
        "bound",
        "effort",
        "margin",
        "where",
    ]
    assert lines[start + 2].split() == [
        "shoulder", "revolute", "11.8", "N·m", "11.8", "N·m", "15", "N·m", "1.27", "proven",
        "shoulder=0,", "elbow=0",
    ]  # fmt: skip
    assert lines[start + 3].split()[:10] == [
        "elbow", "revolute", "1.96", "N·m", "1.96", "N·m", "5", "N·m", "2.55", "proven",
    ]  # fmt: skip
    assert lines[start + 4] == "weakest  shoulder: margin 1.27, 15 N·m for 11.8 N·m: holds"
    assert lines[start + 5] == (
        "payload  the weakest joint allows 0.366 kg at 'tool' (end of the longest chain) at "
        "full reach (shoulder reaches its effort limit)"
    )


def test_info_statics_json(capsys) -> None:
    code, out = run(capsys, "info", "--isolated", "--statics", "--format", "json", str(ARM))
    assert code == 0
    data = json.loads(out)["statics"]
    assert data["computed"] and data["gravity"] == [0, 0, -9.81] and data["frame"] == "base_link"
    shoulder, elbow = data["joints"]
    assert shoulder["name"] == "shoulder" and shoulder["unit"] == "N·m"
    assert shoulder["needed"] == pytest.approx(11.772) and shoulder["at"] == {
        "shoulder": 0,
        "elbow": 0,
    }
    assert shoulder["effort"] == 15 and shoulder["proven"] and not shoulder["passive"]
    assert elbow["margin"] == pytest.approx(5 / 1.962)
    assert data["weakest"] == {"joint": "shoulder", "margin": pytest.approx(15 / 11.772)}
    # g (1.2 + 0.9 m) = 15 at the shoulder, before g (0.2 + 0.4 m) = 5 at the elbow
    allowed = data["allowed_payload"]
    assert allowed["mass"] == pytest.approx((15 / G - 1.2) / 0.9, rel=1e-6)
    assert (allowed["link"], allowed["joint"], allowed["already_exceeded"]) == (
        "tool",
        "shoulder",
        False,
    )


def test_cli_options_and_configuration_agree(capsys, tmp_path: Path) -> None:
    path = D001 / "bad_payload.urdf"
    configured = tmp_path / "urdflint.toml"
    configured.write_text('[statics]\npayload = "2@tool"\ngravity = [0, 0, -9.81]\n')

    def findings(*options: str) -> list[dict]:
        _, out = run(capsys, "check", "--no-cache", "--format", "json", "--select", "D001",
                        *options, str(path))  # fmt: skip
        return json.loads(out)["findings"]

    by_cli = findings("--isolated", "--payload", "2@tool", "--gravity", "0,0,-9.81")
    by_file = findings("--config", str(configured))
    assert by_cli == by_file and len(by_cli) == 1
    assert findings("--config", str(configured), "--payload", "0") == []  # the CLI wins
    wall = tmp_path / "wall.toml"
    wall.write_text("[statics]\ngravity = [9.81, 0, 0]\n")
    assert findings("--isolated", "--gravity", "9.81,0,0") == findings("--config", str(wall))
    assert findings("--isolated", "--gravity=-9.81,0,0") == []  # a leading minus takes =
    info_cli = json.loads(run(capsys, "info", "--statics", "--format", "json", "--isolated",
                              "--payload", "2@tool", str(path))[1])["statics"]  # fmt: skip
    info_file = json.loads(run(capsys, "info", "--statics", "--format", "json", "--config",
                               str(configured), str(path))[1])["statics"]  # fmt: skip
    for data in (info_cli, info_file):
        data.pop("seconds")
    assert info_cli == info_file and info_cli["payload"] == {"mass": 2.0, "link": "tool"}


def test_invalid_options_are_usage_errors(capsys) -> None:
    for option in (["--payload", "-1"], ["--payload", "2@"], ["--gravity", "0,0"]):
        with pytest.raises(SystemExit) as stop:
            main(["check", "--isolated", *option, str(ARM)])
        assert stop.value.code == 2
    with pytest.raises(config.ConfigError, match=r"statics\.mass"):
        config.from_mapping({"statics": {"mass": 2}})


def test_hover_on_a_joint_gives_its_margin() -> None:
    from urdflint.lsp import describe

    text = ARM_TEXT.replace('effort="15"', 'effort="10"')
    doc = Document("arm.urdf", text.encode(), settings=config.Settings())
    element = doc.joint_map["shoulder"].element
    shown = describe.hover(doc, [], element, "joint") or ""
    assert shown.startswith("**joint `shoulder`** (revolute)")
    assert "gravity load up to 11.8 N·m at shoulder=0, elbow=0" in shown
    assert "effort limit 10 N·m, margin 0.849" in shown


# -- real robots ---------------------------------------------------------------------------

# What D001 and D002 report on the corpus (the others report nothing), judged in the rules'
# pages: PR2's shoulders are spring-counterbalanced (its <gazebo> blocks turn gravity off for
# the arm links), Valkyrie's torso pitch needs 184 N·m leaning forward with its arms out;
# the D002 efforts are placeholders.
CORPUS_FINDINGS = {
    "pr2": {
        ("D001", "l_shoulder_lift_joint"), ("D001", "r_shoulder_lift_joint"),
        ("D002", "l_gripper_l_finger_joint"), ("D002", "r_gripper_l_finger_joint"),
        ("D002", "l_gripper_motor_slider_joint"), ("D002", "r_gripper_motor_slider_joint"),
    },
    "valkyrie": {("D001", "torsoPitch")},
    "baxter": {("D002", "head_pan")},
    "solo12": {("D002", f"{leg}_{joint}") for leg in ("FL", "FR", "HL", "HR")
               for joint in ("HAA", "HFE", "KFE")},
    "r2d2": {("D002", "head_swivel"), ("D002", "gripper_extension")},
}  # fmt: skip


@needs_corpus
@pytest.mark.parametrize("path", corpus_models(), ids=lambda p: p.parent.name)
def test_corpus_robots_get_only_the_judged_findings(path: Path) -> None:
    found = lint_file(path, select=("D001", "D002"), settings=config.Settings())
    got = {(f.code, f.element.split("'")[1]) for f in found if f.element != "/robot"}
    assert got == CORPUS_FINDINGS.get(path.parent.name, set())


@pytest.mark.slow  # every corpus robot's statics, stability and reach
@needs_corpus
@pytest.mark.parametrize("model", corpus_models(), ids=lambda p: p.parent.name)
def test_info_statics_json_of_every_corpus_robot_is_json(model: Path) -> None:
    """Panda's bounds and flags were numpy scalars once: json.dumps raised."""
    from urdflint.engine import linter
    from urdflint.outputs import info

    doc = linter.load(model, str(model), config.Settings())
    text, _ = info.render(doc, "json", statics=True)
    statics_data = json.loads(text).get("statics")
    for row in statics_data["joints"] if statics_data else []:
        assert type(row["proven"]) is bool and type(row["bound"]) is float


@pytest.mark.parametrize(
    ("option", "words"),
    [
        ("--payload=1e308@tool", "more than 1e+06 kg"),
        ("--gravity=1e308,0,0", "stronger than 1000 m/s²"),
        ("--gravity=0,0,nan", "expected X,Y,Z"),
    ],
)
def test_absurd_payload_or_gravity_is_a_usage_error_not_a_crashed_rule(
    capsys: pytest.CaptureFixture[str], option: str, words: str
) -> None:
    with pytest.raises(SystemExit) as stopped:
        main(["check", "--isolated", option, str(D001 / "bad.urdf")])
    assert stopped.value.code == 2 and words in capsys.readouterr().err


def test_a_negative_mass_leaves_the_statics_to_the_inertia_rules() -> None:
    """Gravity on a negative mass pulls upwards: no torque to judge (a planted negative mass
    on a real humanoid made the search divide by a negative total mass: U001)."""
    text = ARM_TEXT.replace('<mass value="2', '<mass value="-200', 1)
    assert text != ARM_TEXT
    found = loads(text)
    assert not found.ok and found.reason is not None and "negative" in found.reason
    codes = {f.code for f in lint_text(text)}
    assert "I002" in codes and "U001" not in codes and "D001" not in codes
