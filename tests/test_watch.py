"""``check --watch``: a new report whenever a checked file or a file it reads changes, and a
clean exit on Ctrl-C. Driven as a user would, in a subprocess; every wait is for an event
(a line of output), with generous timeouts, never a timing budget."""

from __future__ import annotations

import queue
import shutil
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import FIXTURES

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
RRBOT = FIXTURES / "xacro" / "rrbot"
TIMEOUT = 120.0  # s: generous, for a loaded machine; a passing run takes a few seconds


class Watch:
    """A running ``urdflint check --watch``, its output read line by line."""

    def __init__(self, cwd: Path, *args: str) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "urdflint", "check", "--watch", "--isolated", *args],
            cwd=cwd,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        self.lines: queue.Queue[tuple[str, str]] = queue.Queue()
        self.stderr: list[str] = []
        for name, stream in (("out", self.proc.stdout), ("err", self.proc.stderr)):
            threading.Thread(target=self._read, args=(name, stream), daemon=True).start()

    def _read(self, name: str, stream: object) -> None:
        for line in iter(stream.readline, ""):  # type: ignore[attr-defined]
            if name == "err":
                self.stderr.append(line)
            self.lines.put((name, line))
        self.lines.put((name, ""))

    def report(self) -> list[str]:
        """The next report on stdout, up to its summary line, once the watch is waiting again
        (its inputs noted: a change from then on is seen)."""
        found: list[str] = []
        summary = waiting = False  # the two streams are read apart: either may come first
        while not (summary and waiting):
            try:
                name, line = self.lines.get(timeout=TIMEOUT)
            except queue.Empty:
                pytest.fail(f"no report in {TIMEOUT} s; so far: {found}, {self.stderr}")
            if line == "":
                pytest.fail(f"urdflint --watch ended: {found}, {self.stderr}")
            if name == "out":
                found.append(line.rstrip("\n"))
                summary = summary or line.startswith("urdflint: ")
            else:
                waiting = waiting or line.startswith("urdflint: watching ")
        return found

    def stop(self) -> tuple[int, str]:
        self.proc.send_signal(signal.SIGINT)
        code = self.proc.wait(timeout=TIMEOUT)
        return code, "".join(self.stderr)

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(timeout=TIMEOUT)


@pytest.fixture
def watching() -> Iterator[list[Watch]]:
    started: list[Watch] = []
    yield started
    for watch in started:
        watch.kill()


def test_watch_reports_again_after_an_edit_and_stops_on_ctrl_c(
    tmp_path: Path, watching: list[Watch]
) -> None:
    shutil.copy(BROKEN, tmp_path / "arm.urdf")
    watch = Watch(tmp_path, "arm.urdf")
    watching.append(watch)
    first = watch.report()
    assert any(" error I002 non-positive-mass: " in line for line in first)
    assert first[-1] == "urdflint: 12 errors, 3 warnings, 2 infos in 1 file"

    path = tmp_path / "arm.urdf"
    path.write_text(path.read_text().replace('<mass value="-1.0"/>', '<mass value="1.0"/>'))
    second = watch.report()
    assert not any(" I002 " in line for line in second)
    assert second[-1] == "urdflint: 11 errors, 3 warnings, 2 infos in 1 file"

    code, err = watch.stop()
    assert code == 0
    assert "Traceback" not in err and "KeyboardInterrupt" not in err
    assert "urdflint: watching 1 file for changes (Ctrl-C stops)" in err


def test_watch_sees_a_change_in_an_included_xacro_file(
    tmp_path: Path, watching: list[Watch]
) -> None:
    pytest.importorskip("xacro")
    folder = tmp_path / "rrbot_description"
    shutil.copytree(RRBOT, folder)
    watch = Watch(folder, "urdf/rrbot.xacro")
    watching.append(watch)
    first = watch.report()
    assert not any(" G001 " in line for line in first)

    gazebo = folder / "urdf" / "rrbot.gazebo"  # not a checked file: included by rrbot.xacro
    gazebo.write_text(gazebo.read_text().replace('reference="link3"', 'reference="link9"'))
    second = watch.report()
    assert any(
        line.startswith("urdf/rrbot.gazebo:") and " error G001 " in line for line in second
    ), second

    code, err = watch.stop()
    assert code == 0 and "Traceback" not in err
