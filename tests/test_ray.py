"""``--executor ray`` on a real Ray: a head with 2 CPUs on 127.0.0.1, started for this
module (``ray start --head --block``) and stopped after it.

The output of a Ray run is the output of ``--jobs 1`` (the JSON byte for byte, the records
but for ``inputs``) on a few hundred variants of the corpus robots; a worker killed in the
middle of a run loses no file; with ``--confirm``, each (file, engine) pair is its own task
and an engine's crash is reported as locally (E005).
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests import variants
from urdflint.outputs import records

pytestmark = pytest.mark.slow
ray = pytest.importorskip("ray")

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "fixtures" / "models"
E005 = ROOT / "fixtures" / "rules" / "E005" / "bad.urdf"
# token authentication (on by default for local clusters since Ray 2.59) is left off for
# this head, which listens on 127.0.0.1 only: driver and head must agree
ENV = {**os.environ, "RAY_AUTH_MODE": "disabled", "URDFLINT_NO_CACHE": "1"}
ENV.pop("RAY_ADDRESS", None)


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@pytest.fixture(scope="module")
def head(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """The address of a Ray head with 2 CPUs on 127.0.0.1."""
    ray_bin = Path(sys.executable).with_name("ray")
    if not ray_bin.exists():
        pytest.skip("the ray command is not installed beside this Python")
    port = _free_port()
    log = tmp_path_factory.mktemp("ray") / "head.log"
    command = [
        str(ray_bin), "start", "--head", "--block", "--num-cpus", "2",
        "--node-ip-address", "127.0.0.1", "--port", str(port),
        "--include-dashboard", "false", "--disable-usage-stats",
    ]  # fmt: skip
    with log.open("wb") as out:
        proc = subprocess.Popen(
            command, env=ENV, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
        )
    address = f"127.0.0.1:{port}"
    deadline = time.monotonic() + 120
    try:
        while time.monotonic() < deadline:
            if proc.poll() is not None:
                pytest.fail(f"ray start exited: {log.read_text()[-2000:]}")
            try:
                with socket.create_connection(("127.0.0.1", port), timeout=1):
                    break
            except OSError:
                time.sleep(0.5)
        else:
            pytest.fail("the Ray head did not start within 120 s")
        yield address
    finally:
        _stop(proc)


def _stop(proc: subprocess.Popen[bytes]) -> None:
    try:
        os.killpg(proc.pid, signal.SIGTERM)
        proc.wait(timeout=30)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        pass
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)


def _urdflint(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "urdflint", *args],
        env=ENV,
        cwd=cwd,
        capture_output=True,
        text=True,
        check=False,
        timeout=1800,
    )


def _records(path: Path) -> dict[str, dict]:
    return {
        item["path"]: {k: v for k, v in item.items() if k != "inputs"}
        for item in records.read(path)[0]
    }


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    if not variants.CORPUS.is_dir():
        pytest.skip("../shared/corpus is absent")
    folder = tmp_path_factory.mktemp("dataset")
    made = variants.make(folder, 240, largest=40_000)
    assert len(made) == 240
    return folder


def test_the_output_is_the_output_of_jobs_1(head: str, dataset: Path, tmp_path: Path) -> None:
    ray_run = _urdflint("check", ".", "--executor", "ray", "--ray-address", head,
                        "--format", "json", "--report", f"jsonl:{tmp_path / 'ray.jsonl'}",
                        cwd=dataset)  # fmt: skip
    local = _urdflint("check", ".", "-j", "1", "--format", "json",
                      "--report", f"jsonl:{tmp_path / 'local.jsonl'}", cwd=dataset)  # fmt: skip
    assert local.returncode == 1, local.stderr
    assert ray_run.returncode == 1, ray_run.stderr
    assert ray_run.stdout == local.stdout
    assert len(json.loads(local.stdout)["findings"]) > 1000
    mine, theirs = _records(tmp_path / "ray.jsonl"), _records(tmp_path / "local.jsonl")
    assert len(mine) == 240 and mine == theirs


def test_a_killed_worker_loses_no_file(head: str, dataset: Path, tmp_path: Path) -> None:
    """SIGKILL to the worker running a chunk of files: Ray runs the chunk again elsewhere,
    and every file is reported, as ``--jobs 1`` reports it."""
    out = tmp_path / "ray.jsonl"
    command = [sys.executable, "-m", "urdflint", "check", ".", "--executor", "ray",
               "--ray-address", head, "--format", "jsonl", "--output", str(out)]  # fmt: skip
    proc = subprocess.Popen(
        command, env=ENV, cwd=dataset, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    killed = None
    deadline = time.monotonic() + 300
    while killed is None and proc.poll() is None and time.monotonic() < deadline:
        for pid in _running("ray::_lint_chunk"):
            os.kill(pid, signal.SIGKILL)
            killed = pid
            break
        time.sleep(0.05)
    _, err = proc.communicate(timeout=1800)
    assert killed is not None, "no worker was seen running a chunk"
    assert proc.returncode == 1, err
    local = tmp_path / "local.jsonl"
    _urdflint("check", ".", "-j", "1", "--format", "jsonl", "--output", str(local), cwd=dataset)
    assert _records(out) == _records(local)


def _running(title: str) -> list[int]:
    """The processes whose command line (a Ray worker's title) starts with ``title``."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        if cmdline.startswith(title.encode()):
            found.append(int(entry.name))
    return found


def test_confirm_on_ray_gives_the_local_verdict(head: str, tmp_path: Path) -> None:
    """--confirm on Ray (engines in warm probes beside the workers) gives the findings a
    local run gives, E005 included (PyBullet crashes on the E005 fixture: tried twice,
    then reported)."""
    from urdflint.engines import runner

    engines = [e for e in ("mujoco", "pybullet") if runner.installed(e)]
    if len(engines) < 2:
        pytest.skip("needs MuJoCo and PyBullet (pip install -e '.[engines]')")
    folder = tmp_path / "models"
    shutil.copytree(MODELS, folder)
    shutil.copy(E005, folder / "e005.urdf")
    args = ["check", ".", "--isolated", "--confirm", ",".join(engines), "--format", "json"]
    ray_run = _urdflint(*args, "--executor", "ray", "--ray-address", head, cwd=folder)
    local = _urdflint(*args, "-j", "1", cwd=folder)
    assert ray_run.returncode == local.returncode == 1, ray_run.stderr
    assert ray_run.stdout == local.stdout
    found = json.loads(ray_run.stdout)["findings"]
    assert any(f["code"] == "E005" and f["path"] == "e005.urdf" for f in found)
    assert {f["engine"] for f in found if f["code"].startswith("E")} == set(engines)
