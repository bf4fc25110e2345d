"""The HTTP API in-process (FastAPI's TestClient, real worker processes): statuses, options,
every attack, the limits, the temporary folders."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import ROOT
from tests.server import attacks
from tests.server.attacks import MESHES, STL, Case, make_zip, mesh_robot, robot

pytest.importorskip("fastapi")
with warnings.catch_warnings():  # starlette 1.x would like httpx2 for its TestClient
    warnings.simplefilter("ignore")
    from fastapi.testclient import TestClient
from urdflint.server import limits as limits_mod
from urdflint.server import options, uploads
from urdflint.server.app import create_app
from urdflint.server.limits import Limits

KiB = 1024


@pytest.fixture(scope="module")
def folders(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("requests")


@pytest.fixture(scope="module")
def client(folders: Path) -> Iterator[TestClient]:
    limits = Limits(
        max_urdf_bytes=64 * KiB,
        max_zip_bytes=512 * KiB,
        max_unzipped_bytes=2 * 2**20,
        max_zip_members=50,
        timeout=30,
        jobs=2,
        queue=4,
        tmpdir=str(folders),
    )
    with TestClient(create_app(limits), raise_server_exceptions=False) as test_client:
        yield test_client


@pytest.fixture(scope="module")
def trap() -> Iterator[tuple[str, object]]:
    with attacks.network_trap() as found:
        yield found


def post(client: TestClient, **kwargs: object) -> object:
    return client.post("/v1/check", **kwargs)  # type: ignore[arg-type]


def xml(client: TestClient, text: str, **params: str) -> object:
    return client.post(
        "/v1/check",
        content=text.encode(),
        headers={"content-type": "application/xml"},
        params=params,
    )


# -- the check --------------------------------------------------------------------------------


def test_raw_xml_gives_the_cli_document_plus_passed(client: TestClient) -> None:
    r = xml(client, robot(), filename="arm.urdf")
    assert r.status_code == 200
    data = r.json()
    assert list(data) == ["version", "tool", "findings", "summary", "models", "targets", "passed"]
    assert data["summary"]["files"] == 1
    assert data["passed"] is True
    assert set(data["models"]) == {"arm.urdf"}
    assert all(f["path"] == "arm.urdf" for f in data["findings"])


def test_broken_model_is_still_200_and_not_passed(client: TestClient) -> None:
    r = xml(client, "<robot name='a'><link name='b'></robot>")
    assert r.status_code == 200
    assert [f["code"] for f in r.json()["findings"]] == ["X001"]
    assert r.json()["passed"] is False


def test_multipart_with_meshes_resolves_packages(client: TestClient) -> None:
    r = post(
        client,
        files={
            "urdf": ("r.urdf", mesh_robot("package://pkg/meshes/box.stl").encode()),
            "meshes": ("m.zip", MESHES),
        },
    )
    assert r.status_code == 200
    assert not {"C004", "C005"} & {f["code"] for f in r.json()["findings"]}


def test_package_xml_in_the_zip_names_its_folder(client: TestClient) -> None:
    manifest = b"<package format='2'><name>my_robot</name></package>"
    zipped = make_zip(
        [
            ("src/my_robot_description/package.xml", manifest),
            ("src/my_robot_description/m.stl", STL),
        ]
    )
    r = post(
        client,
        files={
            "urdf": ("r.urdf", mesh_robot("package://my_robot/m.stl").encode()),
            "meshes": ("m.zip", zipped),
        },
    )
    assert r.status_code == 200
    assert "C004" not in {f["code"] for f in r.json()["findings"]}


def test_relative_mesh_resolves_against_the_zip_root(client: TestClient) -> None:
    r = post(
        client,
        files={
            "urdf": ("r.urdf", mesh_robot("pkg/meshes/box.stl").encode()),
            "meshes": ("m.zip", MESHES),
        },
    )
    assert "C004" not in {f["code"] for f in r.json()["findings"]}


def test_urdf_as_a_text_field_and_an_empty_meshes_part(client: TestClient) -> None:
    r = post(
        client,
        data={"urdf": robot(), "filename": "pasted.urdf", "target": "gz-sim"},
        files={"meshes": ("", b"")},
    )
    assert r.status_code == 200, r.text
    assert set(r.json()["models"]) == {"pasted.urdf"}


def test_options_from_query_and_form(client: TestClient) -> None:
    r = post(
        client,
        files={"urdf": ("r.urdf", robot().encode())},
        data={"select": "I,J", "ignore": "J011", "fail_on": "info", "expect_mass": "5±1%"},
        params={"select": "S"},
    )
    assert r.status_code == 200, r.text
    data = r.json()
    codes = {f["code"] for f in data["findings"]}
    assert "J011" not in codes
    assert codes <= {"P003", "U004"} | {c for c in codes if c[0] in "IJS"}
    assert data["passed"] is (not data["findings"])


def test_expect_mass_and_xacro_args(client: TestClient) -> None:
    text = attacks.xacro(
        '<xacro:arg name="m" default="1"/><link name="l"><inertial><mass value="$(arg m)"/>'
        '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="base"/><child link="l"/></joint>'
    )
    r = post(
        client,
        files={"urdf": ("r.xacro", text.encode())},
        data={"xacro_args": "m:=7", "expect_mass": "7", "select": "P003"},
    )
    assert r.status_code == 200, r.text
    codes = [f["code"] for f in r.json()["findings"]]
    assert "P003" not in codes and "X010" not in codes
    r = post(client, files={"urdf": ("r.xacro", text.encode())}, data={"expect_mass": "7"})
    assert "P003" in [f["code"] for f in r.json()["findings"]]


def test_config_json_is_applied(client: TestClient) -> None:
    cfg = json.dumps({"select": ["J011"], "severity": {"J011": "error"}})
    r = xml(client, robot().replace('<origin xyz="0 0 0.1" rpy="0 0 0"/>', ""), config=cfg)
    assert r.status_code == 200, r.text
    found = r.json()["findings"]
    assert [(f["code"], f["severity"]) for f in found] == [("J011", "error")]
    assert r.json()["passed"] is False


def test_svg_is_added_when_asked(client: TestClient) -> None:
    pytest.importorskip("urdflint.outputs.svg")
    r = xml(client, robot(), svg="true", filename="arm.urdf")
    assert r.status_code == 200
    assert r.json()["svg"]["arm.urdf"].lstrip().startswith("<svg")
    assert "svg" not in xml(client, robot()).json()


def test_other_formats(client: TestClient) -> None:
    r = xml(client, robot(), format="text")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/plain")
    assert "urdflint:" in r.text
    r = xml(client, robot(), format="sarif")
    try:
        import urdflint.outputs.formatters.sarif  # noqa: F401
    except ImportError:
        assert r.status_code == 422
    else:
        assert r.status_code == 200, r.text
        assert r.headers["content-type"].startswith("application/sarif+json")
        rules = json.loads(r.text)["runs"][0]["tool"]["driver"]["rules"]
        assert rules and all(  # each rule links to this service's page of it
            rule["helpUri"] == f"http://testserver/rules/{rule['id']}" for rule in rules
        )
        page = client.get(rules[0]["helpUri"].removeprefix("http://testserver"))
        assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")


# -- malformed requests -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("params", "word"),
    [
        ({"select": "Z999"}, "unknown rule"),
        ({"ignore": "nonsense-rule"}, "unknown rule"),
        ({"target": "webots"}, "unknown target"),
        ({"fail_on": "sometimes"}, "fail_on"),
        ({"expect_mass": "heavy"}, "expect_mass"),
        ({"expect_com": "1,2"}, "expect_com"),
        ({"xacro_args": "novalue"}, "xacro_args"),
        ({"q": "shoulder"}, "q"),
        ({"payload": "heavy"}, "payload"),
        ({"payload": "-2@tool0"}, "payload"),
        ({"payload": "2@"}, "no link after @"),
        ({"gravity": "0,0"}, "gravity"),
        ({"gravity": "0,0,nan"}, "gravity"),
        ({"gravity": "1e308,0,0"}, "stronger than 1000"),
        ({"payload": "1e308@tool"}, "more than 1e+06 kg"),
        ({"config": '{"statics": {"payload": true}}'}, "statics"),
        ({"config": "{not json"}, "not valid JSON"),
        ({"config": '{"bogus": 1}'}, "unknown configuration key"),
        ({"config": '{"package-paths": {"p": "/etc"}}'}, "package-paths"),
        ({"format": "pdf"}, "format"),
        ({"svg": "perhaps"}, "svg"),
    ],
)
def test_bad_options_are_422_with_a_reason(client: TestClient, params: dict, word: str) -> None:
    r = xml(client, robot(), **params)
    assert r.status_code == 422, r.text
    assert word in r.json()["detail"]


def test_malformed_multipart_requests(client: TestClient) -> None:
    cases = [
        {"files": {"meshes": ("m.zip", MESHES)}},  # no urdf
        {"files": {"urdf": ("r.urdf", b"<robot/>")}, "data": {"colour": "red"}},  # unknown field
        {"files": {"urdf": ("r.urdf", b"<robot/>"), "other": ("x.stl", STL)}},  # extra file
        {"files": [("urdf", ("a.urdf", b"<robot/>")), ("urdf", ("b.urdf", b"<robot/>"))]},
    ]
    for kwargs in cases:
        r = post(client, **kwargs)
        assert r.status_code == 422, (kwargs, r.text)
    r = client.post(
        "/v1/check",
        content=b'--xyz\r\nContent-Disposition: form-data; name="urdf"\r\n\r\n<rob',
        headers={"content-type": "multipart/form-data; boundary=xyz"},
    )
    assert r.status_code in (200, 422), r.text  # a truncated body: parsed or refused, never 500


@pytest.mark.parametrize(
    ("content_type", "kwargs"),
    [
        ("text/plain", {}),
        ("application/json", {}),
        (None, {}),
        ("application/x-www-form-urlencoded", {}),
    ],
)
def test_wrong_content_type_is_415(
    client: TestClient, content_type: str | None, kwargs: dict
) -> None:
    headers = {"content-type": content_type} if content_type else {}
    r = client.post("/v1/check", content=robot().encode(), headers=headers)
    assert r.status_code == 415, r.text


def test_wrong_file_kind_is_415(client: TestClient) -> None:
    r = post(client, files={"urdf": ("robot.txt", robot().encode())})
    assert r.status_code == 415
    assert ".urdf" in r.json()["detail"]
    assert xml(client, robot(), filename="robot.sh").status_code == 415


# -- sizes --------------------------------------------------------------------------------------


def test_too_large_bodies_are_413(client: TestClient) -> None:
    big = robot() + "<!--" + "x" * (70 * KiB) + "-->"
    assert xml(client, big).status_code == 413  # Content-Length over the limit

    def chunks() -> Iterator[bytes]:  # no Content-Length: counted as it arrives
        yield robot().encode()
        for _ in range(80):
            yield b"<!--" + b"x" * KiB + b"-->"

    r = client.post("/v1/check", content=chunks(), headers={"content-type": "application/xml"})
    assert r.status_code == 413
    r = post(client, files={"urdf": ("r.urdf", big.encode())})
    assert r.status_code == 413
    r = post(
        client,
        files={"urdf": ("r.urdf", robot().encode()), "meshes": ("m.zip", os.urandom(600 * KiB))},
    )
    assert r.status_code == 413


def test_zip_caps(client: TestClient) -> None:
    many = make_zip([(f"pkg/{i}.stl", b"x") for i in range(60)])
    r = post(client, files={"urdf": ("r.urdf", robot().encode()), "meshes": ("m.zip", many)})
    assert r.status_code == 422 and "members" in r.json()["detail"]
    # 12 members of 200 KiB (each under the ratio check's floor): 2.4 MiB, over the 2 MiB cap
    spread = make_zip([(f"pkg/{i}.stl", bytes(200 * KiB)) for i in range(12)])
    r = post(client, files={"urdf": ("r.urdf", robot().encode()), "meshes": ("m.zip", spread)})
    assert r.status_code == 422 and "expands to more than" in r.json()["detail"], r.text


# -- attacks --------------------------------------------------------------------------------


def test_every_attack_is_refused(
    client: TestClient, trap: tuple[str, object], folders: Path
) -> None:
    url, hits = trap
    for case in attacks.cases(url):
        attacks.check_answer(case, post(client, **case.request()), str(folders))
    assert hits() == []  # type: ignore[operator]
    assert list(folders.iterdir()) == []  # every request folder was removed


def test_a_file_outside_never_reaches_a_rule(client: TestClient, tmp_path: Path) -> None:
    secret = tmp_path / "secret.stl"
    secret.write_bytes(STL)
    r = post(client, files={"urdf": ("r.urdf", mesh_robot(str(secret)).encode())})
    found = [f for f in r.json()["findings"] if f["code"] == "C004"]
    assert found and "outside" in found[0]["message"]
    assert not {"C005", "C006", "I007"} & {f["code"] for f in r.json()["findings"]}


# -- the other endpoints -----------------------------------------------------------------------


def test_probes_and_metadata(client: TestClient) -> None:
    assert client.get("/healthz").json() == {"status": "ok"}
    ready = client.get("/readyz")
    assert ready.status_code == 200, ready.text
    caps = ready.json()["capabilities"]
    for name in ("pinocchio", "trimesh"):
        if caps[name]["available"]:
            assert caps[name]["works"] is True
    assert ready.json()["limits"]["jobs"] == 2
    version = client.get("/version").json()
    assert version["urdflint"] and version["lxml"]
    assert client.get("/openapi.json").json()["paths"]["/v1/check"]["post"]["requestBody"]


def test_rules_endpoints_match_the_cli(client: TestClient) -> None:
    listed = client.get("/v1/rules").json()
    cli = subprocess.run(
        [sys.executable, "-m", "urdflint", "rules", "--format", "json"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert listed == json.loads(cli.stdout)
    one = client.get("/v1/rules/triangle-inequality").json()
    assert one["code"] == "I005"
    for key, args in (("markdown", ["--long"]), ("short_markdown", [])):
        explained = subprocess.run(
            [sys.executable, "-m", "urdflint", "explain", "I005", *args],
            capture_output=True,
            text=True,
        ).stdout
        assert one[key] == explained
    assert one["sections"]["How to fix"]
    assert client.get("/v1/rules/Z999").status_code == 404


def test_web_page_and_static_files(client: TestClient) -> None:
    r = client.get("/")
    assert r.status_code == 200
    assert r.headers["x-content-type-options"] == "nosniff"
    static = ROOT / "server" / "static"
    if (static / "index.html").is_file():
        assert r.headers["content-type"].startswith("text/html")
        for item in static.iterdir():
            if item.is_file():
                assert client.get(f"/static/{item.name}").status_code == 200
    assert client.get("/static/../app.py").status_code == 404


def test_static_files_ship_in_the_wheel() -> None:
    import tomllib

    data = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "static/*" in data["tool"]["setuptools"]["package-data"]["urdflint.server"]


# -- units ------------------------------------------------------------------------------------


def test_limits_from_the_environment() -> None:
    found = Limits.from_env(
        {"URDFLINT_MAX_URDF_BYTES": "2M", "URDFLINT_JOBS": "3", "URDFLINT_TIMEOUT": "2.5"}
    )
    assert (found.max_urdf_bytes, found.jobs, found.timeout) == (2 * 2**20, 3, 2.5)
    assert Limits.from_env({}).max_zip_bytes == 100 * 2**20
    assert Limits.from_env({}).jobs >= 1
    for bad in (
        {"URDFLINT_MAX_URDF_BYTES": "lots"},
        {"URDFLINT_TIMEOUT": "0"},
        {"URDFLINT_JOBS": "-1"},
    ):
        with pytest.raises(limits_mod.LimitError):
            Limits.from_env(bad)
    assert limits_mod.parse_size("64k") == 65536 and limits_mod.parse_size("1GiB") == 2**30


def test_serve_refuses_bad_limits() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "serve", "--port", "0"],
        env={**os.environ, "URDFLINT_TIMEOUT": "soon"},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2 and "URDFLINT_TIMEOUT" in proc.stderr


def test_upload_names() -> None:
    assert uploads.urdf_name("../../etc/robot.urdf") == "robot.urdf"
    assert uploads.urdf_name("C:\\x\\my robot.xacro") == "my_robot.xacro"
    assert uploads.urdf_name(None) == "robot.urdf"
    assert uploads.urdf_name(".hidden.urdf") == "hidden.urdf"
    with pytest.raises(ValueError):
        uploads.urdf_name("robot.py")


def test_option_merging() -> None:
    values = options.merge(
        [("select", "I"), ("fail-on", "error"), ("unknown", "x")],
        [("select", "J001,J002"), ("fail_on", "warning"), ("xacro_arg", "a:=1,2,b:=3")],
    )
    assert values["select"] == ["I", "J001,J002"]
    assert values["fail_on"] == ["warning"]
    parsed = options.parse(values)
    assert parsed.settings.select == ("I", "J001", "J002")
    assert parsed.settings.fail_on == "warning"
    assert parsed.settings.xacro_args == {"a": "1,2", "b": "3"}
    with pytest.raises(options.OptionError):
        options.merge([], [("bogus", "1")])


def test_the_fence_refuses_files_network_and_processes(tmp_path: Path) -> None:
    """The worker's audit hook, in a child process (audit hooks cannot be removed)."""
    code = f"""
import os, socket, subprocess, pathlib
from urdflint.server import worker
root = pathlib.Path({str(tmp_path)!r})
results = []
with worker.fenced(root) as denied:
    for attempt in (
        lambda: open("/etc/passwd").read(),
        lambda: os.listdir("/etc"),
        lambda: open(root.parent / "elsewhere.txt", "w"),
        lambda: socket.create_connection(("127.0.0.1", 9), timeout=1),
        lambda: socket.getaddrinfo("example.com", 80),
        lambda: subprocess.run(["true"]),
        lambda: os.system("true"),
    ):
        try:
            attempt()
            results.append("allowed")
        except PermissionError:
            results.append("refused")
    (root / "inside.txt").write_text("ok")
    results.append((root / "inside.txt").read_text())
    import tempfile
    results.append(tempfile.gettempdir().startswith(str(root)))
print(results)
open("/etc/hostname").close()  # the fence is off between jobs
"""
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == str(["refused"] * 7 + ["ok", True])


def test_zip_member_names() -> None:
    assert uploads.member_path("a/b.stl").parts == ("a", "b.stl")
    for bad in ("../a", "a/../../b", "/etc/passwd", "a\\b", "C:/x", "a\x00b", ""):
        with pytest.raises(uploads.Rejected):
            uploads.member_path(bad)


def test_case_ids_are_unique() -> None:
    ids = [c.id for c in attacks.cases("http://127.0.0.1:9")]
    assert len(ids) == len(set(ids))
    assert isinstance(attacks.cases("x")[0], Case)


@pytest.mark.parametrize(
    "cfg",
    [
        "[]",
        '"select"',
        '{"select": 5}',
        '{"expect": {"mass": "heavy"}}',
        '{"expect": {"q": {"j": []}}}',
        '{"rules": 1}',
        '{"rules": {"I005": {"nope": 1}}}',
        '{"severity": {"I005": 5}}',
        '{"targets": ["webots"]}',
        '{"xacro-args": {"a": [1]}}',
        '{"per-file-ignores": {"*": 7}}',
        "[" * 10_000 + "]" * 10_000,
    ],
)
def test_odd_configs_are_422_never_500(client: TestClient, cfg: str) -> None:
    r = post(client, files={"urdf": ("r.urdf", robot().encode())}, data={"config": cfg})
    assert r.status_code == 422, r.text
    assert r.json()["detail"].startswith("config")


# -- the worker pool ---------------------------------------------------------------------------


class _Exits:
    """Unpickling this in the worker ends the worker (a stand-in for a native crash)."""

    def __reduce__(self) -> tuple[object, tuple[int]]:
        return (os._exit, (3,))


class _Sleeps:
    def __reduce__(self) -> tuple[object, tuple[float]]:
        import time

        return (time.sleep, (30.0,))


def test_pool_kills_overrunning_and_replaces_dead_workers(tmp_path: Path) -> None:
    import asyncio

    from urdflint.server.pool import Busy, JobTimeout, Pool, WorkerDied
    from urdflint.server.worker import ReadyJob

    async def scenario() -> list[object]:
        pool = Pool(size=1, timeout=1.5)
        seen: list[object] = []
        try:
            await pool.start()
            first = pool.pids()
            try:
                await pool.run(_Exits())
            except WorkerDied as exc:
                seen.append(exc.exitcode)
            sleeper = asyncio.ensure_future(pool.run(_Sleeps()))
            await asyncio.sleep(0.2)
            try:
                await pool.run(_Sleeps(), wait=0.1)  # the only worker is taken
            except Busy:
                seen.append("busy")
            try:
                await sleeper
            except JobTimeout:
                seen.append("timeout")
            folder = tmp_path / "ready"
            folder.mkdir()
            answer = await pool.run(ReadyJob(str(folder)))
            seen.append(answer["status"])
            seen.append(first.isdisjoint(pool.pids()))  # a new process took the place
        finally:
            await pool.close()
        return seen

    assert asyncio.run(scenario()) == [3, "busy", "timeout", 200, True]


def test_page_has_a_strict_content_security_policy() -> None:
    from fastapi.testclient import TestClient
    from urdflint.server.app import create_app

    with TestClient(create_app()) as client:
        page = client.get("/")
        assert page.status_code == 200
        policy = page.headers["content-security-policy"]
        assert "default-src 'none'" in policy and "script-src 'self'" in policy
        script = client.get("/static/app.js")
        assert script.status_code == 200 and script.headers["cache-control"] == "no-cache"


def test_docs_and_rules_pages_are_served_offline() -> None:
    from fastapi.testclient import TestClient
    from urdflint.server.app import create_app

    with TestClient(create_app()) as client:
        for path, status in (("/docs", 200), ("/rules", 200), ("/rules/J001", 200)):
            page = client.get(path)
            assert page.status_code == status, path
            assert page.headers["content-type"].startswith("text/html")
            policy = page.headers["content-security-policy"]
            assert "default-src 'none'" in policy and "script-src 'self'" in policy
            assert "https://" not in page.text and "<script>" not in page.text  # same origin
        assert client.get("/rules/missing-limit").status_code == 200  # a name works too
        assert client.get("/rules/Z999").status_code == 404
        assert client.get("/redoc").status_code == 404  # ReDoc would need a CDN: not served
        docs = client.get("/docs").text
        for asset in (
            "/static/swagger-ui/swagger-ui-bundle.js",
            "/static/swagger-ui/swagger-ui.css",
        ):
            assert asset in docs
            assert client.get(asset).status_code == 200
        assert "/static/rules.js" in client.get("/rules").text
        assert client.get("/openapi.json").json()["paths"]["/v1/rules/{code}"]


def test_a_request_whose_worker_dies_gets_a_retryable_503(
    folders: Path, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    """A worker killed from outside while it checks a request: the client gets 503 with
    Retry-After (no verdict on its file), the death is logged with its reason, and the same
    request then passes on the replacement worker (issue 23, 7)."""
    import logging
    import signal

    from urdflint.server import pool as pool_mod

    limits = Limits(timeout=60, jobs=1, queue=4, tmpdir=str(folders))
    original = pool_mod.Worker.call
    killed: list[int] = []

    def dying(self: pool_mod.Worker, job: object, timeout: float) -> object:
        if not killed and type(job).__name__ == "CheckJob":
            killed.append(self.process.pid)  # killed from outside, the request in flight
            os.kill(self.process.pid, signal.SIGKILL)
            self.process.join(10)
        return original(self, job, timeout)

    monkeypatch.setattr(pool_mod.Worker, "call", dying)
    body = (robot() + f"<!-- {os.urandom(8).hex()} -->\n").encode()  # never seen: no cached answer
    headers = {"Content-Type": "application/xml"}
    with (
        caplog.at_level(logging.WARNING, logger="urdflint.server.pool"),
        TestClient(create_app(limits), raise_server_exceptions=False) as client,
    ):
        died = client.post("/v1/check", content=body, headers=headers)
        again = client.post("/v1/check", content=body, headers=headers)
    assert killed
    assert died.status_code == 503, died.text
    assert died.headers.get("Retry-After") == "1"
    assert "retry" in died.json()["detail"]
    assert again.status_code == 200, again.text
    deaths = [r for r in caplog.records if "died" in r.getMessage()]
    assert len(deaths) == 1 and "SIGKILL" in deaths[0].getMessage()


def test_readyz_is_503_while_every_worker_and_queue_place_is_taken(client: TestClient) -> None:
    """Readiness tells the truth: no capacity left (every worker busy and the queue full, as
    the admission count says), 503 with the reason; capacity back, 200 (issue 23, 7)."""
    assert client.get("/readyz").status_code == 200
    load = client.app.state.load  # type: ignore[attr-defined]
    limits = client.app.state.limits  # type: ignore[attr-defined]
    saved = load.active
    load.active = limits.jobs + limits.queue
    try:
        full = client.get("/readyz")
        assert full.status_code == 503
        assert full.json()["reason"] == "every lint worker and queue place is taken"
        assert full.headers.get("Retry-After") == "1"
        busy = client.post(
            "/v1/check", content=robot(), headers={"Content-Type": "application/xml"}
        )
        assert busy.status_code == 503  # the admission control says the same
    finally:
        load.active = saved
    assert client.get("/readyz").status_code == 200
