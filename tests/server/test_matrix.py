"""The ``matrix`` and ``confirm`` options of ``POST /v1/check``, ``--allow-confirm``, and
what confines the engines a confirming job starts (``server/confirming.py``, the fence)."""

from __future__ import annotations

import importlib.util
import json
import multiprocessing
import os
import subprocess
import sys
import time
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.server import attacks
from urdflint.engine import config
from urdflint.model import targets

pytest.importorskip("fastapi")
with warnings.catch_warnings():  # starlette 1.x would like httpx2 for its TestClient
    warnings.simplefilter("ignore")
    from fastapi.testclient import TestClient
from urdflint.server import options
from urdflint.server.app import create_app
from urdflint.server.confirming import Confinement, margin
from urdflint.server.limits import LimitError, Limits

OUTCOMES = {"loads", "changes", "refused", "crashes"}
CONFIRMED = OUTCOMES | {"not-installed"}
TWO_ROOTS = """<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <link name="stray"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>
"""
NAME = "two_roots.urdf"
HAS_PINOCCHIO = importlib.util.find_spec("pinocchio") is not None
HAS_MUJOCO = importlib.util.find_spec("mujoco") is not None


def _limits(folder: Path, allow_confirm: bool) -> Limits:
    return Limits(timeout=60, jobs=1, queue=4, tmpdir=str(folder), allow_confirm=allow_confirm)


@pytest.fixture(scope="module")
def folders(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("matrix-requests")


@pytest.fixture(scope="module")
def client(folders: Path) -> Iterator[TestClient]:
    """A server as started by default: no ``--allow-confirm``."""
    with TestClient(create_app(_limits(folders, False)), raise_server_exceptions=False) as c:
        yield c


@pytest.fixture(scope="module")
def confirming(folders: Path) -> Iterator[TestClient]:
    """A server started with ``--allow-confirm``."""
    with TestClient(create_app(_limits(folders, True)), raise_server_exceptions=False) as c:
        yield c


def check(client: TestClient, text: str = TWO_ROOTS, **params: str) -> Any:
    return client.post(
        "/v1/check",
        content=text.encode(),
        headers={"content-type": "application/xml"},
        params={"filename": NAME, **params},
    )


def cli_matrix(tmp_path: Path, *args: str) -> list[dict[str, Any]]:
    """``urdflint check --matrix --isolated --format json`` on :data:`TWO_ROOTS`."""
    path = tmp_path / NAME
    path.write_text(TWO_ROOTS)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--matrix", "--isolated", "--format", "json",
         *args, NAME],
        capture_output=True, text=True, cwd=tmp_path, timeout=120,
    )  # fmt: skip
    assert proc.returncode in (0, 1), proc.stderr
    rows: list[dict[str, Any]] = json.loads(proc.stdout)["matrix"]
    return rows


# -- matrix ------------------------------------------------------------------------------------


def test_matrix_has_a_row_per_target_as_the_cli(client: TestClient, tmp_path: Path) -> None:
    r = check(client, matrix="true")
    assert r.status_code == 200, r.text
    data = r.json()
    rows = data["matrix"]
    assert [row["target"] for row in rows] == list(targets.TARGETS)  # every target, in order
    codes = {f["code"] for f in data["findings"]}
    assert "S004" in codes
    for row in rows:
        assert row["path"] == NAME and row["confirmed"] is None
        assert row["label"] == targets.LABELS[row["target"]]
        expected_basis = "engine" if targets.ENGINE[row["target"]] else "source and documentation"
        assert row["basis"] == expected_basis
        assert row["predicted"]["outcome"] in OUTCOMES
        for found in row["predicted"]["findings"]:
            assert found["code"] in codes and found["path"] == NAME
            assert set(found) == {"code", "path", "line", "element", "consequence", "detail"}
    assert rows == cli_matrix(tmp_path)  # the service and the CLI agree exactly


def test_matrix_follows_the_target_option(client: TestClient) -> None:
    """Every target has a row; the option marks the selected ones (the matrix is a display:
    it never changes which targets the findings are for, issue 24, 8)."""

    def selected(rows: list[dict]) -> list[str]:
        assert [row["target"] for row in rows] == list(targets.TARGETS)
        return [row["target"] for row in rows if row["selected"]]

    assert selected(check(client, matrix="true", target="mujoco").json()["matrix"]) == ["mujoco"]
    both = check(client, matrix="1", target="pinocchio,drake").json()["matrix"]
    assert selected(both) == ["drake", "pinocchio"]
    every = check(client, matrix="true", target="all").json()["matrix"]
    assert selected(every) == list(targets.TARGETS)
    assert check(client, matrix="true").json()["findings"] == check(client).json()["findings"]
    assert "matrix" not in check(client).json()
    assert "matrix" not in check(client, matrix="false").json()
    bad = check(client, matrix="maybe")
    assert bad.status_code == 422 and "matrix" in bad.json()["detail"]


def test_matrix_as_form_fields_and_in_text(client: TestClient) -> None:
    r = client.post(
        "/v1/check",
        files={"urdf": (NAME, TWO_ROOTS.encode())},
        data={"matrix": "true", "target": "ros"},
    )
    assert r.status_code == 200, r.text
    assert [row["target"] for row in r.json()["matrix"] if row["selected"]] == ["ros"]
    text = check(client, matrix="true", format="text")
    assert text.status_code == 200 and "S004" in text.text


def test_no_matrix_for_a_file_that_is_not_a_model(client: TestClient) -> None:
    r = check(client, "this is not XML", matrix="true")
    assert r.status_code == 200
    assert "matrix" not in r.json()  # as the CLI: no model, no rows
    assert [f["code"] for f in r.json()["findings"]] == ["X001"]


# -- confirm -----------------------------------------------------------------------------------


def test_confirm_is_refused_without_allow_confirm(client: TestClient) -> None:
    for params in ({"confirm": "pinocchio"}, {"confirm": "all", "matrix": "true"}):
        r = check(client, **params)
        assert r.status_code == 422, r.text
        assert "--allow-confirm" in r.json()["detail"]
    form = client.post("/v1/check", files={"urdf": (NAME, TWO_ROOTS.encode())},
                       data={"confirm": "mujoco"})  # fmt: skip
    assert form.status_code == 422 and "--allow-confirm" in form.json()["detail"]
    via_config = check(client, config=json.dumps({"confirm": ["drake"]}))
    assert via_config.status_code == 422 and "--allow-confirm" in via_config.json()["detail"]
    assert check(client, confirm="").status_code == 200  # an empty field names no engine


def test_bad_engine_names_are_422(confirming: TestClient) -> None:
    r = check(confirming, confirm="gazebo")
    assert r.status_code == 422 and "unknown engine 'gazebo'" in r.json()["detail"]


@pytest.mark.slow  # the real engines
@pytest.mark.skipif(not HAS_PINOCCHIO, reason="needs pinocchio")
def test_confirm_runs_the_engine_in_the_worker(confirming: TestClient, folders: Path) -> None:
    r = check(confirming, matrix="true", confirm="pinocchio")
    assert r.status_code == 200, r.text
    data = r.json()
    rows = {row["target"]: row for row in data["matrix"]}
    assert set(rows) == set(targets.TARGETS)
    confirmed = rows["pinocchio"]["confirmed"]
    assert isinstance(confirmed, dict) and confirmed["engine"] == "pinocchio"
    assert confirmed["outcome"] in CONFIRMED and confirmed["outcome"] != "not-installed"
    for found in confirmed["findings"]:
        assert found["path"] == NAME and set(found) == {"code", "path", "line", "message"}
    assert all(row["confirmed"] is None for t, row in rows.items() if t != "pinocchio")
    engine = [f for f in data["findings"] if f["code"].startswith("E")]
    assert engine and any("Pinocchio" in f["message"] for f in engine)  # it did load it
    assert not attacks.leaks(r.text, str(folders))
    assert list(folders.iterdir()) == []


@pytest.mark.slow  # the real engines
@pytest.mark.skipif(not HAS_MUJOCO, reason="needs mujoco")
def test_confirmed_engines_never_open_files_outside_the_upload(
    confirming: TestClient, folders: Path
) -> None:
    """Every mesh attack, with every engine: no engine opens what the linter refused."""
    with attacks.network_trap() as (url, hits):
        for case in attacks.cases(url):
            if not case.id.startswith("mesh-") or case.status != 200:
                continue
            request = case.request()
            request["params"] = {**request["params"], "confirm": "all", "matrix": "true"}
            r = confirming.post("/v1/check", **request)
            attacks.check_answer(case, r, str(folders))
            assert "matrix" in r.json(), case.id
        assert hits() == []
    assert list(folders.iterdir()) == []
    collision = "<collision><geometry><mesh filename='/etc/passwd.stl'/></geometry></collision>"
    passwd = TWO_ROOTS.replace('<link name="arm"/>', f'<link name="arm">{collision}</link>')
    r = check(confirming, passwd, confirm="mujoco")
    said = [f["message"] for f in r.json()["findings"] if f["code"] == "E001"]
    assert said and "/etc/passwd.stl" in said[0], said  # the reference as written
    assert not attacks.leaks(r.text, str(folders))


# -- what the page and clients learn ----------------------------------------------------------


def test_capabilities_and_readyz_say_whether_confirm_is_allowed(
    client: TestClient, confirming: TestClient
) -> None:
    for app, allowed in ((client, False), (confirming, True)):
        found = app.get("/v1/capabilities").json()
        assert found["confirm"]["allowed"] is allowed
        assert set(found["confirm"]["engines"]) == set(config.ENGINES)
        assert all(isinstance(v, bool) for v in found["confirm"]["engines"].values())
        assert [t["name"] for t in found["targets"]] == list(targets.TARGETS)
        assert found["matrix"] is True and "json" in found["formats"]
        ready = app.get("/readyz")
        assert ready.status_code == 200 and ready.json()["confirm"]["allowed"] is allowed
        assert app.get("/healthz").json() == {"status": "ok"}
    installed = client.get("/v1/capabilities").json()["confirm"]["engines"]
    assert installed.get("pinocchio") is HAS_PINOCCHIO


def test_allow_confirm_from_the_environment() -> None:
    assert Limits.from_env({}).allow_confirm is False
    assert Limits.from_env({"URDFLINT_ALLOW_CONFIRM": "1"}).allow_confirm is True
    assert Limits.from_env({"URDFLINT_ALLOW_CONFIRM": "false"}).allow_confirm is False
    with pytest.raises(LimitError):
        Limits.from_env({"URDFLINT_ALLOW_CONFIRM": "perhaps"})


def test_serve_allow_confirm_reaches_the_app(monkeypatch: pytest.MonkeyPatch) -> None:
    uvicorn = pytest.importorskip("uvicorn")
    from urdflint.cli import main

    seen: dict[str, Any] = {}
    monkeypatch.delenv("URDFLINT_ALLOW_CONFIRM", raising=False)
    monkeypatch.setattr(uvicorn, "run", lambda *a, **k: seen.update(env=dict(os.environ)))
    assert main(["serve", "--port", "0"]) == 0
    assert "URDFLINT_ALLOW_CONFIRM" not in seen["env"]
    assert main(["serve", "--port", "0", "--allow-confirm"]) == 0
    assert seen["env"]["URDFLINT_ALLOW_CONFIRM"] == "1"
    assert Limits.from_env(seen["env"]).allow_confirm is True


def test_option_parsing_units() -> None:
    parsed = options.parse(options.merge([("matrix", "true")]))
    assert parsed.matrix and parsed.settings.targets == ()  # a display: still inferred
    assert options.parse(options.merge([])).settings.targets == ()  # inferred, as the CLI
    kept = options.parse(options.merge([("matrix", "on"), ("target", "drake")]))
    assert kept.settings.targets == ("drake",)
    allowed = options.parse(options.merge([("confirm", "drake"), ("confirm", "mujoco")]), True)
    assert allowed.settings.confirm == ("drake", "mujoco")
    every = options.parse(options.merge([("confirm", "all")]), allow_confirm=True)
    assert every.settings.confirm == config.ENGINES
    with pytest.raises(options.OptionError, match="allow-confirm"):
        options.parse(options.merge([("confirm", "drake")]))


# -- the confinement ---------------------------------------------------------------------------


def test_the_written_model_only_references_the_upload(tmp_path: Path) -> None:
    root = tmp_path / "files"
    (root / "pkg").mkdir(parents=True)
    mesh = root / "pkg" / "arm.stl"
    mesh.write_bytes(attacks.STL)
    outside = tmp_path / "secret.stl"
    outside.write_bytes(attacks.STL)
    (root / "pkg" / "link.stl").symlink_to(outside)
    engines = tmp_path / "tmp" / "engines"
    engines.mkdir(parents=True)
    model = engines / "robot.urdf"
    refs = [str(mesh), str(outside), str(root / "pkg" / "link.stl"), "/etc/passwd",
            "../../../etc/hostname", "package://pkg/arm.stl", "http://example.com/x.stl",
            str(root / "pkg")]  # fmt: skip
    body = "".join(f'<mesh filename="{ref}"/>' for ref in refs)
    model.write_text(f'\n\n<robot name="r">\n{body}<texture file="/dev/zero"/></robot>')
    job = Confinement(root, time.monotonic() + 30)
    job.confine(model)
    text = model.read_text()
    assert text.startswith('\n\n<robot name="r">\n')  # line numbers kept
    from lxml import etree

    written = [e.get("filename") or e.get("file") for e in etree.fromstring(text.strip()).iter()]
    written = [w for w in written if w]
    assert written[0] == str(mesh)  # a file of the upload, absolute: kept
    for ref, now in zip([*refs[1:], "/dev/zero"], written[1:], strict=True):
        assert now.startswith(str(engines / "unresolved") + os.sep) and not Path(now).exists()
        assert job.shown[now] == ref  # messages show the reference as written
    assert 1.0 <= job.budget(60) <= 30
    assert job.budget(0.5) == 1.0  # never below one second
    assert Confinement(root, time.monotonic() - 5).budget(60) == 1.0
    assert margin(60) == 10 and margin(2) == 1 and margin(20) == 4


def test_the_fence_lets_a_job_start_only_the_probe(tmp_path: Path) -> None:
    """In a child process (audit hooks cannot be removed): spawns from any thread are
    refused, except the allowed command, from inside the request's folder."""
    code = f"""
import pathlib, subprocess, sys, threading
from urdflint.server import fence
root = pathlib.Path({str(tmp_path)!r})
(root / "tmp").mkdir(exist_ok=True)
probe = [sys.executable, "-m", "urdflint.engines.probe", "none", "x.urdf", "0"]
results = []

def attempt(command, cwd, thread):
    def go():
        try:
            subprocess.run(command, cwd=cwd, capture_output=True, timeout=60)
            results.append("allowed")
        except PermissionError:
            results.append("refused")
    if not thread:
        return go()
    worker = threading.Thread(target=go)
    worker.start()
    worker.join()

with fence.fenced(root):
    attempt([sys.executable, "-c", "pass"], str(root / "tmp"), True)
    attempt(probe, str(root / "tmp"), True)
    fence.FENCE.commands = ((sys.executable, "-m", "urdflint.engines.probe"),)
    attempt(probe, str(root / "tmp"), True)
    attempt(probe, str(root / "tmp"), False)
    attempt(probe, str(root.parent), True)
    attempt(["/bin/sh", "-c", "true"], str(root / "tmp"), True)
    attempt([sys.executable, "-c", "pass"], str(root / "tmp"), False)
print(results, fence.FENCE.commands)
"""
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    expected = ["refused", "refused", "allowed", "allowed", "refused", "refused", "refused"]
    assert proc.stdout.strip() == f"{expected} ()"


def _leader(conn: Any) -> None:  # pragma: no cover - runs in a child process
    from urdflint.server.worker import own_process_group

    own_process_group()
    child = subprocess.Popen(["sleep", "60"])
    conn.send(child.pid)
    time.sleep(60)


def _gone(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return True
    return state == "Z"


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
def test_killing_a_worker_kills_the_engines_it_started() -> None:
    from urdflint.server.pool import Worker

    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe()
    process = ctx.Process(target=_leader, args=(child,), daemon=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # fork with threads (3.12+)
        process.start()
    assert parent.poll(30)
    grandchild = int(parent.recv())
    Worker(process, parent).kill()
    deadline = time.monotonic() + 10
    while not _gone(grandchild) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _gone(grandchild)
