"""``check --show-files`` and ``check --show-settings``: what a run would check, and with
which settings, without linting."""

from __future__ import annotations

import json
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, ROOT
from urdflint.cli import main
from urdflint.engine import registry

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
RRBOT = FIXTURES / "xacro" / "rrbot"


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(["check", *args])
    out, err = capsys.readouterr()
    return code, out, err


NO_SIMULATOR = "nothing in the model or its package names a simulator"


def every_rule() -> int:
    return len(registry.load_rules())


# -- --show-files -----------------------------------------------------------------------------


def test_show_files_lists_the_entry_files_of_folders_and_lints_nothing(capsys, monkeypatch) -> None:
    monkeypatch.chdir(ROOT)
    code, out, err = run(capsys, "--show-files", "fixtures/models", "fixtures/xacro/rrbot")
    assert (code, err) == (0, "")
    assert out == (
        "fixtures/models/broken_arm.urdf\n"
        "fixtures/models/example_arm.urdf\n"
        "fixtures/models/inertia_view.urdf\n"
        "fixtures/models/template_good.urdf\n"
        "fixtures/xacro/rrbot/urdf/rrbot.xacro\n"  # materials.xacro is a library it includes
    )


def test_show_files_names_the_entry_that_checks_a_library(capsys, monkeypatch) -> None:
    monkeypatch.chdir(ROOT)
    code, out, _ = run(capsys, "--show-files", "fixtures/xacro/rrbot/urdf/materials.xacro")
    assert (code, out) == (0, "fixtures/xacro/rrbot/urdf/rrbot.xacro\n")


def test_show_files_applies_changed_since(capsys, tmp_path: Path, monkeypatch) -> None:
    (tmp_path / "robots").mkdir()
    for name in ("a.urdf", "b.urdf"):
        shutil.copy(BROKEN, tmp_path / "robots" / name)
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@example.com"]
    for command in (["init", "-q"], ["add", "."], ["commit", "-q", "-m", "two"]):
        subprocess.run([*git, *command], cwd=tmp_path, check=True, capture_output=True)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robots" / "b.urdf").write_text(BROKEN.read_text() + "<!-- edited -->\n")
    assert run(capsys, "--show-files", "--changed-since", "HEAD", "robots") == (
        0,
        "robots/b.urdf\n",
        "",
    )
    (tmp_path / "robots" / "b.urdf").write_text(BROKEN.read_text())
    code, out, err = run(capsys, "--show-files", "--changed-since", "HEAD", "robots")
    assert (code, out) == (0, "")
    assert err == "urdflint: no *.urdf or *.xacro files changed since HEAD\n"


def test_show_files_reports_an_unusable_path(capsys, tmp_path: Path) -> None:
    shutil.copy(BROKEN, tmp_path / "arm.urdf")
    code, out, err = run(capsys, "--show-files", str(tmp_path / "arm.urdf"), str(tmp_path / "no"))
    assert (code, out) == (2, f"{tmp_path / 'arm.urdf'}\n")
    assert err == f"urdflint: error: {tmp_path / 'no'}: no such file or directory\n"


def test_the_modes_exclude_each_other(capsys) -> None:
    with pytest.raises(SystemExit) as exited:
        main(["check", "--show-files", "--add-noqa", str(BROKEN)])
    assert exited.value.code == 2
    assert "not allowed with argument" in capsys.readouterr().err


# -- --show-settings --------------------------------------------------------------------------


def test_show_settings_of_a_file_without_configuration(capsys, monkeypatch) -> None:
    monkeypatch.chdir(ROOT)
    code, out, err = run(
        capsys, "--show-settings", "--isolated", "--no-cache", "fixtures/models/broken_arm.urdf"
    )
    assert (code, err) == (0, "")
    assert out == textwrap.dedent(f"""\
        fixtures/models/broken_arm.urdf
          configuration     none (--isolated)
          targets           gz-sim, ros: assumed, {NO_SIMULATOR}
          select            every rule (default)
          ignore            nothing
          per-file-ignores  none matches
          rules             {every_rule()} of {every_rule()} selected for this file
          severity          as each rule says
          rule options      defaults
          fail-on           error (default)
          xacro-args        none (not a xacro file)
          package-paths     none
          srdf              found beside the file or through its package (default)
          profile           none: the N rules do not run (default)
          confirm           none: no engine loads the model (default)
          expect            nothing: P003 and P004 do not run (default)
          statics           payload: none (default)
                            gravity: 0, 0, -9.81 m/s², root link frame (default)
          stability         contact-links: found by the heuristic (default)
                            contact-tolerance: 0.01 m (default)
                            samples: 512 (default)
          cache             not used (--no-cache)
          packages          none used
        """)  # fmt: skip


STATICS = """\
[tool.urdflint.statics]
payload = "2@tool0"
gravity = [0, 0, -9.81]

[tool.urdflint.stability]
contact-links = ["wheel_left", "wheel_right"]
samples = 64
"""


def test_show_settings_of_statics_and_stability(capsys, tmp_path: Path, monkeypatch) -> None:
    """payload and gravity: the command line wins key by key over [tool.urdflint.statics];
    a configured value equal to the default is the default."""
    (tmp_path / "pyproject.toml").write_text(STATICS)
    shutil.copy(BROKEN, tmp_path / "arm.urdf")
    monkeypatch.chdir(tmp_path)
    code, out, _ = run(capsys, "--show-settings", "--no-cache", "arm.urdf")
    assert code == 0
    lines = out.splitlines()
    start = lines.index("  statics           payload: 2 kg at 'tool0' (pyproject.toml)")
    assert lines[start + 1 : start + 5] == [
        "                    gravity: 0, 0, -9.81 m/s², root link frame (default)",
        "  stability         contact-links: wheel_left, wheel_right (pyproject.toml)",
        "                    contact-tolerance: 0.01 m (default)",
        "                    samples: 64 (pyproject.toml)",
    ]
    code, out, _ = run(capsys, "--show-settings", "--no-cache", "--payload", "0.5",
                       "--gravity=9.81,0,0", "arm.urdf")  # fmt: skip
    lines = out.splitlines()
    start = lines.index(
        "  statics           payload: 0.5 kg at the end of the longest chain (command line)"
    )
    gravity = "gravity: 9.81, 0, 0 m/s², root link frame (command line)"
    assert lines[start + 1] == " " * 20 + gravity
    code, out, _ = run(capsys, "--show-settings", "--format", "json", "--no-cache",
                       "--gravity=9.81,0,0", "arm.urdf")  # fmt: skip
    [one] = json.loads(out)["files"]
    assert one["statics"] == {
        "payload": {"value": {"kg": 2.0, "link": "tool0"}, "from": "pyproject.toml"},
        "gravity": {"value": [9.81, 0.0, 0.0], "from": "command line"},
    }
    assert one["stability"] == {
        "contact-links": {"value": ["wheel_left", "wheel_right"], "from": "pyproject.toml"},
        "contact-tolerance": {"value": 0.01, "from": "default"},
        "samples": {"value": 64, "from": "pyproject.toml"},
    }


CONFIG = """\
[tool.urdflint]
ignore = ["C002"]
targets = ["mujoco"]
fail-on = "warning"

[tool.urdflint.severity]
J008 = "error"

[tool.urdflint.per-file-ignores]
"legacy/*.urdf" = ["I0", "C001"]
"other/*.urdf" = ["J"]

[tool.urdflint.package-paths]
my_meshes = "meshes"

[tool.urdflint.rules.I007]
max-ratio = 5.0
"""


@pytest.fixture
def configured(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A project with a pyproject.toml and a legacy robot whose meshes are in a package."""
    (tmp_path / "pyproject.toml").write_text(CONFIG)
    (tmp_path / "legacy").mkdir()
    text = BROKEN.read_text().replace(
        '<cylinder radius="-0.025" length="0.3"/>', '<mesh filename="package://arm_meshes/f.stl"/>'
    )
    assert "arm_meshes" in text
    (tmp_path / "legacy" / "arm.urdf").write_text(text)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_show_settings_says_where_each_value_comes_from(capsys, configured: Path) -> None:
    code, out, _ = run(
        capsys, "--show-settings", "--ignore", "G", "--fail-on", "error",
        "--package-path", "arm_meshes=meshes", "--expect-mass", "3.5", "--no-cache",
        "legacy/arm.urdf",
    )  # fmt: skip
    assert code == 0
    lines = out.splitlines()
    assert lines[0] == "legacy/arm.urdf"
    rows = {line[2:19].strip(): line[20:] for line in lines[1:] if line[2:19].strip()}
    assert rows["configuration"] == "pyproject.toml"
    assert rows["targets"] == "mujoco: configured (pyproject.toml)"
    assert rows["ignore"] == "C002 (configuration); G (command line)"
    assert rows["per-file-ignores"] == '"legacy/*.urdf" = I0, C001'
    assert rows["severity"] == "J008 = error"
    assert rows["rule options"] == "I007: {'max-ratio': 5.0}"
    assert rows["fail-on"] == "error (command line)"
    assert rows["package-paths"] == "arm_meshes = meshes (command line)"
    assert f"my_meshes = {configured / 'meshes'} (pyproject.toml)" in [x.strip() for x in lines]
    assert rows["expect"] == "mass 3.5 ± 0.07 kg (command line)"
    # the package the file uses: not there yet, so where it was looked for
    assert rows["packages"].startswith("arm_meshes: not found (looked at: package path")
    (configured / "meshes").mkdir()
    code, out, _ = run(capsys, "--show-settings", "--package-path", "arm_meshes=meshes",
                       "legacy/arm.urdf")  # fmt: skip
    assert "  packages          arm_meshes: meshes (--package-path)" in out.splitlines()


def test_show_settings_of_a_xacro_package_infers_targets_and_resolves_packages(
    capsys, tmp_path: Path, monkeypatch
) -> None:
    shutil.copytree(RRBOT, tmp_path / "rrbot_description")
    monkeypatch.chdir(tmp_path)
    code, out, _ = run(capsys, "--show-settings", "--isolated", "--xacro-arg", "camera:=false",
                       "rrbot_description/urdf/rrbot.xacro")  # fmt: skip
    assert code == 0
    lines = out.splitlines()
    start = lines.index("  targets           gazebo-classic, ros: inferred")
    assert lines[start + 1 : start + 3] == [
        "                      gazebo-classic: the plugin libgazebo_ros_control.so"
        " (rrbot_description/urdf/rrbot.gazebo:7)",
        "                      ros: a ROS package (rrbot_description)"
        " (rrbot_description/package.xml)",
    ]
    assert "  xacro-args        camera:=false" in lines
    assert lines[-1] == (
        "  packages          rrbot_description: rrbot_description (the package holding the file)"
    )


def test_show_settings_as_json(capsys, configured: Path) -> None:
    code, out, _ = run(capsys, "--show-settings", "--format", "json", "--target", "drake",
                       "legacy/arm.urdf")  # fmt: skip
    assert code == 0
    data = json.loads(out)
    assert data["version"] == 1
    [one] = data["files"]
    assert one["path"] == "legacy/arm.urdf"
    assert one["configuration"] == {"file": "pyproject.toml", "how": "found"}
    assert one["targets"] == {"names": ["drake"], "how": "given", "evidence": [],
                              "from": "command line"}  # fmt: skip
    assert one["ignore"] == {"configuration": ["C002"], "command line": []}
    assert one["per-file-ignores"] == [{"pattern": "legacy/*.urdf", "codes": ["I0", "C001"]}]
    assert one["fail-on"] == {"value": "warning", "from": "pyproject.toml"}
    assert one["cache"]["folder"] is not None
    [package] = one["packages"]
    assert package["name"] == "arm_meshes" and package["folder"] is None
    assert package["tried"]  # where it was looked for
