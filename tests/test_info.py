"""``urdflint info``: tree, per-link masses, totals; text and JSON; without Pinocchio too."""

from __future__ import annotations

import builtins
import json
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, ROOT
from urdflint.cli import main
from urdflint.model.document import Document
from urdflint.model.optional import install_command
from urdflint.outputs import info

ARM = FIXTURES / "models" / "example_arm.urdf"
BLOCKED = FIXTURES / "rules" / "P001" / "bad_blocked.urdf"


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str]:
    code = main(list(args))
    out, _ = capsys.readouterr()
    return code, out


def test_info_text_shows_tree_masses_and_totals(capsys) -> None:
    pytest.importorskip("pinocchio")
    code, out = run(capsys, "info", "--isolated", str(ARM))
    assert code == 0
    lines = out.splitlines()
    assert lines[0].split() == ["robot", "example_arm"]
    assert lines[1].split() == ["root", "base_footprint"]
    tree = [line for line in lines if "from '" in line or "(root)" in line]
    assert [len(line) - len(line.lstrip()) for line in tree] == [0, 2, 4, 6]
    assert "fixed 'base_joint' from 'base_footprint'" in tree[1]
    assert "revolute 'elbow' from 'upper_arm'" in tree[3]
    assert tree[1].split()[1] == "2" and tree[3].split()[1] == "0.5"
    assert "mass    3.5 kg (Pinocchio; sum of <mass> values: 3.5 kg)" in out
    assert (
        "com     0 0 0.207143 m (frame of root link 'base_footprint', neutral configuration)" in out
    )
    assert "dof     2" in out


def test_info_json_carries_the_same_data(capsys) -> None:
    pytest.importorskip("pinocchio")
    code, out = run(capsys, "info", "--isolated", "--format", "json", "--q", "elbow=0.5", str(ARM))
    assert code == 0
    data = json.loads(out)
    assert data["name"] == "example_arm" and data["root"] == "base_footprint"
    assert data["built"] is True and data["dof"] == 2
    assert data["mass"] == pytest.approx(3.5) and data["mass_urdf"] == pytest.approx(3.5)
    assert [link["name"] for link in data["links"]] == [
        "base_footprint",
        "base_link",
        "upper_arm",
        "forearm",
    ]
    assert data["links"][3] == {
        "name": "forearm",
        "depth": 3,
        "parent": "upper_arm",
        "joint": "elbow",
        "joint_type": "revolute",
        "mass": 0.5,
        "inertial": True,
    }
    assert data["configuration"] == {"elbow": 0.5}
    assert len(data["com"]) == 3 and data["com"][0] != pytest.approx(0.0)
    assert {j["name"] for j in data["joints"]} == {"base_joint", "shoulder", "elbow"}


def test_summary_is_the_check_models_entry() -> None:
    pytest.importorskip("pinocchio")
    doc = Document(str(ARM), ARM.read_bytes())
    summary = info.summary(doc)
    assert summary is not None
    assert summary == {
        "name": "example_arm",
        "root": "base_footprint",
        "links": 4,
        "joints": 3,
        "dof": 2,
        "mass": pytest.approx(3.5),
        "com": pytest.approx([0.0, 0.0, 0.207142857142857]),
    }
    assert info.summary(Document("b.urdf", BLOCKED.read_bytes())) is None


def test_model_that_cannot_be_built_exits_1(capsys) -> None:
    pytest.importorskip("pinocchio")
    code, out = run(capsys, "info", "--isolated", str(BLOCKED))
    assert code == 1
    assert "upper_arm" in out  # the tree is still shown
    assert "model not built: Pinocchio refuses the model: joint " in out
    assert "(see J010 non-positive-effort-or-velocity on line 10)" in out
    code, out = run(capsys, "info", "--isolated", "--format", "json", str(BLOCKED))
    data = json.loads(out)
    assert code == 1 and data["built"] is False and data["mass"] is None
    assert data["mass_urdf"] == pytest.approx(1.0) and "J010" in data["problem"]


def test_unknown_q_joint_exits_1(capsys) -> None:
    pytest.importorskip("pinocchio")
    code, out = run(capsys, "info", "--isolated", "--q", "elbo=1", str(ARM))
    assert code == 1 and "error: --q/expect.q names joint 'elbo'" in out


def test_not_a_urdf(capsys, tmp_path: Path) -> None:
    path = tmp_path / "x.urdf"
    path.write_text("<robot")
    code, out = run(capsys, "info", "--isolated", str(path))
    assert code == 1 and "not a usable URDF: X001" in out


def test_without_pinocchio_info_prints_tree_and_urdf_masses(capsys, monkeypatch) -> None:
    real_import = builtins.__import__

    def no_pinocchio(name: str, *args: object, **kwargs: object):  # type: ignore[no-untyped-def]
        if name == "pinocchio" or name.startswith("pinocchio."):
            raise ImportError("No module named 'pinocchio'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pinocchio)
    code, out = run(capsys, "info", "--isolated", str(ARM))
    assert code == 0
    assert "revolute 'elbow' from 'upper_arm'" in out
    assert "mass    3.5 kg (sum of <mass> values)" in out
    assert f"com, dof: need Pinocchio ({install_command('dynamics')})" in out
    assert install_command("dynamics") == f"pip install -e '{ROOT}[dynamics]'"  # a checkout
    doc = Document(str(ARM), ARM.read_bytes())
    assert info.summary(doc) is None
