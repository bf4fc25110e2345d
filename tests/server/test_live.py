"""A real ``urdflint serve`` process over HTTP: the CLI's JSON, every attack, the limits,
time-outs, saturation, ``/healthz`` during a long job, and the temporary folders."""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import threading
import time
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES, needs_corpus
from tests.server import attacks
from tests.server.attacks import MESHES, make_zip, robot
from tests.server.conftest import _wait as wait_until
from tests.server.conftest import free_port, running_server, start_server, stop_server

httpx = pytest.importorskip("httpx")

MiB = 2**20
SLOW_XACRO = attacks.xacro(
    '<xacro:property name="big" value="${10**10**8}"/>\n  <link name="${big % 7}"/>'
)


def zip_folder(folder: Path, prefix: str) -> bytes:
    """``folder``'s files in a zip, under ``prefix/`` (as a user would pack a package)."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted(folder.rglob("*")):
            if path.is_file():
                zf.write(path, f"{prefix}/{path.relative_to(folder).as_posix()}")
    return buf.getvalue()


def cli_json(*args: str) -> tuple[dict[str, Any], int]:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--isolated", "--format", "json", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode in (0, 1), proc.stderr
    return json.loads(proc.stdout), proc.returncode


def normalised(document: dict[str, Any]) -> dict[str, Any]:
    """The document with every path field reduced to the file name (nothing else touched)."""
    data = json.loads(json.dumps(document))
    for finding in data["findings"]:
        finding["path"] = Path(finding["path"]).name
        for edit in (finding.get("autofix") or {}).get("edits", []):
            edit["path"] = Path(edit["path"]).name
    data["models"] = {Path(k).name: v for k, v in data.get("models", {}).items()}
    data["targets"] = {Path(k).name: v for k, v in data.get("targets", {}).items()}
    for chosen in data["targets"].values():
        for evidence in chosen["evidence"]:
            evidence["path"] = evidence["path"] and Path(evidence["path"]).name
    data.pop("passed", None)
    return data


# -- the CLI's JSON ---------------------------------------------------------------------------


@needs_corpus
@pytest.mark.parametrize(
    ("params", "flags"),
    [
        ({}, []),
        (
            {
                "target": "gz-sim,mujoco",
                "ignore": "J006",
                "fail_on": "info",
                "expect_mass": "3±1%",
                "expect_com": "0,0,1±0.5",
            },
            [
                "--target",
                "gz-sim",
                "--target",
                "mujoco",
                "--ignore",
                "J006",
                "--fail-on",
                "info",
                "--expect-mass",
                "3±1%",
                "--expect-com",
                "0,0,1±0.5",
            ],
        ),
    ],
    ids=["defaults", "options"],
)
def test_corpus_robot_json_is_the_clis(live_server: str, params: dict, flags: list[str]) -> None:
    folder = CORPUS / "rrbot"
    meshes = folder / "meshes" / "rrbot_description"
    expected, code = cli_json(
        *flags, "--package-path", f"rrbot_description={meshes}", str(folder / "model.urdf")
    )
    r = httpx.post(
        f"{live_server}/v1/check",
        files={
            "urdf": ("model.urdf", (folder / "model.urdf").read_bytes()),
            "meshes": ("meshes.zip", zip_folder(meshes, "rrbot_description")),
        },
        params=params,
        timeout=120,
    )
    assert r.status_code == 200, r.text
    got = r.json()
    assert normalised(got) == normalised(expected)
    assert got["models"]["model.urdf"] is not None  # Pinocchio ran (meshes found: no C004)
    assert got["passed"] is (code == 0)
    assert "C004" not in {f["code"] for f in got["findings"]}


def test_xacro_package_json_is_the_clis(live_server: str) -> None:
    package = FIXTURES / "xacro" / "rrbot"
    main = package / "urdf" / "rrbot.xacro"
    expected, _ = cli_json(
        "--package-path", f"rrbot_description={package}", "--xacro-arg", "camera:=false", str(main)
    )
    r = httpx.post(
        f"{live_server}/v1/check",
        files={
            "urdf": ("rrbot.xacro", main.read_bytes()),
            "meshes": ("package.zip", zip_folder(package, "rrbot")),
        },
        data={"xacro_args": "camera:=false"},
        timeout=120,
    )
    assert r.status_code == 200, r.text
    # the upload sits in no package: the service infers the targets from the model alone, so
    # the package's package.xml adds ROS only in the CLI (README, Targets); findings agree
    served, local = normalised(r.json()), normalised(expected)
    assert local["targets"]["rrbot.xacro"]["names"] == ["gazebo-classic", "ros"]
    assert served.pop("targets")["rrbot.xacro"]["names"] == ["gazebo-classic"]
    local.pop("targets")
    assert served == local
    assert "X010" not in {f["code"] for f in r.json()["findings"]}


def test_raw_body_json_is_the_clis(live_server: str, tmp_path: Path) -> None:
    source = FIXTURES / "models" / "broken_arm.urdf"
    expected, code = cli_json("--select", "I,J,S", str(source))
    r = httpx.post(
        f"{live_server}/v1/check?select=I,J,S&filename=broken_arm.urdf",
        content=source.read_bytes(),
        headers={"content-type": "text/xml; charset=utf-8"},
    )
    assert r.status_code == 200
    assert normalised(r.json()) == normalised(expected)
    assert r.json()["passed"] is (code == 0)


# -- attacks and limits -----------------------------------------------------------------------


def test_every_attack_is_refused_over_http(live_server: str, live_server_tmpdir: Path) -> None:
    with attacks.network_trap() as (url, hits), httpx.Client(timeout=60) as client:
        for case in attacks.cases(url):
            r = client.post(f"{live_server}/v1/check", **case.request())
            attacks.check_answer(case, r, str(live_server_tmpdir))
        time.sleep(0.3)
        assert hits() == []  # nothing fetched: no entity, DTD, include or mesh over the network
    assert list(live_server_tmpdir.iterdir()) == []


def test_sizes_and_types_over_http(live_server: str) -> None:
    url = f"{live_server}/v1/check"
    xml = {"content-type": "application/xml"}
    big = robot().encode() + b"<!--" + b"x" * (5 * MiB) + b"-->"
    assert httpx.post(url, content=big, headers=xml).status_code == 413

    def chunked() -> Iterator[bytes]:
        yield robot().encode()
        for _ in range(6):
            yield b"<!--" + b"x" * MiB + b"-->"

    assert httpx.post(url, content=chunked(), headers=xml).status_code == 413
    r = httpx.post(url, files={"urdf": ("r.urdf", big)})
    assert r.status_code == 413 and "URDF" in r.json()["detail"]
    text = httpx.post(url, content=robot().encode(), headers={"content-type": "text/plain"})
    assert text.status_code == 415
    assert httpx.post(url, files={"urdf": ("r.png", b"x")}).status_code == 415
    unknown = httpx.post(url, files={"urdf": ("r.urdf", robot().encode())}, data={"nope": "1"})
    assert unknown.status_code == 422
    assert httpx.get(f"{live_server}/healthz").json() == {"status": "ok"}


def test_probes_over_http(live_server: str) -> None:
    ready = httpx.get(f"{live_server}/readyz", timeout=30)
    assert ready.status_code == 200 and ready.json()["ready"] is True
    assert httpx.get(f"{live_server}/version").json()["urdflint"]
    assert httpx.get(f"{live_server}/v1/rules/X002").json()["code"] == "X002"
    assert httpx.get(f"{live_server}/docs").status_code == 200


# -- a small, slow server: time-outs, saturation, liveness -----------------------------------


@pytest.fixture(scope="module")
def slow_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Path]]:
    folders = tmp_path_factory.mktemp("slow-requests")
    env = {
        "URDFLINT_JOBS": "1",
        "URDFLINT_QUEUE": "0",
        "URDFLINT_TIMEOUT": "3",
        "URDFLINT_TMPDIR": str(folders),
        "URDFLINT_MAX_UNZIPPED_BYTES": "1M",
        "URDFLINT_MAX_ZIP_MEMBERS": "20",
    }
    with running_server(env) as base:
        yield base, folders


def test_long_job_times_out_while_the_server_stays_live(slow_server: tuple[str, Path]) -> None:
    base, folders = slow_server
    answer: dict[str, Any] = {}

    def slow() -> None:
        started = time.monotonic()
        r = httpx.post(
            f"{base}/v1/check", files={"urdf": ("slow.xacro", SLOW_XACRO.encode())}, timeout=60
        )
        answer.update(
            status=r.status_code, detail=r.json()["detail"], took=time.monotonic() - started
        )

    thread = threading.Thread(target=slow)
    thread.start()
    time.sleep(0.8)  # the job is running in the only worker
    for _ in range(5):  # answered while the job still runs: the event loop is free
        assert httpx.get(f"{base}/healthz", timeout=5).status_code == 200
        assert thread.is_alive() and not answer  # no wall-clock bound: CI is loaded
        time.sleep(0.1)
    busy = httpx.post(
        f"{base}/v1/check",
        content=robot().encode(),
        headers={"content-type": "application/xml"},
        timeout=10,
    )
    assert busy.status_code in (429, 503), busy.text
    assert busy.headers.get("retry-after")
    thread.join(30)
    assert answer["status"] == 504, answer
    assert 2.5 < answer["took"] < 15
    # the killed worker was replaced: the next request is linted normally
    for _ in range(50):
        r = httpx.post(
            f"{base}/v1/check",
            content=robot().encode(),
            headers={"content-type": "application/xml"},
            timeout=30,
        )
        if r.status_code != 503:
            break
        time.sleep(0.1)
    assert r.status_code == 200, r.text
    assert list(folders.iterdir()) == []


def test_zip_caps_over_http(slow_server: tuple[str, Path]) -> None:
    base, folders = slow_server
    url = f"{base}/v1/check"
    many = make_zip([(f"pkg/{i}.stl", b"x") for i in range(30)])
    wide = make_zip([(f"pkg/{i}.stl", bytes(300 * 1024)) for i in range(5)])  # 1.5 MiB in all
    for data, word in ((many, "members"), (wide, "expands to more than"), (MESHES, "")):
        r = httpx.post(url, files={"urdf": ("r.urdf", robot().encode()), "meshes": ("m.zip", data)})
        if word:
            assert r.status_code == 422 and word in r.json()["detail"], r.text
        else:
            assert r.status_code == 200, r.text
    assert list(folders.iterdir()) == []


# -- a bounded load loop: readiness under saturation, a worker killed mid-request -----------


def _lint_workers(server_pid: int) -> list[int]:
    """The server's lint workers: its descendants that lead their own process group
    (``worker.main`` makes each worker a group leader; the fork server and the resource
    tracker are not)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            children.setdefault(int(stat[1]), []).append(int(entry.name))
    found, todo = [], list(children.get(server_pid, []))
    while todo:
        pid = todo.pop()
        todo.extend(children.get(pid, []))
        try:
            if os.getpgid(pid) == pid:
                found.append(pid)
        except OSError:
            continue
    return found


@pytest.mark.slow  # a load loop against the real server
@needs_corpus
@pytest.mark.skipif(not Path("/proc").is_dir(), reason="finds the lint workers in /proc")
def test_a_bounded_load_loop_saturates_readiness_and_survives_a_killed_worker(
    tmp_path: Path,
) -> None:
    """Six clients post PR2 (a new body each time: no cached answer) to a server with one
    worker and one queue place, a bounded number of times. While every place is taken,
    /readyz says 503 with the reason; one worker is SIGKILLed while it checks a request.
    Every answer is 200, or 503 with Retry-After (never a verdict such as 422 on a killed
    check); the death is logged once, with its signal; nothing refused is logged (the
    model reads only its own files); capacity back, /readyz is 200 (issue 23, 7)."""
    urdf = (CORPUS / "pr2" / "model.urdf").read_bytes()
    log = tmp_path / "serve.log"
    env = {"URDFLINT_JOBS": "1", "URDFLINT_QUEUE": "1", "URDFLINT_TMPDIR": str(tmp_path)}
    answers: list[tuple[int, str | None, str]] = []
    lock = threading.Lock()
    stop = threading.Event()

    def client(number: int) -> None:
        with httpx.Client(timeout=120) as http:
            for attempt in range(8):  # bounded: 8 requests per client
                if stop.is_set():
                    return
                body = urdf + f"<!-- client {number} request {attempt} -->\n".encode()
                r = http.post(
                    f"{base}/v1/check", content=body, headers={"content-type": "application/xml"}
                )
                detail = r.json().get("detail", "") if r.status_code != 200 else ""
                with lock:
                    answers.append((r.status_code, r.headers.get("retry-after"), detail))
                if r.status_code == 503:
                    time.sleep(0.05)

    port = free_port()
    base = f"http://127.0.0.1:{port}"
    server = start_server(port, env, log)
    try:
        wait_until(server, base, "/readyz", log)
        server_pid = server.pid
        threads = [threading.Thread(target=client, args=(n,)) for n in range(6)]
        for thread in threads:
            thread.start()
        saturated, killed = None, None
        deadline = time.monotonic() + 120
        while any(t.is_alive() for t in threads) and time.monotonic() < deadline:
            ready = httpx.get(f"{base}/readyz", timeout=10)
            if ready.status_code == 503 and saturated is None:
                saturated = ready.json().get("reason"), ready.headers.get("retry-after")
            if saturated is not None and killed is None:
                workers = _lint_workers(server_pid)
                if workers:
                    killed = workers[0]
                    os.kill(killed, signal.SIGKILL)
            time.sleep(0.05)
        stop.set()
        for thread in threads:
            thread.join(60)
        for _ in range(200):  # the replacement starts; capacity returns
            if httpx.get(f"{base}/readyz", timeout=10).status_code == 200:
                break
            time.sleep(0.1)
        assert httpx.get(f"{base}/readyz", timeout=10).status_code == 200
        last = httpx.post(
            f"{base}/v1/check", content=urdf, headers={"content-type": "application/xml"},
            timeout=120,
        )  # fmt: skip
    finally:
        stop_server(server)
    text = log.read_text(errors="replace")
    assert saturated == ("every lint worker and queue place is taken", "1"), saturated
    assert killed is not None
    assert {status for status, _, _ in answers} <= {200, 503}, answers
    assert all(retry for status, retry, _ in answers if status == 503), answers
    assert sum("(SIGKILL)" in detail for _, _, detail in answers) == 1, answers
    assert sum(status == 200 for status, _, _ in answers) >= 6, answers
    assert last.status_code == 200
    deaths = [line for line in text.splitlines() if "died" in line]
    assert len(deaths) == 1 and "SIGKILL" in deaths[0], text[-3000:]
    assert "refused" not in text, text[-3000:]
