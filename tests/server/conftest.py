"""Fixtures for the HTTP service tests: a real ``urdflint serve`` process on a free port.

``live_server`` (session) yields the base URL of a server started with
``python -m urdflint serve --host 127.0.0.1 --port <free port>``; its per-request folders
go to ``live_server_tmpdir`` so tests can check they are removed. ``running_server(env)``
starts another one with environment overrides (limits) as a context manager.
"""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from pathlib import Path

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


@contextlib.contextmanager
def running_server(
    env: Mapping[str, str] | None = None, log: Path | None = None, ready: bool = True
) -> Iterator[str]:
    """Start ``urdflint serve`` with ``env`` added to the environment; yield its base URL.

    Waits until ``/healthz`` answers (and ``/readyz`` when ``ready``: the lint workers are
    up), and stops the server (SIGTERM, then SIGKILL) afterwards.
    """
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    full_env = {**os.environ, "PYTHONUNBUFFERED": "1", **(env or {})}
    log = log or Path(os.environ.get("TMPDIR", "/tmp")) / f"urdflint-serve-{port}.log"
    with open(log, "wb") as out:
        proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "urdflint",
                "serve",
                "--host",
                "127.0.0.1",
                "--port",
                str(port),
                "--log-level",
                "warning",
            ],
            env=full_env,
            stdout=out,
            stderr=subprocess.STDOUT,
        )
    try:
        _wait(proc, base, "/healthz", log)
        if ready:
            _wait(proc, base, "/readyz", log)
        yield base
    finally:
        proc.terminate()
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(5)
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
