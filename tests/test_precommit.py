"""The published pre-commit hook, run for real with ``pre-commit try-repo``.

This installs the hook's own environment from this checkout (pip, network to
PyPI for lxml), so it takes a while; it is skipped when pre-commit or git is
missing.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from tests.conftest import FIXTURES, ROOT

PRE_COMMIT = shutil.which("pre-commit") or str(Path(sys.executable).parent / "pre-commit")
pytestmark = pytest.mark.skipif(
    not Path(PRE_COMMIT).exists() or shutil.which("git") is None, reason="pre-commit or git missing"
)


def test_manifest_declares_light_and_full_hooks() -> None:
    hooks = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}
    assert set(hooks) == {"urdflint", "urdflint-full"}
    for hook in hooks.values():
        assert hook["entry"] == "urdflint check"
        assert hook["language"] == "python"
    assert "additional_dependencies" not in hooks["urdflint"]
    assert any(dep.startswith("pin") for dep in hooks["urdflint-full"]["additional_dependencies"])


def _git(cwd: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True)


@pytest.mark.slow  # pre-commit builds its own environment
def test_try_repo_fails_on_broken_and_passes_on_clean(tmp_path: Path) -> None:
    repo = tmp_path / "robot"
    repo.mkdir()
    _git(repo, "init", "-q")
    _git(repo, "config", "user.email", "t@example.invalid")
    _git(repo, "config", "user.name", "t")
    shutil.copy(FIXTURES / "models" / "broken_arm.urdf", repo / "broken.urdf")
    shutil.copy(FIXTURES / "models" / "example_arm.urdf", repo / "clean.urdf")
    _git(repo, "add", ".")
    env = {**os.environ, "PRE_COMMIT_HOME": str(tmp_path / "cache"), "PRE_COMMIT_COLOR": "never"}
    env.pop("GITHUB_ACTIONS", None)

    def run(name: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [PRE_COMMIT, "try-repo", str(ROOT), "urdflint", "--files", name],
            cwd=repo,
            env=env,
            capture_output=True,
            text=True,
            timeout=900,
        )

    broken = run("broken.urdf")
    assert broken.returncode == 1, broken.stdout + broken.stderr
    assert "Failed" in broken.stdout
    assert "broken.urdf:" in broken.stdout and "error" in broken.stdout
    clean = run("clean.urdf")
    assert clean.returncode == 0, clean.stdout + clean.stderr
    assert "Passed" in clean.stdout
