"""Confirmation against the real engines (``--confirm``, the E rules), per installed engine.

Each engine is used only when it is installed (``urdflint[engines]``); the others skip.
The fixtures are in ``fixtures/engines/``; what each engine does with them was observed
with mujoco 4.0.0, pybullet 3.2.7, drake 1.51.1, pin 4.1.0 and sdformat 12.3.0 (Debian's
libsdformat-dev; more in tests/test_engines_sdformat.py).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import CORPUS, FIXTURES, ROOT, needs_corpus
from tests.helpers import lint_file
from urdflint.engine import config, linter
from urdflint.engines import runner, warm

pytestmark = pytest.mark.slow  # the real engines

MODELS = FIXTURES / "engines"
ENGINES = runner.ENGINES
JOINT = "/robot/joint[@name='wrist_mount']"
WORLD = "/robot/link[@name='world']"
ARM = "/robot/link[@name='upper_arm']"
ELBOW = "/robot/joint[@name='elbow']/limit"
PLATE = "/robot/link[@name='plate']"

# fixture -> engine -> the (line, code, element) of the E findings; absent engines: none
EXPECTED: dict[str, dict[str, set[tuple[int, str, str]]]] = {
    "good_arm": {},
    "undefined_link": {e: {(28, "E001", JOINT)} for e in ENGINES},
    "negative_mass": {
        "drake": {(20, "E006", f"{ARM}/inertial"), (20, "E004", f"{ARM}/inertial")},
        "sdformat": {(19, "E001", ARM)},
    },
    "no_inertial": {"pybullet": {(19, "E006", ARM), (19, "E004", ARM)}},
    "inverted_limits": {
        "mujoco": {(13, "E003", ELBOW)},
        "pybullet": {(13, "E003", ELBOW)},
        "drake": {(2, "E005", "/robot")},
        "sdformat": {(9, "E006", "/robot/joint[@name='elbow']"), (13, "E003", ELBOW)},
    },
    "triangle_inertia": {
        "mujoco": {(2, "E001", "/robot")},
        "pybullet": {(16, "E006", PLATE), (17, "E004", f"{PLATE}/inertial")},
        "drake": {(17, "E006", f"{PLATE}/inertial"), (17, "E004", f"{PLATE}/inertial")},
        "sdformat": {(16, "E001", PLATE)},
    },
    "two_roots": {
        "pybullet": {(2, "E005", "/robot"), (3, "E006", "/robot/link[@name='base']")},
        "pinocchio": {(3, "E001", "/robot/link[@name='base']")},
        "sdformat": {(3, "E001", "/robot/link[@name='base']")},
    },
    "world_link": {
        "drake": {(3, "E002", WORLD), (3, "E006", WORLD)},
        "sdformat": {(3, "E002", WORLD)},
    },
}


def confirmed(path: Path, *engines: str) -> list:
    settings = config.Settings(confirm=engines)
    return [f for f in lint_file(path, select=("E",), settings=settings)]


def needs(engine: str):
    return pytest.mark.skipif(not runner.installed(engine), reason=f"{engine} is not installed")


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
@pytest.mark.parametrize("model", sorted(EXPECTED))
def test_each_engine_reports_what_it_does_with_the_model(engine: str, model: str) -> None:
    findings = confirmed(MODELS / f"{model}.urdf", engine)
    assert {(f.line, f.code, f.element) for f in findings} == EXPECTED[model].get(engine, set())
    label = {"mujoco": "MuJoCo", "pybullet": "PyBullet", "drake": "Drake",
             "sdformat": "sdformat (Gazebo)"}.get(engine, "Pinocchio")  # fmt: skip
    assert all(f.message.startswith(label + " ") for f in findings)


@needs("pinocchio")
def test_the_message_is_the_engines_first_line_of_reason() -> None:
    (found,) = confirmed(MODELS / "undefined_link.urdf", "pinocchio")
    assert found.message == (
        "Pinocchio refused the model: Failed to build tree: child link [gripper] of joint "
        "[wrist_mount] not found"
    )
    assert found.severity.name == "ERROR"


def test_nothing_runs_without_confirm(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(runner, "confirm", lambda *a: pytest.fail("an engine was started"))
    assert lint_file(MODELS / "undefined_link.urdf", select=("E",)) == []


def test_an_engine_that_is_not_installed_is_one_info_note(monkeypatch) -> None:
    monkeypatch.setattr(runner, "installed", lambda engine: False)
    findings = confirmed(MODELS / "undefined_link.urdf", *ENGINES)
    assert [(f.code, f.severity.name, f.element) for f in findings] == [
        ("E007", "INFO", "/robot")
    ] * len(ENGINES)
    assert findings[0].message.endswith("is not installed: the model was not loaded in it")


def test_a_probe_that_times_out_is_a_crash(monkeypatch, tmp_path: Path) -> None:
    monkeypatch.setattr(runner, "installed", lambda engine: True)
    warm.close_all()  # a new probe: its start (Drake's import) counts in the timeout
    doc = linter.load(MODELS / "good_arm.urdf", "good_arm.urdf", config.Settings())
    path = runner.write_model(doc, tmp_path)
    outcome = runner.run(doc, "drake", path, timeout=0.001)
    assert outcome.crash == "did not finish loading the model within 0.001 s"
    assert not outcome.built


def test_meshes_are_rewritten_to_absolute_paths_on_the_same_lines(tmp_path: Path) -> None:
    source = FIXTURES / "rules" / "C004" / "good.urdf"
    settings = config.load(source.parent / "config.toml")
    doc = linter.load(source, str(source), settings)
    written = runner.write_model(doc, tmp_path).read_text().splitlines()
    original = source.read_text().splitlines()
    mesh = str((source.parent / "pkg" / "meshes" / "box.obj").resolve())
    assert f'<mesh filename="{mesh}"/>' in written[25] and "package://" in original[25]
    assert written[2] == original[2] and len(written) == len(original)
    assert 'strippath="false"' in written[-1]  # MuJoCo keeps the absolute paths


@needs("mujoco")
def test_xacro_input_is_confirmed_from_its_expanded_document(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "box.obj").write_text(
        (FIXTURES / "rules" / "C004" / "meshes" / "box.obj").read_text()
    )
    arm = (MODELS / "good_arm.urdf").read_text()
    arm = arm.replace('<robot name="good_arm">', '<robot name="arm" '
                      'xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:property name="m" '
                      'value="1"/>')  # fmt: skip
    arm = arm.replace('<cylinder radius="0.03" length="0.3"/>', '<mesh filename="meshes/box.obj"/>')
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(arm)
    assert confirmed(path, "mujoco") == []  # the relative mesh was found
    path.write_text(arm.replace("meshes/box.obj", "meshes/nothere.obj"))
    (found,) = confirmed(path, "mujoco")
    assert (found.code, Path(found.path).name) == ("E001", "arm.urdf.xacro")


def test_the_command_line_option(tmp_path: Path) -> None:
    command = [sys.executable, "-m", "urdflint", "check", "--isolated", "--select", "E",
               "--format", "json", str(MODELS / "undefined_link.urdf")]  # fmt: skip
    bad = subprocess.run([*command, "--confirm", "bullet"], capture_output=True, text=True)
    assert bad.returncode == 2 and "unknown engine 'bullet'" in bad.stderr
    run = subprocess.run([*command, "--confirm", "all"], capture_output=True, text=True, cwd=ROOT)
    codes = {(f["code"], f["severity"]) for f in json.loads(run.stdout)["findings"]}
    expected = {("E001", "error") if runner.installed(e) else ("E007", "info") for e in ENGINES}
    assert codes == expected and run.returncode == (1 if ("E001", "error") in codes else 0)


def test_the_configuration_key_and_the_service() -> None:
    assert config.from_mapping({"confirm": ["all"]}).confirm == ENGINES
    assert config.from_mapping({"confirm": "drake"}).confirm == ("drake",)
    with pytest.raises(config.ConfigError, match="unknown engine 'gazebo'"):
        config.from_mapping({"confirm": ["gazebo"]})
    pytest.importorskip("fastapi")
    from urdflint.server import options as service

    # the service starts no engine on uploaded files unless started with --allow-confirm
    with pytest.raises(service.OptionError, match="--allow-confirm"):
        service.parse({"config": ['{"confirm": ["all"]}']})


# fixture -> engine -> the E003 and E004 messages, as observed (Pinocchio keeps all four)
REPLACED = {
    "inverted_limits": {
        "mujoco": "MuJoCo built joint 'elbow' without limits (the URDF gives lower=1 upper=-1)",
        "pybullet": "PyBullet built joint 'elbow' without limits (the URDF gives lower=1 upper=-1)",
        "sdformat": "sdformat (Gazebo) built joint 'elbow' with limits [-1, 1] (the URDF gives "
        "lower=1 upper=-1)",
    },
    "negative_mass": {
        "drake": "Drake uses mass 1 kg and principal moments 0.00154 0.00154 0.00154 for link "
        "'upper_arm' (the URDF gives mass -1 kg and principal moments 0.01 0.01 0.01)",
    },
    "triangle_inertia": {
        "drake": "Drake uses mass 1 kg and principal moments 0.00154 0.00154 0.00154 for link "
        "'plate' (the URDF gives mass 1 kg and principal moments 1 1 5)",
        "pybullet": "PyBullet uses mass 1 kg and principal moments 0 0 0 for link 'plate' "
        "(the URDF gives mass 1 kg and principal moments 1 1 5)",
    },
    "no_inertial": {
        "pybullet": "PyBullet uses mass 1 kg and unit inertia for link 'upper_arm' "
        "(the URDF gives none)",
    },
}


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
@pytest.mark.parametrize("model", sorted(REPLACED))
def test_replaced_limits_and_inertias_are_reported_with_both_values(engine, model) -> None:
    findings = [
        f for f in confirmed(MODELS / f"{model}.urdf", engine) if f.code in ("E003", "E004")
    ]
    expected = REPLACED[model].get(engine)
    assert [f.message for f in findings] == ([expected] if expected else [])
    assert all(f.severity.name == "WARNING" for f in findings)


# what each engine built for the inverted elbow (lower=1 upper=-1) and the slider
BUILT_LIMITS = {
    "mujoco": ("revolute", None, None),
    "pybullet": ("revolute", None, None),
    "pinocchio": ("revolute", 1.0, -1.0),
    "sdformat": ("revolute", -1.0, 1.0),  # swapped, with a warning
}


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
def test_the_probe_reports_the_limits_each_engine_built(engine: str, tmp_path: Path) -> None:
    doc = linter.load(MODELS / "inverted_limits.urdf", "inverted_limits.urdf", config.Settings())
    outcome = runner.run(doc, engine, runner.write_model(doc, tmp_path), timeout=runner.TIMEOUT)
    if engine == "drake":  # Drake aborts: Joint(): condition 'pos_lower <= pos_upper' failed
        assert outcome.crash and not outcome.built
        return
    assert outcome.limits["elbow"] == BUILT_LIMITS[engine]
    assert outcome.limits["slider"] == ("prismatic", -0.25, 0.5)
    mass, moments = outcome.inertias["carriage"]
    assert mass == pytest.approx(0.5) and moments == pytest.approx((0.001, 0.001, 0.0015))


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
def test_the_limit_and_inertia_rules_are_silent_on_healthy_robots(engine: str) -> None:
    findings = confirmed(FIXTURES / "models" / "example_arm.urdf", engine)
    assert [f for f in findings if f.code in ("E003", "E004")] == []


@needs_corpus
def test_the_limit_and_inertia_rules_are_silent_on_the_ur5() -> None:
    model = CORPUS / "ur5" / "model.urdf"
    mapping = json.loads((model.parent / "package_map.json").read_text())
    paths = {name: (model.parent / folder).resolve() for name, folder in mapping.items()}
    engines = tuple(e for e in ENGINES if runner.installed(e))
    settings = config.Settings(confirm=engines, package_paths=paths)
    findings = lint_file(model, select=("E003", "E004"), settings=settings)
    assert findings == []
