"""``statics=true`` on ``POST /v1/check``: the answer carries what ``urdflint info --statics
--format json`` gives under ``statics`` for the same file (the joints' gravity loads, the
weakest joint, the payload, the base's support polygon and stability), computed in the
worker from the linted document, scrubbed, and without ``inf``/``nan`` (JSON has neither)."""

from __future__ import annotations

import json
import logging
import math
import subprocess
import sys
import zipfile
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES, ROOT

pytest.importorskip("fastapi")
pytest.importorskip("pinocchio")

ARM = FIXTURES / "rules" / "D001" / "bad.urdf"  # the shoulder cannot hold the arm (D001)
BASE = FIXTURES / "rules" / "D003" / "good.urdf"  # a mobile base that stands
TIAGO = CORPUS / "tiago" / "model.urdf"


def info(path: Path) -> dict[str, Any]:
    """``urdflint info --statics --format json --isolated path``'s ``statics``."""
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "info", "--statics", "--format", "json",
         "--isolated", str(path)],
        capture_output=True, text=True, cwd=ROOT, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    return dict(json.loads(proc.stdout)["statics"])


def answered(client: Any, path: Path, **files: Any) -> dict[str, Any]:
    sent = {"urdf": (path.name, path.read_bytes(), "application/xml"), **files}
    answer = client.post("/v1/check", files=sent, data={"statics": "true"})
    assert answer.status_code == 200, answer.text
    data = answer.json()
    assert list(data["statics"]) == [path.name]
    return dict(data["statics"][path.name])


def mesh_zip(robot: Path, target: Path) -> Path:
    """A corpus robot's ``meshes`` folder as a zip whose folders are the packages."""
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted((robot / "meshes").rglob("*")):
            if path.is_file():
                zf.write(path, path.relative_to(robot / "meshes").as_posix())
    return target


def same(found: dict[str, Any], expected: dict[str, Any]) -> None:
    """Everything but the time it took."""
    found, expected = dict(found), dict(expected)
    assert found.pop("seconds") >= 0 and expected.pop("seconds") >= 0
    assert found == expected


def test_the_joints_are_those_of_info_statics(client: Any) -> None:
    found = answered(client, ARM)
    same(found, info(ARM))
    joints = {j["name"]: j for j in found["joints"]}
    assert list(joints) == ["shoulder", "elbow"]
    shoulder = joints["shoulder"]
    assert shoulder["unit"] == "N·m" and shoulder["effort"] == 10.0
    assert shoulder["needed"] == pytest.approx(11.772, rel=1e-6)
    assert shoulder["margin"] < 1 and not shoulder["passive"]
    assert found["weakest"]["joint"] == "shoulder"
    [base] = found["sections"]
    assert base["name"] == "base" and base["data"]["mobile"] is False  # a fixed arm


def test_a_mobile_base_has_its_support_polygon(client: Any) -> None:
    found = answered(client, BASE)
    same(found, info(BASE))
    base = found["sections"][0]["data"]
    assert base["mobile"] and base["support"]["kind"] == "polygon"
    assert len(base["support"]["polygon"]) >= 3
    assert base["zero"]["margin_mm"] > 0 and base["zero"]["tipping_angle_deg"] > 0


def test_statics_only_when_asked_and_documented(client: Any) -> None:
    files = {"urdf": (ARM.name, ARM.read_bytes(), "application/xml")}
    assert "statics" not in client.post("/v1/check", files=files).json()
    refused = client.post("/v1/check", files=files, data={"statics": "perhaps"})
    assert refused.status_code == 422 and "statics" in refused.json()["detail"]
    broken = client.post(
        "/v1/check",
        content=b"<robot name='r'><link name='a'>",
        headers={"content-type": "application/xml"},
        params={"statics": "true"},
    )
    assert broken.status_code == 200 and "statics" not in broken.json()  # no model, no statics
    schema = client.get("/openapi.json").json()["paths"]
    for path in ("/v1/check", "/v1/fix"):
        assert "statics" in {p["name"] for p in schema[path]["post"]["parameters"]}
    body = schema["/v1/check"]["post"]["requestBody"]["content"]["multipart/form-data"]
    assert body["schema"]["properties"]["statics"]["type"] == "boolean"


def test_statics_are_scrubbed_and_finite(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    from urdflint.server import extras, jobs

    from urdflint.outputs import statics_info

    root = tmp_path / "files"
    root.mkdir()
    made = {"problem": f"cannot read {root}/meshes/a.stl", "margin": math.inf, "x": (math.nan, 1.0)}
    monkeypatch.setattr(statics_info, "collect", lambda doc: made)
    found = extras.statics(SimpleNamespace(ok=True), root, jobs.Scrub(root, tmp_path))
    assert found == {"problem": "cannot read meshes/a.stl", "margin": None, "x": [None, 1.0]}
    json.dumps(found, allow_nan=False)
    assert extras.statics(SimpleNamespace(ok=False), root, jobs.Scrub(root, tmp_path)) is None

    def fails(doc: Any) -> Any:
        raise ValueError("no")

    monkeypatch.setattr(statics_info, "collect", fails)
    with caplog.at_level(logging.WARNING, logger="urdflint.server.worker"):
        assert extras.statics(SimpleNamespace(ok=True), root, jobs.Scrub(root, tmp_path)) is None
    assert "the statics failed" in caplog.text  # logged; the findings are answered anyway


@pytest.mark.slow  # TIAGo: 48 joints, ~10 s with the CLI's run
@pytest.mark.skipif(not TIAGO.is_file(), reason="needs the corpus")
def test_tiago_as_info_statics_gives_it(client: Any, tmp_path: Path) -> None:
    found = answered(client, TIAGO)
    same(found, info(TIAGO))
    arm = next(j for j in found["joints"] if j["name"] == "arm_2_joint")
    assert 1 < arm["margin"] < 1.5 and found["weakest"]["joint"] == "arm_2_joint"
    base = found["sections"][0]["data"]
    assert base["mobile"] and len(base["support"]["polygon"]) >= 3
    # with its meshes (the contact links' collision read from the zip): the same joints, and
    # nothing of the server's folders anywhere
    meshes = mesh_zip(TIAGO.parent, tmp_path / "meshes.zip").read_bytes()
    zipped = answered(client, TIAGO, meshes=("meshes.zip", meshes))
    assert zipped["joints"] == found["joints"] and zipped["weakest"] == found["weakest"]
    text = json.dumps(zipped)
    assert "urdflint-" not in text and str(tmp_path) not in text
