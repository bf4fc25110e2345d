"""Real editors as clients of ``urdflint lsp``: Debian's Neovim (0.7+), headless, with a small
Lua client (tests/editors/nvim_client.lua), and Emacs (28+) with Eglot in batch
(tests/editors/eglot_client.el): open a robot, get its diagnostics, ask the code actions of
one, apply the fix, save, and see the diagnostic go (issue 23: real clients)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES

pytestmark = pytest.mark.slow  # real editors (Neovim, Emacs)

pytest.importorskip("pygls")
NVIM = shutil.which("nvim")
EMACS = shutil.which("emacs")
CLIENT = Path(__file__).parent / "editors" / "nvim_client.lua"
EGLOT_CLIENT = Path(__file__).parent / "editors" / "eglot_client.el"
NO_EGLOT = (
    "needs Eglot: built into Emacs 29+; on Emacs 28 the GNU ELPA package "
    "(Debian 12: apt-get install elpa-eglot, or M-x package-install RET eglot)"
)


@pytest.mark.skipif(NVIM is None, reason="needs Neovim (Debian: apt-get install neovim)")
def test_neovim_shows_applies_a_fix_and_clears_the_diagnostic(tmp_path: Path) -> None:
    robot = tmp_path / "arm.urdf"
    shutil.copy(FIXTURES / "rules" / "J008" / "bad.urdf", robot)
    out = tmp_path / "report.json"
    env = {
        **os.environ,
        **_client_env(tmp_path, robot, out),
        "XDG_CONFIG_HOME": str(tmp_path / "config"),
        "XDG_DATA_HOME": str(tmp_path / "data"),
        "XDG_STATE_HOME": str(tmp_path / "state"),
    }
    done = subprocess.run(
        [str(NVIM), "--headless", "-u", "NONE", "-i", "NONE", "-c", f"luafile {CLIENT}"],
        env=env, cwd=tmp_path, capture_output=True, text=True, timeout=240, check=False,
    )  # fmt: skip
    _assert_fixed(out, robot, done)


def _client_env(tmp_path: Path, robot: Path, out: Path) -> dict[str, str]:
    return {
        "T_FILE": str(robot),
        "T_ROOT": str(tmp_path),
        "T_CODE": "J008",
        "T_OUT": str(out),
        "T_PYTHON": sys.executable,
    }


def _assert_fixed(out: Path, robot: Path, done: subprocess.CompletedProcess[str]) -> None:
    assert out.is_file(), done.stderr[-2000:]
    report = json.loads(out.read_text())
    assert report["ok"], report
    steps = {s["name"]: s["value"] for s in report["steps"]}
    assert steps["with code"] == 3  # the three J008 of the fixture
    assert any(t.startswith("Fix J008") for t in steps["actions"]), steps
    assert "Suppress J008 (non-unit-axis) with a comment" in steps["actions"]
    assert steps["fixed"] is True and steps["with code after"] == 2
    assert "0.707107 0.707107 0" in robot.read_text()  # the fix, saved by the editor


@pytest.mark.skipif(
    EMACS is None, reason="needs Emacs (Debian: apt-get install emacs-nox elpa-eglot)"
)
def test_emacs_eglot_shows_applies_a_fix_and_clears_the_diagnostic(tmp_path: Path) -> None:
    env = {**os.environ, "HOME": str(tmp_path / "home")}  # no user init, no ~/.emacs.d written
    probe = subprocess.run(
        [str(EMACS), "--batch", "-Q", "-l", str(EGLOT_CLIENT)],
        env={**env, "T_PROBE": "1"}, capture_output=True, text=True, timeout=60, check=False,
    )  # fmt: skip
    if probe.returncode != 0:
        pytest.skip(NO_EGLOT)
    robot = tmp_path / "arm.urdf"
    shutil.copy(FIXTURES / "rules" / "J008" / "bad.urdf", robot)
    out = tmp_path / "report.json"
    done = subprocess.run(
        [str(EMACS), "--batch", "-Q", "-l", str(EGLOT_CLIENT)],
        env={**env, **_client_env(tmp_path, robot, out)},
        cwd=tmp_path, capture_output=True, text=True, timeout=240, check=False,
    )  # fmt: skip
    _assert_fixed(out, robot, done)
