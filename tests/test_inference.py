"""Targets inferred from the model and its package when none is given (issue 24, 4).

Each rule of thumb has a small fixture under fixtures/targets/; the evidence is asserted
with its file and line, and the text output's one line and JSON's ``targets`` say it.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main
from urdflint.engine import config, inference, linter

CASES = FIXTURES / "targets"


def _infer(path: Path, **settings: object) -> linter.Result:
    return linter.lint_path(path, str(path), config.Settings(**settings))  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("case", "names", "why", "line"),
    [
        ("classic_pkg/urdf", ("gazebo-classic", "ros"), "package.xml depends on gazebo_ros", None),
        ("sim_plugin", ("gz-sim",), "the plugin gz-sim-joint-state-publisher-system", 9),
        ("mujoco_block", ("mujoco",), "a <mujoco> block", 3),
        ("drake_elements", ("drake",), "<drake:collision_filter_group>", 8),
        ("pybullet_contact", ("pybullet",), "PyBullet's <contact> block", 4),
    ],
)
def test_each_rule_of_thumb_names_its_target_and_where(
    case: str, names: tuple[str, ...], why: str, line: int | None
) -> None:
    path = CASES / case / "arm.urdf"
    chosen = _infer(path).targets
    assert chosen is not None and not chosen.given and not chosen.assumed
    assert chosen.names == names
    first = next(e for e in chosen.evidence if e.target == names[0])
    assert first.why == why and first.line == line
    expected = CASES / case.split("/")[0] / "package.xml" if line is None else path
    assert Path(first.path or "").resolve() == expected.resolve()


def test_no_evidence_assumes_gazebo_sim_and_ros() -> None:
    chosen = _infer(CASES / "plain" / "arm.urdf").targets
    assert chosen is not None and chosen.assumed
    assert chosen.names == inference.ASSUMED == ("gz-sim", "ros")


def test_given_targets_replace_the_inference() -> None:
    path = CASES / "sim_plugin" / "arm.urdf"
    chosen = _infer(path, targets=("mujoco",)).targets
    assert chosen is not None and chosen.given and chosen.names == ("mujoco",)
    assert chosen.evidence == ()


def test_the_inferred_targets_decide_the_findings() -> None:
    """The same model: G002 is a Gazebo Classic warning in a package that runs Classic, an
    info where Gazebo Sim (which converts URDF colours) is assumed."""
    classic = [f for f in _infer(CASES / "classic_pkg/urdf/arm.urdf").findings if f.code == "G002"]
    plain = [f for f in _infer(CASES / "plain/arm.urdf").findings if f.code == "G002"]
    assert "Gazebo Classic ignores the colour" in classic[0].message
    assert "Gazebo Sim converts" in plain[0].message


def test_text_says_in_one_line_which_targets_and_why(capsys: pytest.CaptureFixture[str]) -> None:
    main(["check", str(CASES / "plain" / "arm.urdf")])
    lines = [x for x in capsys.readouterr().out.splitlines() if x.startswith("targets: ")]
    assert lines == [
        "targets: Gazebo Sim, ROS (KDL, MoveIt): assumed, nothing in the model or its package "
        "names a simulator (--target chooses)"
    ]
    main(["check", "--target", "mujoco", str(CASES / "plain" / "arm.urdf")])
    assert "targets: " not in capsys.readouterr().out  # given: nothing to say


def test_json_lists_the_targets_with_their_evidence(capsys: pytest.CaptureFixture[str]) -> None:
    path = CASES / "sim_plugin" / "arm.urdf"
    main(["check", "--format", "json", str(path)])
    data = json.loads(capsys.readouterr().out)
    assert data["targets"] == {
        str(path): {
            "names": ["gz-sim"],
            "how": "inferred",
            "evidence": [
                {
                    "target": "gz-sim",
                    "why": "the plugin gz-sim-joint-state-publisher-system",
                    "path": str(path),
                    "line": 9,
                }
            ],
        }
    }


def test_a_configuration_s_targets_are_given(tmp_path: Path) -> None:
    robot = tmp_path / "arm.urdf"
    robot.write_bytes((CASES / "sim_plugin" / "arm.urdf").read_bytes())
    (tmp_path / "urdflint.toml").write_text('targets = ["drake"]\n')
    settings = config.load(tmp_path / "urdflint.toml")
    chosen = linter.lint_path(robot, str(robot), settings).targets
    assert chosen is not None and chosen.given and chosen.names == ("drake",)


def test_xacro_evidence_points_into_the_macro_file() -> None:
    """A plugin written in an included xacro file is shown where it is written."""
    path = FIXTURES / "targets" / "xacro_pkg" / "urdf" / "robot.urdf.xacro"
    chosen = _infer(path).targets
    assert chosen is not None and chosen.names == ("gz-sim", "ros")
    (plugin,) = [e for e in chosen.evidence if e.target == "gz-sim"]
    assert plugin.path is not None and plugin.path.endswith("gazebo.xacro") and plugin.line == 4
