"""Fixtures for the HTTP service tests: a real ``urdflint serve`` process on a free port.

``live_server`` (session) yields the base URL of a server started with
``python -m urdflint serve --host 127.0.0.1 --port <free port>``; its per-request folders
go to ``live_server_tmpdir`` so tests can check they are removed. ``running_server(env)``
starts another one with environment overrides (limits) as a context manager;
``start_server`` and ``stop_server`` for a test that watches the process itself.
"""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
import warnings
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")
httpx = pytest.importorskip("httpx")

START_TIMEOUT = 60.0


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _log_tail(path: Path) -> str:
    with contextlib.suppress(OSError):
        return path.read_text(errors="replace")[-4000:]
    return ""


def start_server(
    port: int,
    env: Mapping[str, str] | None,
    log: Path,
    cwd: Path | None = None,
    script: bool = False,
) -> subprocess.Popen[bytes]:
    """Start ``urdflint serve`` on ``port`` with ``env`` added, from ``cwd``; output to ``log``.

    ``script``: through the ``urdflint`` console script, as the Docker image does (so the
    current folder is not on the server's ``sys.path`` before uvicorn puts it there),
    instead of ``python -m urdflint``.
    """
    full_env = {**os.environ, "PYTHONUNBUFFERED": "1", **(env or {})}
    module = [sys.executable, "-m", "urdflint"]
    launcher = [str(Path(sys.executable).parent / "urdflint")] if script else module
    args = ["serve", "--host", "127.0.0.1", "--port", str(port), "--log-level", "warning"]
    with open(log, "wb") as out:
        return subprocess.Popen(
            [*launcher, *args], env=full_env, cwd=cwd, stdout=out, stderr=subprocess.STDOUT
        )


def stop_server(proc: subprocess.Popen[bytes]) -> None:
    """SIGTERM, then SIGKILL after 15 s."""
    if proc.poll() is not None:
        return
    proc.terminate()
    try:
        proc.wait(15)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(5)


@contextlib.contextmanager
def running_server(
    env: Mapping[str, str] | None = None,
    log: Path | None = None,
    ready: bool = True,
    cwd: Path | None = None,
    script: bool = False,
) -> Iterator[str]:
    """Start ``urdflint serve`` with ``env`` added to the environment; yield its base URL.

    Waits until ``/healthz`` answers (and ``/readyz`` when ``ready``: the lint workers are
    up), and stops the server (SIGTERM, then SIGKILL) afterwards. ``cwd`` and ``script``:
    see :func:`start_server`.
    """
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    log = log or Path(os.environ.get("TMPDIR", "/tmp")) / f"urdflint-serve-{port}.log"
    proc = start_server(port, env, log, cwd, script)
    try:
        _wait(proc, base, "/healthz", log)
        if ready:
            _wait(proc, base, "/readyz", log)
        yield base
    finally:
        stop_server(proc)
        with contextlib.suppress(OSError):
            log.unlink()


def _wait(proc: subprocess.Popen[bytes], base: str, path: str, log: Path) -> None:
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"urdflint serve exited with {proc.returncode}:\n{_log_tail(log)}")
        with contextlib.suppress(httpx.HTTPError):
            if httpx.get(base + path, timeout=2).status_code == 200:
                return
        time.sleep(0.1)
    raise RuntimeError(f"urdflint serve did not answer {path} in time:\n{_log_tail(log)}")


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    """The app in this process (one worker, request folders in a temporary folder), for a
    module that does not define its own ``client``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from fastapi.testclient import TestClient
    from urdflint.server.app import create_app
    from urdflint.server.limits import Limits

    folders = tmp_path_factory.mktemp("requests")
    with TestClient(
        create_app(Limits(jobs=1, tmpdir=str(folders))), raise_server_exceptions=False
    ) as test_client:
        yield test_client


@pytest.fixture(scope="module")
def base_url(live_server: str) -> str:
    """The session's ``urdflint serve`` process, for the browser tests."""
    return live_server


@pytest.fixture(scope="module")
def driver(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Any]:
    """Headless Chromium for one module (tests/server/browsing.py; the module skips
    without Chromium)."""
    from tests.server.browsing import new_driver

    browser = new_driver(tmp_path_factory.mktemp("chromium-profile"))
    try:
        yield browser
    finally:
        browser.quit()


@pytest.fixture(scope="session")
def live_server_tmpdir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where the session's live server makes (and must remove) its per-request folders."""
    return tmp_path_factory.mktemp("urdflint-requests")


@pytest.fixture(scope="session")
def live_server(live_server_tmpdir: Path) -> Iterator[str]:
    """Base URL (``http://127.0.0.1:PORT``) of a real ``urdflint serve`` process."""
    env = {
        "URDFLINT_TMPDIR": str(live_server_tmpdir),
        "URDFLINT_JOBS": "2",
        "URDFLINT_TEST_SECRET": "s3cr3t-do-not-leak",
    }
    with running_server(env) as base:
        yield base
