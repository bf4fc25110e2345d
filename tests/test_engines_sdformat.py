"""``--confirm sdformat``: Gazebo's URDF converter (libsdformat12) in its compiled probe.

The tests that load models need ``pkg-config sdformat12`` and ``g++`` (Debian:
``apt-get install libsdformat-dev``) and skip without them; the probe is compiled once per
session (into the usual cache, ``~/.cache/urdflint/``, where later sessions find it).
What sdformat 12.3 does with each planted defect is in the E rules' docstrings; the
measurements are the cases below.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.engine import config, linter
from urdflint.engines import runner, sdformat

pytestmark = pytest.mark.slow  # sdformat, compiled on first use

MODELS = FIXTURES / "engines"
INERTIA = '<inertia ixx="{i}" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/>'


def _available() -> str | None:
    """Why sdformat cannot run here (``None``: it can)."""
    if shutil.which("g++") is None:
        return "g++ is not installed"
    if shutil.which("pkg-config") is None:
        return "pkg-config is not installed"
    if subprocess.run(["pkg-config", "--exists", sdformat.PACKAGE]).returncode != 0:
        return f"pkg-config does not know {sdformat.PACKAGE} (apt-get install libsdformat-dev)"
    return None


@pytest.fixture(scope="session")
def probe() -> Path:
    """The compiled probe (built once, or found in the cache)."""
    missing = _available()
    if missing:
        pytest.skip(missing)
    try:
        return sdformat.binary()
    except sdformat.Unavailable as exc:
        pytest.skip(f"sdformat's probe did not compile: {exc}")


def link(name: str, mass: str | None = "1", inertia: str = "0.01", extra: str = "") -> str:
    inertial = (
        ""
        if mass is None
        else f'<inertial><origin xyz="0.01 0.02 0.03" rpy="0.1 0.2 0.3"/><mass value="{mass}"/>'
        f"{INERTIA.format(i=inertia)}</inertial>"
    )
    return f'<link name="{name}">{inertial}{extra}</link>\n'


def joint(name: str, parent: str, child: str, kind: str = "revolute", rpy: str = "0 0 0") -> str:
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind != "fixed" else ""
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="0.1 0 0.2" rpy="{rpy}"/><axis xyz="0 0 1"/>{limit}</joint>\n'
    )


def write(tmp_path: Path, *parts: str) -> Path:
    path = tmp_path / "robot.urdf"
    path.write_text('<?xml version="1.0"?>\n<robot name="r">\n' + "".join(parts) + "</robot>\n")
    return path


def confirmed(path: Path) -> list:
    return lint_file(path, select=("E",), settings=config.Settings(confirm=("sdformat",)))


def found(path: Path) -> set[tuple[int, str, str]]:
    return {(f.line, f.code, f.element) for f in confirmed(path)}


def test_a_negative_mass_is_refused_on_its_link(probe: Path, tmp_path: Path) -> None:
    path = write(tmp_path, link("base"), joint("j1", "base", "arm"), link("arm", mass="-1"))
    (finding,) = confirmed(path)
    assert (finding.code, finding.line, finding.element) == ("E001", 5, "/robot/link[@name='arm']")
    assert finding.message == (
        "sdformat (Gazebo) refused the model: A link named arm has invalid inertia."
    )
    assert finding.severity.name == "ERROR" and finding.engine == "sdformat"
    assert found(MODELS / "negative_mass.urdf") == {(19, "E001", "/robot/link[@name='upper_arm']")}


def test_a_massless_moving_link_is_dropped_with_what_hangs_below_it(probe, tmp_path) -> None:
    path = write(
        tmp_path,
        link("base"),
        joint("j1", "base", "arm"),
        link("arm", mass=None),  # no <inertial>: sdformat drops it, j1, hand and tool
        joint("j2", "arm", "hand"),
        link("hand"),
        joint("mount", "hand", "tool", "fixed"),
        link("tool", mass="0.2"),
    )
    messages = {f.element: f.message for f in confirmed(path) if f.code == "E002"}
    assert messages == {
        "/robot/link[@name='arm']": "sdformat (Gazebo) built no body for link 'arm': it has no "
        "mass, and its joint 'j1' is not in the model either",
        "/robot/link[@name='hand']": "sdformat (Gazebo) built no body for link 'hand': its 1 kg "
        "are not in the model",
        "/robot/link[@name='tool']": "sdformat (Gazebo) built no body for link 'tool': its 0.2 "
        "kg are not in the model",
    }
    zero = write(tmp_path, link("base"), joint("j1", "base", "arm"), link("arm", mass="0"))
    assert found(zero) == {(5, "E002", "/robot/link[@name='arm']")}


def test_fixed_joint_lumping_is_neither_a_dropped_link_nor_a_replaced_inertia(
    probe, tmp_path
) -> None:
    path = write(
        tmp_path,
        link("base"),
        joint("mount_base", "base", "plate", "fixed", rpy="0.3 0 0"),
        link("plate", mass="0.5", inertia="0.002"),
        joint("j1", "base", "arm"),
        link("arm", mass="1.5", inertia="0.02"),
        joint("mount", "arm", "tool", "fixed", rpy="0 0.4 1.2"),  # lumped, rotated and offset
        link("tool", mass="0.2", inertia="0.001"),
        joint("frame", "tool", "sensor", "fixed"),  # a massless frame lumped twice
        link("sensor", mass=None),
        joint("j2", "arm", "hand"),
        link("hand", mass=None),  # no inertial, but the welded finger gives it mass
        joint("weld", "hand", "finger", "fixed"),
        link("finger", mass="0.1", inertia="0.0001"),
    )
    assert confirmed(path) == []
    doc = linter.load(path, str(path), config.Settings())
    (tmp_path / "out").mkdir()
    outcome = runner.run(doc, "sdformat", runner.write_model(doc, tmp_path / "out"), 60.0)
    assert outcome.built and set(outcome.bodies) == {"base", "arm", "hand"}
    assert outcome.inertias["arm"][0] == pytest.approx(1.7)
    assert confirmed(FIXTURES / "models" / "example_arm.urdf") == []
    assert found(MODELS / "good_arm.urdf") == set()


def test_a_preserved_fixed_joint_keeps_its_link(probe: Path, tmp_path: Path) -> None:
    path = write(
        tmp_path,
        link("base"),
        joint("j1", "base", "arm"),
        link("arm"),
        joint("mount", "arm", "tool", "fixed"),
        link("tool", mass="0.2", inertia="0.001"),
        '<gazebo reference="mount"><preserveFixedJoint>true</preserveFixedJoint></gazebo>\n',
    )
    doc = linter.load(path, str(path), config.Settings())
    (tmp_path / "out").mkdir()
    outcome = runner.run(doc, "sdformat", runner.write_model(doc, tmp_path / "out"), 60.0)
    assert outcome.bodies == ("base", "arm", "tool") and "mount" in outcome.joints
    assert confirmed(path) == []


def test_inverted_limits_are_swapped_with_a_warning(probe: Path) -> None:
    findings = confirmed(MODELS / "inverted_limits.urdf")
    assert {(f.code, f.message) for f in findings} == {
        ("E006", "sdformat (Gazebo) warns: urdf2sdf: revolute joint [elbow] with limits: "
         "lowStop[1] > highStop[-1], switching the two."),
        ("E003", "sdformat (Gazebo) built joint 'elbow' with limits [-1, 1] (the URDF gives "
         "lower=1 upper=-1)"),
    }  # fmt: skip


def test_sdformat_does_not_write_in_the_users_home(probe, tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(sdformat.cache_dir().parent))
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert found(MODELS / "good_arm.urdf") == set()
    assert not (tmp_path / "home").exists()


# -- the compile cache (no sdformat needed: the library and the compiler are stand-ins) --


@pytest.fixture
def fake(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """A pretend sdformat and a pretend g++ (a shell script), a cache in ``tmp_path``."""
    compiler = tmp_path / "fake-g++"
    compiler.write_text('#!/bin/sh\necho "fake" > "$3"\n')  # g++ -O1 -o OUT ...
    compiler.chmod(0o755)
    monkeypatch.setenv("CXX", str(compiler))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setattr(sdformat, "library", lambda: ("12.3.0", ("-lsdformat12",)))
    monkeypatch.setattr(sdformat, "_FAILURE", [])
    return compiler


def test_the_probe_is_compiled_once_into_the_cache(fake: Path, tmp_path: Path) -> None:
    assert sdformat.installed()
    assert not any((tmp_path / "cache").glob("**/*"))  # installed() compiles nothing
    built = sdformat.binary()
    assert built.parent == tmp_path / "cache" / "urdflint"
    assert built.name.startswith("sdformat_probe-12.3.0-")
    fake.write_text("#!/bin/sh\nexit 1\n")  # a second compile would fail
    assert sdformat.binary() == built
    assert [p.name for p in built.parent.iterdir()] == [built.name]  # no temporary left


def test_a_compile_failure_is_a_not_installed_note_with_the_reason(fake, tmp_path) -> None:
    fake.write_text(
        "#!/bin/sh\necho 'probe.cc:3:1: error: sdf/Root.hh: No such file' >&2\nexit 1\n"
    )
    findings = confirmed(MODELS / "good_arm.urdf")
    assert [(f.code, f.severity.name, f.message) for f in findings] == [
        ("E007", "INFO", "sdformat (Gazebo): its probe did not compile (probe.cc:3:1: error: "
         "sdf/Root.hh: No such file), so it is not installed: the model was not loaded in it"),
    ]  # fmt: skip
    assert "libsdformat-dev" in (findings[0].fix or "")
    assert not sdformat.installed()  # not retried in this process
    assert not any((tmp_path / "cache" / "urdflint").iterdir())


def test_nothing_is_compiled_unless_sdformat_is_asked_for(fake, monkeypatch) -> None:
    monkeypatch.setattr(sdformat, "_compile", lambda target: pytest.fail("compiled"))
    assert runner.installed("sdformat")
    settings = config.Settings(confirm=("pinocchio",))
    lint_file(MODELS / "undefined_link.urdf", select=("E",), settings=settings)
    assert lint_file(MODELS / "undefined_link.urdf", select=("E",)) == []
