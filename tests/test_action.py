"""The composite GitHub Action (action.yml): valid, documented inputs, and its scripts work."""

from __future__ import annotations

import atexit
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import FIXTURES, ROOT

ACTION = ROOT / "action.yml"
MODELS = FIXTURES / "models"
DOCUMENTED = {"paths", "fail-on", "target", "baseline", "sarif-file"}
BIN = Path(sys.executable).parent
RUNNER_TEMP = Path(tempfile.mkdtemp(prefix="urdflint-runner-temp-"))  # ${{ runner.temp }}
atexit.register(shutil.rmtree, RUNNER_TEMP, ignore_errors=True)

pytestmark = pytest.mark.skipif(shutil.which("bash") is None, reason="bash is not installed")


@pytest.fixture(scope="module")
def action() -> dict[str, Any]:
    data = yaml.safe_load(ACTION.read_text())
    assert isinstance(data, dict)
    return data


def step(action: dict[str, Any], name: str) -> dict[str, Any]:
    [found] = [s for s in action["runs"]["steps"] if s.get("name") == name]
    return found


def test_action_is_a_composite_action_with_the_documented_inputs(action) -> None:
    assert action["name"] == "urdflint" and action["description"]
    assert action["runs"]["using"] == "composite"
    inputs = action["inputs"]
    assert set(inputs) >= DOCUMENTED
    assert inputs["paths"]["default"] == "." and inputs["fail-on"]["default"] == "error"
    for name, spec in inputs.items():
        assert spec.get("description"), name
        assert "default" in spec and not spec.get("required"), name
    uses = [s["uses"] for s in action["runs"]["steps"] if "uses" in s]
    assert any(u.startswith("actions/setup-python@") for u in uses)
    for s in action["runs"]["steps"]:
        if "run" in s:
            assert s["shell"] == "bash"
            # inputs reach the scripts only through env (no ${{ }} injection into shell code)
            assert "${{" not in s["run"], s["name"]


def test_every_input_reaches_a_step(action) -> None:
    text = json.dumps(action["runs"])
    for name in action["inputs"]:
        assert f"inputs.{name}" in text, name


def inputs_env(action: dict[str, Any], name: str, values: dict[str, str]) -> dict[str, str]:
    """The step's env with ``${{ inputs.X }}`` substituted (defaults unless given)."""
    env = {}
    for key, template in step(action, name)["env"].items():
        value = str(template)
        for input_name, spec in action["inputs"].items():
            given = values.get(input_name, str(spec.get("default", "")))
            value = value.replace("${{ inputs." + input_name + " }}", given)
        value = value.replace("${{ github.action_path }}", str(ROOT))
        value = value.replace("${{ runner.temp }}", str(RUNNER_TEMP))
        value = value.replace("${{ github.action_repository }}", ACTION_REPOSITORY)
        value = value.replace("${{ github.action_ref }}", ACTION_REF)
        assert "${{" not in value, key
        env[key] = value
    return env


ACTION_REPOSITORY, ACTION_REF = "someone/urdflint", "v1"  # as `uses: someone/urdflint@v1`


def run_step(
    action: dict[str, Any], name: str, values: dict[str, str], path_prefix: Path = BIN
) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, **inputs_env(action, name, values)}
    env["PATH"] = f"{path_prefix}{os.pathsep}{BIN}{os.pathsep}{env.get('PATH', '')}"
    env.pop("GITHUB_ACTIONS", None)
    return subprocess.run(
        ["bash", "-c", step(action, name)["run"]],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_the_analysis_cache_is_kept_between_runs_keyed_on_the_version(action) -> None:
    """actions/cache restores the newest cache of this urdflint version into the folder the
    run step points urdflint at; cache: false runs without one."""
    cached = step(action, "Restore urdflint's analysis cache")
    assert cached["uses"].startswith("actions/cache@") and cached["if"] == "inputs.cache == 'true'"
    assert "steps.install.outputs.version" in cached["with"]["key"]
    assert cached["with"]["restore-keys"].strip().endswith("-")
    env = step(action, "Run urdflint")["env"]
    assert env["URDFLINT_CACHE_DIR"] == cached["with"]["path"]
    done = run_step(action, "Run urdflint", {"paths": "fixtures/models/broken_arm.urdf"})
    assert done.returncode == 1, done.stderr
    assert (RUNNER_TEMP / "urdflint-cache" / "analysis-v1" / "check").is_dir()
    shutil.rmtree(RUNNER_TEMP / "urdflint-cache")
    off = run_step(action, "Run urdflint", {"paths": "fixtures/models/", "cache": "false"})
    assert off.returncode == 1 and not (RUNNER_TEMP / "urdflint-cache").exists()


def annotations(out: str) -> list[str]:
    return [line for line in out.splitlines() if line.startswith(("::error ", "::warning "))]


def test_run_step_fails_with_annotations_on_the_fixture_models(action) -> None:
    done = run_step(action, "Run urdflint", {"paths": "fixtures/models/"})
    assert done.returncode == 1, done.stderr
    found = annotations(done.stdout)
    assert found and all(" file=fixtures/models/" in a and ",line=" in a for a in found)
    assert any(a.startswith("::error ") and "broken_arm.urdf" in a for a in found)
    assert "template_good.urdf" not in "\n".join(found)


def test_run_step_honours_fail_on_target_and_several_paths(action) -> None:
    good = "fixtures/models/template_good.urdf"
    done = run_step(
        action, "Run urdflint", {"paths": f"{good}\n{good}", "fail-on": "never", "target": "gz-sim"}
    )
    assert done.returncode == 0, done.stderr
    assert "--target gz-sim" in done.stdout and "--fail-on never" in done.stdout
    done = run_step(action, "Run urdflint", {"paths": "fixtures/models/", "fail-on": "never"})
    assert done.returncode == 0 and annotations(done.stdout)


def test_run_step_writes_sarif_and_junit(action, tmp_path: Path) -> None:
    sarif, junit = tmp_path / "urdflint.sarif", tmp_path / "urdflint.xml"
    values = {"paths": "fixtures/models/", "sarif-file": str(sarif), "junit-file": str(junit)}
    done = run_step(action, "Run urdflint", values)
    assert done.returncode == 1, done.stderr
    data = json.loads(sarif.read_text())
    assert data["version"] == "2.1.0" and data["runs"][0]["results"]
    assert junit.read_text().lstrip().startswith("<")


def test_run_step_with_a_baseline_passes_until_something_new_appears(
    action, tmp_path: Path
) -> None:
    models = tmp_path / "models"
    shutil.copytree(MODELS, models)
    base = tmp_path / "urdflint-baseline.json"
    subprocess.run(
        [str(BIN / "urdflint"), "check", "--write-baseline", str(base), str(models)],
        check=True,
        capture_output=True,
    )
    done = run_step(action, "Run urdflint", {"paths": str(models), "baseline": str(base)})
    assert done.returncode == 0, done.stdout + done.stderr
    assert annotations(done.stdout) == []
    good = models / "template_good.urdf"
    good.write_text(good.read_text().replace('<mass value="', '<mass value="-', 1))
    done = run_step(action, "Run urdflint", {"paths": str(models), "baseline": str(base)})
    assert done.returncode == 1
    [annotation] = annotations(done.stdout)
    assert "template_good.urdf" in annotation and "I002" in annotation


@pytest.mark.parametrize(
    ("values", "spec"),
    [
        ({}, f"{ROOT}[model,dynamics]"),
        ({"extras": ""}, str(ROOT)),
        ({"version": "v0.4.0", "extras": "model"}, "urdflint[model]==0.4.0"),
    ],
)
def test_install_step_builds_the_pip_requirement(
    action, tmp_path: Path, values: dict[str, str], spec: str
) -> None:
    shim = tmp_path / "bin"
    shim.mkdir()
    log = tmp_path / "pip.log"
    (shim / "python").write_text(f'#!/bin/sh\nprintf "%s\\n" "$@" > "{log}"\n')
    (shim / "python").chmod(0o755)
    done = run_step(action, "Install urdflint", values, path_prefix=shim)
    assert done.returncode == 0, done.stderr
    args = log.read_text().splitlines()
    assert args[:3] == ["-m", "pip", "install"] and args[-1] == spec
    assert done.stdout.startswith("urdflint ")  # the --version check after installing


def test_sarif_rules_link_to_their_source_in_the_action_repository(action, tmp_path) -> None:
    out = tmp_path / "u.sarif"
    values = {"paths": "fixtures/models/broken_arm.urdf", "sarif-file": str(out)}
    done = run_step(action, "Run urdflint", values)
    assert done.returncode == 1, done.stderr
    rules = json.loads(out.read_text())["runs"][0]["tool"]["driver"]["rules"]
    base = f"https://github.com/{ACTION_REPOSITORY}/blob/{ACTION_REF}/rules/"
    assert rules and all(r["helpUri"].startswith(base) for r in rules)
    assert all((ROOT / r["helpUri"].removeprefix(base[: -len("rules/")])).is_file() for r in rules)
