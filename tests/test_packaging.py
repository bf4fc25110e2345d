"""The wheel installs urdflint.rules and urdflint.server, never top-level rules/server."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.conftest import ROOT


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> zipfile.ZipFile:
    out = tmp_path_factory.mktemp("wheel")
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(out), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    if proc.returncode != 0:
        pytest.skip(f"cannot build a wheel here: {proc.stderr.strip().splitlines()[-1:]}")
    return zipfile.ZipFile(next(Path(out).glob("urdflint-*.whl")))


@pytest.mark.slow  # builds the wheel
def test_wheel_layout(wheel: zipfile.ZipFile) -> None:
    names = wheel.namelist()
    tops = {n.split("/")[0] for n in names if not n.startswith("urdflint-")}
    assert tops == {"urdflint"}
    assert "urdflint/rules/inertial/i005_triangle_inequality.py" in names
    assert "urdflint/server/__init__.py" in names
    assert "urdflint/server/app.py" in names
    assert "urdflint/server/static/index.html" in names  # the web page ships with the service
    assert "urdflint/fixtures/rules/I005/bad.urdf" in names  # `urdflint explain` examples
    assert "urdflint/data/gazebo-classic-materials.txt" in names
    entry = wheel.read(next(n for n in names if n.endswith("entry_points.txt"))).decode()
    assert "urdflint = urdflint.cli:main" in entry
