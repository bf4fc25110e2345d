"""The unsafe inertia fixes (I001, I005, I006, I007): each ``fixed/`` twin removes the
rule's fixable findings, adds no error from any rule, loads in Pinocchio, and holds the
values the textbook formulas give; ``--density`` and ``rules.I001.density`` reach I001."""

from __future__ import annotations

import json
import math
import shutil
from collections import Counter
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import FIXTURES
from tests.helpers import fixture_settings, lint_text
from tests.test_fix import copy_fixture
from urdflint.cli import main
from urdflint.engine import config, linter
from urdflint.model.finding import Finding, Severity

CODES = ("I001", "I005", "I006", "I007")


def pairs() -> list:
    found = []
    for code in CODES:
        folder = FIXTURES / "rules" / code
        for expected in sorted((folder / "fixed").glob("*.urdf")):
            found.append(
                pytest.param(code, folder / expected.name, expected, id=f"{code}/{expected.name}")
            )
    return found


def fixed_copy(bad: Path, expected: Path, tmp_path: Path) -> tuple[Path, Path]:
    """The bad fixture and its fixed twin, each in a folder with the fixture's settings and
    meshes (so that relative mesh paths resolve for both)."""
    (tmp_path / "before").mkdir()
    (tmp_path / "after").mkdir()
    before = copy_fixture(bad, tmp_path / "before")
    after = copy_fixture(bad, tmp_path / "after")
    shutil.copyfile(expected, after)
    return before, after


def lint(path: Path, bad: Path) -> list[Finding]:
    return linter.lint_path(path, str(path), fixture_settings(bad)).findings


@pytest.mark.parametrize(("code", "bad", "expected"), pairs())
def test_fixed_twin_adds_no_error_and_leaves_no_fix(
    code: str, bad: Path, expected: Path, tmp_path: Path
) -> None:
    before, after = fixed_copy(bad, expected, tmp_path)
    old = Counter(f.code for f in lint(before, bad) if f.severity is Severity.ERROR)
    found = lint(after, bad)
    new = Counter(f.code for f in found if f.severity is Severity.ERROR)
    added = {c: n for c, n in new.items() if n > old.get(c, 0)}
    assert not added, [f"{f.line}: {f.code} {f.message}" for f in found if f.code in added]
    left = [f for f in found if f.code == code and f.autofix is not None]
    assert left == [], [f"{f.line}: {f.message}" for f in left]
    assert len([f for f in found if f.code == code]) < len(
        [f for f in lint(before, bad) if f.code == code]
    )


@pytest.mark.parametrize(("code", "bad", "expected"), pairs())
def test_pinocchio_builds_the_fixed_twin(
    code: str, bad: Path, expected: Path, tmp_path: Path
) -> None:
    pinocchio = pytest.importorskip("pinocchio")
    _, after = fixed_copy(bad, expected, tmp_path)
    model = pinocchio.buildModelFromUrdf(str(after))
    assert model.nq >= 1


# -- the numbers, from the formulas -----------------------------------------------------------


def box(m: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    return m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12


def cylinder(m: float, r: float, h: float) -> tuple[float, float, float]:
    side = m * (3 * r * r + h * h) / 12
    return side, side, m * r * r / 2


ROD = 1000 * math.pi * 0.04**2 * 0.3  # kg: the I001 cylinder at 1000 kg/m³
ARM = box(1.0, 0.1, 0.1, 0.3)  # ixx = iyy = (0.1² + 0.3²)/12 = 0.00833333, izz = 0.00166667
EXPECTED = {  # fixed twin: {link: (mass, com, (ixx, iyy, izz), rpy)}
    "I001/bad_collision": {
        "upper_arm": (ROD, (0, 0, 0.15), cylinder(ROD, 0.04, 0.3), None),
    },
    "I001/bad_kinematics_only": {
        "upper_arm": (3.0, (0, 0, 0.15), box(3.0, 0.1, 0.1, 0.3), None),
        "forearm": (3.0, (0, 0, 0.15), box(3.0, 0.1, 0.1, 0.3), None),
        "hand": (0.125, (0, 0, 0.025), box(0.125, 0.05, 0.05, 0.05), None),
    },
    "I001/bad_mujoco": {"upper_arm": (3.0, (0, 0, 0.15), box(3.0, 0.1, 0.1, 0.3), None)},
    "I001/bad_four_spaces": {"arm": (3.0, (0, 0, 0), box(3.0, 0.1, 0.1, 0.3), None)},
    "I005/bad": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},
    "I005/bad_welded_body": {"shell": (1.0, (0, 0, 0.15), ARM, None)},
    "I005/bad_welded": {"camera": (0.01, (0, 0, 0), (1.2e-4 / 3,) * 3, None)},  # balanced
    "I005/bad_welded_mujoco": {"camera": (0.01, (0, 0, 0), (1.2e-4 / 3,) * 3, None)},
    "I006/bad": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},
    "I006/bad_copies": {
        "upper_arm": (1.0, (0, 0, 0.15), ARM, None),
        "forearm": (0.05, (0, 0, 0.15), box(0.05, 0.1, 0.1, 0.3), None),
    },
    "I007/bad": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},
    "I007/bad_cylinder": {"upper_arm": (1.0, (0, 0, 0.15), cylinder(1.0, 0.05, 0.3), None)},
    "I007/bad_mesh": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},
    "I007/bad_mesh_hull": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},  # hull of the open box
    "I007/bad_too_small": {"upper_arm": (1.0, (0, 0, 0.15), ARM, None)},
    "I007/bad_rotated": {"upper_arm": (1.0, (0, 0, 0.15), ARM, "0 0 0")},
}


def test_every_pair_has_its_numbers() -> None:
    assert {f"{code}/{bad.stem}" for code, bad, _ in (p.values for p in pairs())} == set(EXPECTED)


@pytest.mark.parametrize("key", sorted(EXPECTED))
def test_fixed_values_match_the_formulas(key: str) -> None:
    code, name = key.split("/")
    root = etree.parse(str(FIXTURES / "rules" / code / "fixed" / f"{name}.urdf")).getroot()
    for link, (mass, com, moments, rpy) in EXPECTED[key].items():
        inertial = root.find(f"link[@name='{link}']/inertial")
        assert inertial is not None, link
        assert float(inertial.find("mass").get("value")) == pytest.approx(mass, rel=1e-5)
        origin = inertial.find("origin")
        xyz = [float(v) for v in origin.get("xyz").split()]
        assert xyz == pytest.approx(list(com), abs=1e-12)
        if rpy is not None:
            assert origin.get("rpy") == rpy
        tensor = inertial.find("inertia")
        for axis, value in zip(("ixx", "iyy", "izz"), moments, strict=True):
            assert float(tensor.get(axis)) == pytest.approx(value, rel=1e-5), (link, axis)
        for product in ("ixy", "ixz", "iyz"):
            assert float(tensor.get(product)) == 0.0


def test_box_numbers_by_hand() -> None:
    # a box 0.1 x 0.2 x 0.3 m of 2 kg: ixx = 2 (0.2² + 0.3²)/12
    assert box(2.0, 0.1, 0.2, 0.3) == pytest.approx((0.0216667, 0.0166667, 0.00833333), rel=1e-5)


# -- descriptions and options ---------------------------------------------------------------


def autofixes(path: Path, code: str, *extra: str, capsys) -> list[dict]:
    main(["check", "--isolated", "--format", "json", "--select", code, *extra, str(path)])
    found = json.loads(capsys.readouterr().out)["findings"]
    return [f["autofix"] for f in found if f.get("autofix")]


def test_descriptions_name_the_method(tmp_path: Path, capsys) -> None:
    rules = FIXTURES / "rules"
    (fix,) = autofixes(rules / "I007" / "bad.urdf", "I007", capsys=capsys)
    assert fix["applicability"] == "unsafe"
    assert "collision box at 1 kg" in fix["description"]
    assert "centre of mass is kept" in fix["description"]
    (fix,) = autofixes(rules / "I005" / "bad_welded.urdf", "I005", capsys=capsys)
    assert (
        "MuJoCo's balanceinertia: the three principal moments set to their average"
        in (fix["description"])
    )
    (fix,) = autofixes(rules / "I005" / "bad.urdf", "I005", capsys=capsys)
    assert "collision box at 1 kg" in fix["description"]
    fix = autofixes(rules / "I001" / "bad_collision.urdf", "I001", capsys=capsys)[0]
    assert "collision cylinder at 1000 kg/m³: 1.50796 kg" in fix["description"]


def test_no_fix_without_collision_geometry(capsys) -> None:
    assert autofixes(FIXTURES / "rules" / "I001" / "bad.urdf", "I001", capsys=capsys) == []


def mass_after_fix(path: Path, *extra: str) -> float:
    main(["fix", "--select", "I001", "--unsafe-fixes", "--exit-zero", *extra, str(path)])
    root = etree.parse(str(path)).getroot()
    return float(root.find("link[@name='upper_arm']/inertial/mass").get("value"))


def test_density_flag_and_option(tmp_path: Path, capsys) -> None:
    bad = FIXTURES / "rules" / "I001" / "bad_collision.urdf"
    volume = math.pi * 0.04**2 * 0.3
    path = copy_fixture(bad, tmp_path)
    flagged = mass_after_fix(path, "--isolated", "--density", "800")
    assert flagged == pytest.approx(800 * volume, rel=1e-5)
    settings = tmp_path / "urdflint.toml"
    settings.write_text("[rules.I001]\ndensity = 2700\n")
    assert config.load(settings).options("I001")["density"] == 2700
    path = copy_fixture(bad, tmp_path)
    assert mass_after_fix(path, "--config", str(settings)) == pytest.approx(2700 * volume, rel=1e-5)
    path = copy_fixture(bad, tmp_path)
    flagged = mass_after_fix(path, "--config", str(settings), "--density", "500")
    assert flagged == pytest.approx(500 * volume, rel=1e-5)  # the command line wins
    capsys.readouterr()


@pytest.mark.parametrize("value", ["0", "-3", "nan", "lots"])
def test_density_must_be_positive(value: str, tmp_path: Path, capsys) -> None:
    path = copy_fixture(FIXTURES / "rules" / "I001" / "bad_collision.urdf", tmp_path)
    with pytest.raises(SystemExit):
        main(["fix", "--unsafe-fixes", f"--density={value}", str(path)])
    assert "positive density" in capsys.readouterr().err


def test_fix_runs_only_the_selected_rules(tmp_path: Path, capsys) -> None:
    path = copy_fixture(FIXTURES / "rules" / "I007" / "bad.urdf", tmp_path)
    text = path.read_text()
    path.write_text(text.replace('izz="0.01333"', 'izz="0.02"'))  # base_link breaks A + B >= C
    main(["fix", "--isolated", "--select", "I007", "--unsafe-fixes", "--exit-zero", str(path)])
    capsys.readouterr()
    fixed = path.read_text()
    assert 'izz="0.02"' in fixed and 'ixx="0.00833333"' in fixed


TOKEN = """<robot name="r">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"/>
    </inertial>
    <collision><geometry><sphere radius="0.001"/></geometry></collision>
  </link>
</robot>
"""


def test_a_token_collision_is_not_the_body() -> None:
    # 1 kg in a 1 mm sphere (2.4e8 kg/m³): I005 balances instead of using the sphere
    (found,) = lint_text(TOKEN, select=("I005",))
    assert found.autofix is not None
    assert found.autofix.description.startswith("MuJoCo's balanceinertia")
    assert "0.004 kg·m²" in found.autofix.description  # (0.001 + 0.001 + 0.01) / 3
