"""--changed-since REF (alias --diff-only): lint only the URDF/xacro files changed since REF."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.cli import main

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")

GOOD = FIXTURES / "models" / "template_good.urdf"


def git(repo: Path, *args: str) -> None:
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@example.com", *args],
        cwd=repo,
        check=True,
        capture_output=True,
    )


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A repository with two committed URDFs and a README; the working directory."""
    root = tmp_path / "repo"
    (root / "robots").mkdir(parents=True)
    for name in ("a.urdf", "b.urdf"):
        shutil.copy(GOOD, root / "robots" / name)
    (root / "README.md").write_text("robots\n")
    git(root, "init", "-q")
    git(root, "add", ".")
    git(root, "commit", "-q", "-m", "two robots")
    monkeypatch.chdir(root)
    return root


def checked(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, list[str], str]:
    code = main(["check", "--format", "json", *args])
    out, err = capsys.readouterr()
    files = sorted({f["path"] for f in json.loads(out)["findings"]}) if out else []
    return code, files, err


def break_mass(path: Path) -> None:
    text = path.read_text()
    path.write_text(text.replace('<mass value="', '<mass value="-', 1))


def test_only_the_modified_file_is_linted(capsys, repo: Path) -> None:
    break_mass(repo / "robots" / "a.urdf")
    break_mass(repo / "robots" / "b.urdf")
    git(repo, "commit", "-q", "-am", "both broken")
    (repo / "robots" / "a.urdf").write_text((repo / "robots" / "a.urdf").read_text() + "\n")
    code, files, _ = checked(capsys, "--changed-since", "HEAD", "robots")
    assert code == 1 and files == ["robots/a.urdf"]
    code, files, _ = checked(capsys, "--diff-only", "HEAD~1", "robots")
    assert code == 1 and files == ["robots/a.urdf", "robots/b.urdf"]


def test_untracked_and_staged_files_count_as_changed(capsys, repo: Path) -> None:
    shutil.copy(repo / "robots" / "a.urdf", repo / "robots" / "new.urdf")
    break_mass(repo / "robots" / "new.urdf")
    break_mass(repo / "robots" / "b.urdf")
    git(repo, "add", "robots/b.urdf")
    code, files, _ = checked(capsys, "--changed-since", "HEAD", ".")
    assert code == 1 and files == ["robots/b.urdf", "robots/new.urdf"]


def test_summary_counts_only_changed_files(capsys, repo: Path) -> None:
    (repo / "robots" / "b.urdf").write_text(GOOD.read_text() + "<!-- edited -->\n")
    code = main(["check", "--format", "json", "--changed-since", "HEAD", "robots", "README.md"])
    assert code == 0
    assert json.loads(capsys.readouterr().out)["summary"]["files"] == 1


def test_explicit_file_paths_are_filtered_too(capsys, repo: Path) -> None:
    break_mass(repo / "robots" / "b.urdf")
    code, files, _ = checked(capsys, "--changed-since", "HEAD", "robots/a.urdf")
    assert code == 0 and files == []


def test_changed_xacro_below_a_folder_is_linted(capsys, repo: Path) -> None:
    xacro = repo / "robots" / "arm.urdf.xacro"
    xacro.write_text(GOOD.read_text().replace('<mass value="', '<mass value="-', 1))
    code, files, _ = checked(capsys, "--changed-since", "HEAD", "robots")
    assert code == 1 and files == ["robots/arm.urdf.xacro"]


def test_deleted_files_are_not_linted(capsys, repo: Path) -> None:
    (repo / "robots" / "b.urdf").unlink()
    code = main(["check", "--changed-since", "HEAD", "robots"])
    assert code == 0 and "no *.urdf or *.xacro files changed since HEAD" in capsys.readouterr().err


def test_nothing_changed_exits_0_with_a_note(capsys, repo: Path) -> None:
    code = main(["check", "--format", "text", "--changed-since", "HEAD", "."])
    _, err = capsys.readouterr()
    assert code == 0
    assert err.strip() == "urdflint: no *.urdf or *.xacro files changed since HEAD"


def test_unknown_ref_is_a_usage_error(capsys, repo: Path) -> None:
    code = main(["check", "--changed-since", "no-such-branch", "."])
    err = capsys.readouterr().err
    assert code == 2 and "unknown git ref 'no-such-branch'" in err
    assert len(err.strip().splitlines()) == 1


def test_option_like_ref_is_refused(capsys, repo: Path) -> None:
    assert main(["check", "--changed-since=--output=x", "."]) == 2
    assert "not a git ref" in capsys.readouterr().err


def test_outside_a_git_repository_is_a_usage_error(
    capsys, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    plain = tmp_path / "plain"
    plain.mkdir()
    shutil.copy(GOOD, plain / "a.urdf")
    monkeypatch.chdir(plain)
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(tmp_path))
    code = main(["check", "--changed-since", "HEAD", "."])
    err = capsys.readouterr().err
    assert code == 2 and "not inside a git work tree" in err


def test_write_baseline_refuses_changed_since(capsys, repo: Path) -> None:
    assert main(["check", "--changed-since", "HEAD", "--write-baseline", "b.json", "."]) == 2
    assert "--write-baseline" in capsys.readouterr().err
