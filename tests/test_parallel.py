"""``--jobs N``: the same report as a serial run, in the same order; progress only on a tty."""

from __future__ import annotations

import io
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, ROOT
from urdflint.cli import parallel

CMD = [sys.executable, "-m", "urdflint", "check", "--isolated", "--exit-zero"]


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Twenty bad fixture files of different families, one unreadable name among them."""
    out = tmp_path_factory.mktemp("many")
    codes = sorted(p.name for p in (FIXTURES / "rules").iterdir() if (p / "bad.urdf").is_file())
    for code in codes[::3][:20]:
        shutil.copy(FIXTURES / "rules" / code / "bad.urdf", out / f"{code}.urdf")
    return out


def run(*args: str, stdin: bytes | None = None) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run([*CMD, *args], capture_output=True, cwd=ROOT, input=stdin, check=False)


@pytest.mark.parametrize("fmt", ["text", "json", "sarif"])
def test_two_processes_report_exactly_what_one_does(folder: Path, fmt: str) -> None:
    serial = run("--format", fmt, "--jobs", "1", str(folder))
    pooled = run("--format", fmt, "--jobs", "2", str(folder))
    assert serial.returncode == pooled.returncode == 0
    assert serial.stdout, serial.stderr
    assert pooled.stdout == serial.stdout
    assert pooled.stderr == serial.stderr == b""  # not a terminal: no progress line


def test_matrix_and_a_missing_file_keep_their_order(folder: Path) -> None:
    files = sorted(str(p) for p in folder.glob("*.urdf"))
    args = ("--matrix", "--format", "json", files[3], str(folder / "missing.urdf"), files[0])
    serial, pooled = run(*args, "-j", "1"), run(*args, "-j", "2")
    assert pooled.stdout == serial.stdout
    assert pooled.stderr == serial.stderr
    assert b"missing.urdf" in serial.stderr
    assert serial.returncode == pooled.returncode == 2


def test_stdin_among_files_with_two_processes(folder: Path) -> None:
    data = (FIXTURES / "rules" / "I005" / "bad.urdf").read_bytes()
    first = sorted(folder.glob("*.urdf"))[0]
    args = ("--format", "json", "--stdin-filename", "piped.urdf", str(first), "-")
    serial, pooled = run(*args, "-j", "1", stdin=data), run(*args, "-j", "2", stdin=data)
    assert pooled.stdout == serial.stdout
    assert b'"path": "piped.urdf"' in pooled.stdout
    assert b'"I005"' in pooled.stdout


def test_fix_with_two_processes_fixes_every_file(tmp_path: Path) -> None:
    for name in ("a", "b", "c"):
        shutil.copy(FIXTURES / "rules" / "J008" / "bad.urdf", tmp_path / f"{name}.urdf")
    done = subprocess.run(
        [sys.executable, "-m", "urdflint", "fix", "--isolated", "-j", "2", str(tmp_path)],
        capture_output=True,
        cwd=ROOT,
        check=False,
    )
    fixed = (FIXTURES / "rules" / "J008" / "fixed" / "bad.urdf").read_bytes()
    assert all((tmp_path / f"{n}.urdf").read_bytes() == fixed for n in "abc"), done.stderr


@pytest.mark.parametrize("value", ["0", "-1", "two"])
def test_jobs_must_be_a_positive_number(value: str) -> None:
    done = run("--jobs", value, str(FIXTURES / "models" / "example_arm.urdf"))
    assert done.returncode == 2
    assert b"--jobs" in done.stderr


def test_default_is_one_process_for_a_few_files_and_every_cpu_for_many() -> None:
    assert parallel.jobs_for(None, 3) == 1
    assert parallel.jobs_for(None, 200) == parallel.cpu_count()
    assert parallel.jobs_for(8, 3) == 3  # never more processes than files
    assert parallel.jobs_for(2, 200) == 2


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_shows_on_a_terminal_once_the_run_is_long() -> None:
    stream = Terminal()
    bar = parallel.Progress(4, stream)
    bar.step()
    assert stream.getvalue() == ""  # the first second: silent
    bar.started -= 2
    bar.step()
    assert "checked 2/4 files" in stream.getvalue()
    bar.close()
    assert stream.getvalue().endswith("\r\x1b[K")


def test_progress_is_silent_when_stderr_is_not_a_terminal() -> None:
    stream = io.StringIO()
    bar = parallel.Progress(4, stream)
    bar.started -= 2
    bar.step()
    bar.close()
    assert stream.getvalue() == ""
