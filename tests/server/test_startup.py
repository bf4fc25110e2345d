"""Starting the service where its lint workers could break (issue 10).

A server started from a folder holding a ``urdflint`` package, an ``xacro.py`` and other
look-alikes still lints: its workers never import from the current folder. When the workers
cannot start for a reason the server cannot fix (here a ``sitecustomize`` that breaks
``urdflint.server.worker`` inside the fork server), ``/healthz`` stays 200 (liveness),
``/readyz`` answers 503 with the reason, and the process exits with code 3 within seconds,
for its supervisor to restart it. Real ``urdflint serve`` processes on free ports, started
with the console script as the Docker image does.
"""

from __future__ import annotations

import asyncio
import os
import sys
import time
from pathlib import Path

import pytest

from tests.server.conftest import free_port, running_server, start_server, stop_server

httpx = pytest.importorskip("httpx")

SCRIPT = Path(sys.executable).parent / "urdflint"
needs_script = pytest.mark.skipif(not SCRIPT.is_file(), reason="no urdflint console script")
XACRO = b"""<robot name="shadowed" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="base" value="base_link"/>
  <link name="${base}"/>
</robot>
"""
XML = {"content-type": "application/xml"}
# in the fork server only (started as ``python -c``), not in the service itself
BREAK_WORKERS = """import sys

if sys.argv == ["-c"]:
    sys.modules["urdflint.server.worker"] = None
"""


def shadowing_folder(root: Path) -> Path:
    """A folder that shadows urdflint and its libraries from the current folder.

    The empty ``urdflint`` folder is what broke every worker before (issue 10): the fork
    server runs ``python -c``, so with ``''`` first on its path it imported that folder as
    a namespace package while preloading, and every worker forked from it inherited that.
    """
    folder = root / "project"
    (folder / "urdflint" / "rules").mkdir(parents=True)
    for name in ("xacro", "lxml", "numpy", "trimesh", "pinocchio", "multipart"):
        (folder / f"{name}.py").write_text(f"raise ImportError('the shadow {name}')\n")
    return folder


@needs_script
def test_server_started_from_a_shadowing_folder_lints(tmp_path: Path) -> None:
    folder = shadowing_folder(tmp_path)
    env = {"URDFLINT_JOBS": "1", "URDFLINT_TMPDIR": str(tmp_path)}
    with running_server(env, cwd=folder, script=True) as base:
        assert httpx.get(f"{base}/healthz").status_code == 200
        ready = httpx.get(f"{base}/readyz", timeout=30)
        assert ready.status_code == 200 and ready.json()["ready"] is True, ready.text
        assert ready.json()["capabilities"]["pinocchio"]["works"] is not False
        r = httpx.post(f"{base}/v1/check", files={"urdf": ("r.xacro", XACRO)}, timeout=60)
        assert r.status_code == 200, r.text
        assert r.json()["models"]["r.xacro"]["root"] == "base_link"  # xacro ran, the real one


WAIT = 120.0  # s: a generous bound for the server to give up on its own (about 5 s idle)


@pytest.mark.slow  # waits for the server to give up
@needs_script
def test_server_exits_when_no_worker_can_start(tmp_path: Path) -> None:
    site = tmp_path / "site"
    site.mkdir()
    (site / "sitecustomize.py").write_text(BREAK_WORKERS)
    paths = [str(site), *filter(None, [os.environ.get("PYTHONPATH")])]
    env = {"URDFLINT_JOBS": "2", "PYTHONPATH": os.pathsep.join(paths)}
    port, log = free_port(), tmp_path / "serve.log"
    base = f"http://127.0.0.1:{port}"
    started = time.monotonic()
    proc = start_server(port, env, log, cwd=shadowing_folder(tmp_path), script=True)
    seen: dict[str, object] = {}
    try:
        while proc.poll() is None and time.monotonic() - started < WAIT:
            time.sleep(0.1)
            try:  # the server may stop between two requests: that is the point
                health = httpx.get(f"{base}/healthz", timeout=2)
                assert health.status_code == 200  # liveness, whatever the workers do
                ready = httpx.get(f"{base}/readyz", timeout=2)
                if ready.status_code == 503 and "urdflint.server.worker" in ready.text:
                    seen["ready"] = ready.json()
                    check = httpx.post(f"{base}/v1/check", content=XACRO, headers=XML, timeout=2)
                    seen["check"] = (check.status_code, check.json()["detail"])
            except httpx.TransportError:
                continue
        code = proc.wait(max(0.1, WAIT - (time.monotonic() - started)))
    finally:
        stop_server(proc)
    output = log.read_text(errors="replace")
    assert code == 3, output[-3000:]  # it gave up by itself (no wall-clock budget: CI is loaded)
    body = seen.get("ready")
    assert isinstance(body, dict), output[-3000:]
    assert body["ready"] is False and body["workers"]["started"] is False
    assert "ModuleNotFoundError" in body["reason"] and "urdflint.server.worker" in body["reason"]
    assert seen["check"] == (503, "no lint worker can start (see /readyz)")
    assert "no lint worker could start" in output and "exiting with code 3" in output


# -- in-process: the pool's bookkeeping and the probes ------------------------------------------

# a worker that cannot start: what the bootstrap sends when urdflint cannot be imported
FAILING = "conn.send(('failed', 'ImportError: simulated', 'Traceback ...'))\nraise SystemExit(1)"


def test_pool_counts_failed_starts_and_gives_up(monkeypatch: pytest.MonkeyPatch) -> None:
    from urdflint.server import starting
    from urdflint.server.pool import Busy, Pool

    monkeypatch.setattr(starting, "BOOTSTRAP", FAILING)
    told: list[str] = []

    async def scenario() -> tuple[bool, str | None, int]:
        pool = Pool(size=2, timeout=5, on_failed=told.append)
        try:
            ok = await pool.keep_starting(attempts=2, backoff=0.01)
            with pytest.raises(Busy, match="simulated"):
                await pool.run(object())
            return ok, pool.problem, pool.failures
        finally:
            await pool.close()

    ok, problem, failures = asyncio.run(scenario())
    assert ok is False and failures == 2  # the first worker of each attempt (then it stops)
    assert problem == told[0] == "no lint worker could start (2 attempts): ImportError: simulated"


def test_readyz_names_the_cause_in_process(monkeypatch: pytest.MonkeyPatch) -> None:
    from fastapi.testclient import TestClient
    from urdflint.server import starting
    from urdflint.server.app import create_app

    monkeypatch.setattr(starting, "BOOTSTRAP", FAILING)
    with TestClient(create_app()) as client:
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            ready = client.get("/readyz")
            if "simulated" in ready.text:
                break
            time.sleep(0.05)
        assert ready.status_code == 503, ready.text
        assert ready.json()["ready"] is False
        assert ready.json()["reason"].endswith("ImportError: simulated")
        assert client.get("/healthz").status_code == 200
        check = client.post("/v1/check", content=XACRO, headers={"content-type": "text/xml"})
        assert check.status_code == 503 and "see /readyz" in check.json()["detail"]


def test_workers_do_not_import_from_the_current_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from urdflint.server.starting import away_from_current_folder

    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("PYTHONSAFEPATH", raising=False)
    here = str(tmp_path)
    for chosen, kept in (("", ["/elsewhere"]), (here, [".", here, "/elsewhere"])):
        monkeypatch.setenv("PYTHONPATH", chosen)  # an entry named on purpose stays
        monkeypatch.setattr(sys, "path", ["", ".", here, "/elsewhere"])
        with away_from_current_folder():
            assert sys.path == kept
            assert os.environ["PYTHONSAFEPATH"] == "1"
        assert sys.path == ["", ".", here, "/elsewhere"]
        assert "PYTHONSAFEPATH" not in os.environ
