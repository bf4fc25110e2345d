"""``POST /v1/fix`` in-process (FastAPI's TestClient, real worker processes): the fixed file,
its diff, what is left, the same limits and refusals as ``/v1/check``, and no edit ever
leaving the uploaded file."""

from __future__ import annotations

import asyncio
import importlib.util
import subprocess
import sys
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.server import attacks
from tests.server.attacks import STL, make_zip

pytest.importorskip("fastapi")
with warnings.catch_warnings():  # starlette 1.x would like httpx2 for its TestClient
    warnings.simplefilter("ignore")
    from fastapi.testclient import TestClient
from urdflint.server import fixing
from urdflint.server.app import create_app
from urdflint.server.limits import Guard, Limits

from urdflint.engine.fixes import forget_files
from urdflint.model.edits import Autofix, Edit

KiB = 1024
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# a non-unit axis (J008: safe fix) and inverted limits (J009: unsafe fix)
ARM = """<?xml version="1.0"?>
<robot name="arm">
  <!-- kept as written: comments, spacing, attribute order -->
  <link name="base_link"/>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <parent   link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 2"/>
    <limit lower="1.57" upper="-1.57" effort="30" velocity="2"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <mass value="1.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
</robot>
"""
AXIS_FIXED = ARM.replace('<axis xyz="0 0 2"/>', '<axis xyz="0 0 1"/>')
ALL_FIXED = AXIS_FIXED.replace('lower="1.57" upper="-1.57"', 'lower="-1.57" upper="1.57"')


@pytest.fixture(scope="module")
def folders(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("fix-requests")


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


def fix(client: TestClient, text: str, name: str = "arm.urdf", **data: Any) -> Any:
    meshes = data.pop("meshes", None)
    files: dict[str, tuple[str, bytes]] = {"urdf": (name, text.encode())}
    if meshes is not None:
        files["meshes"] = ("meshes.zip", meshes)
    return client.post("/v1/fix", files=files, data=data)


def codes(answer: dict[str, Any]) -> set[str]:
    return {f["code"] for f in answer["findings"]}


# -- the fix ----------------------------------------------------------------------------------


def test_safe_fixes_change_the_axis_only(client: TestClient) -> None:
    r = fix(client, ARM)
    assert r.status_code == 200, r.text
    data = r.json()
    assert list(data)[:5] == ["version", "tool", "fixed", "diff", "applied"]
    assert {"findings", "summary", "models", "passed"} <= set(data)
    assert data["fixed"] == AXIS_FIXED  # everything else byte for byte
    assert data["applied"] == 1
    assert data["diff"].splitlines()[:2] == ["--- arm.urdf", "+++ arm.urdf"]
    changed = [line for line in data["diff"].splitlines()[2:] if line[:1] in "+-"]
    assert changed == ['-    <axis xyz="0 0 2"/>', '+    <axis xyz="0 0 1"/>']
    # what is left is the check of the fixed file: the unsafe fix still waits
    assert "J008" not in codes(data) and "J009" in codes(data)
    j009 = next(f for f in data["findings"] if f["code"] == "J009")
    assert j009["autofix"]["applicability"] == "unsafe" and j009["line"] == 10
    assert data["passed"] is False  # J009 is an error
    assert data["summary"]["files"] == 1


def test_unsafe_fixes_swap_the_limits_too(client: TestClient) -> None:
    r = fix(client, ARM, unsafe_fixes="true")
    assert r.status_code == 200, r.text
    data = r.json()
    assert data["fixed"] == ALL_FIXED and data["applied"] == 2
    changed = [line for line in data["diff"].splitlines()[2:] if line[:1] in "+-"]
    assert changed == [
        '-    <axis xyz="0 0 2"/>',
        '-    <limit lower="1.57" upper="-1.57" effort="30" velocity="2"/>',
        '+    <axis xyz="0 0 1"/>',
        '+    <limit lower="-1.57" upper="1.57" effort="30" velocity="2"/>',
    ]
    assert not {"J008", "J009"} & codes(data)


def test_the_fixed_file_is_what_urdflint_fix_writes(client: TestClient, tmp_path: Path) -> None:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    subprocess.run(
        [sys.executable, "-m", "urdflint", "fix", "--unsafe-fixes", "--isolated", str(path)],
        capture_output=True,
        check=False,
    )
    assert fix(client, ARM, unsafe_fixes="on").json()["fixed"] == path.read_text()


def test_nothing_to_fix_returns_the_input(client: TestClient) -> None:
    clean = attacks.robot()
    data = fix(client, clean).json()
    assert data["fixed"] == clean and data["diff"] == "" and data["applied"] == 0
    broken = "<robot name='a'><link name='b'></robot>"
    data = fix(client, broken).json()
    assert data["fixed"] == broken and data["applied"] == 0 and codes(data) == {"X001"}


def test_raw_body_query_options_and_select(client: TestClient) -> None:
    r = client.post(
        "/v1/fix",
        content=ARM.encode(),
        headers={"content-type": "application/xml"},
        params={"unsafe_fixes": "true", "select": "J009", "filename": "mine.urdf"},
    )
    assert r.status_code == 200, r.text
    data = r.json()
    # only the selected rule ran, so only its fix applies
    assert data["fixed"] == ARM.replace('lower="1.57" upper="-1.57"', 'lower="-1.57" upper="1.57"')
    assert data["applied"] == 1 and data["diff"].startswith("--- mine.urdf\n+++ mine.urdf\n")
    assert set(data["models"]) == {"mine.urdf"}


def test_line_endings_and_a_missing_last_newline_are_kept(client: TestClient) -> None:
    crlf = ARM.replace("\n", "\r\n")
    data = fix(client, crlf).json()
    assert data["fixed"] == AXIS_FIXED.replace("\n", "\r\n") and data["applied"] == 1
    last = ARM.replace('<axis xyz="0 0 2"/>', "").replace(
        "</robot>\n",
        '<joint name="j" type="fixed"><parent link="base_link"/><child link="t"/>'
        '<axis xyz="1 0 0"/></joint><link name="t"/></robot>',
    )
    data = fix(client, last).json()
    assert data["fixed"] == last.replace('<axis xyz="1 0 0"/>', "")  # J006: ignored by fixed
    assert data["diff"].endswith("</robot>\n\\ No newline at end of file\n")


def test_svg_and_matrix_describe_the_fixed_file(client: TestClient) -> None:
    data = fix(client, ARM, matrix="true", unsafe_fixes="true").json()
    assert data["matrix"]
    flagged = {f["code"] for row in data["matrix"] for f in row["predicted"]["findings"]}
    assert "J009" not in flagged


@pytest.mark.skipif(importlib.util.find_spec("pinocchio") is None, reason="needs pinocchio")
def test_confirm_loads_the_fixed_file_in_the_engine(folders: Path) -> None:
    limits = Limits(timeout=60, jobs=1, queue=2, tmpdir=str(folders), allow_confirm=True)
    with TestClient(create_app(limits), raise_server_exceptions=False) as confirming:
        r = fix(confirming, ARM, unsafe_fixes="true", confirm="pinocchio", matrix="true")
    assert r.status_code == 200, r.text
    data = r.json()
    assert data["fixed"] == ALL_FIXED and data["applied"] == 2
    rows = {row["target"]: row for row in data["matrix"]}
    confirmed = rows["pinocchio"]["confirmed"]  # the engine loaded the fixed file
    assert confirmed["engine"] == "pinocchio" and confirmed["outcome"] == "loads"
    assert not attacks.leaks(str(data["findings"]), str(folders))
    assert list(folders.iterdir()) == []


# -- xacro --------------------------------------------------------------------------------------


def test_a_xacro_file_is_fixed_where_the_value_is_written(client: TestClient) -> None:
    text = ARM.replace('<robot name="arm">', f'<robot name="arm" {XACRO_NS}>')
    data = fix(client, text, "arm.urdf.xacro").json()
    assert data["fixed"] == AXIS_FIXED.replace(
        '<robot name="arm">', f'<robot name="arm" {XACRO_NS}>'
    )
    assert data["applied"] == 1 and "J008" not in codes(data)  # the fixed file, linted
    # a computed value is left alone, and the finding says why
    computed = text.replace('xyz="0 0 2"', 'xyz="0 0 ${1+1}"')
    data = fix(client, computed, "arm.xacro").json()
    assert data["fixed"] == computed and data["applied"] == 0
    j008 = next(f for f in data["findings"] if f["code"] == "J008")
    assert "computed by xacro" in j008["autofix"]["unavailable"]


INCLUDED = f"""<?xml version="1.0"?>
<robot {XACRO_NS}>
  <joint name="elbow" type="revolute">
    <parent link="upper_arm"/>
    <child link="forearm"/>
    <axis xyz="0 3 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="forearm"/>
</robot>
"""


def test_only_the_uploaded_file_is_edited_never_a_file_of_the_zip(client: TestClient) -> None:
    top = ARM.replace('<robot name="arm">', f'<robot name="arm" {XACRO_NS}>').replace(
        "</robot>", '  <xacro:include filename="pkg/urdf/elbow.xacro"/>\n</robot>'
    )
    zipped = make_zip([("pkg/urdf/elbow.xacro", INCLUDED.encode()), ("pkg/m.stl", STL)])
    data = fix(client, top, "arm.xacro", meshes=zipped).json()
    assert data["applied"] == 1 and "0 0 1" in data["fixed"]  # the upload's own axis
    elbow = next(f for f in data["findings"] if f["code"] == "J008")
    assert elbow["line"] == 6 and elbow["path"] == "pkg/urdf/elbow.xacro"
    assert [e["path"] for e in elbow["autofix"]["edits"]] == ["pkg/urdf/elbow.xacro"]
    assert "elbow.xacro" not in data["diff"]


def test_an_include_outside_the_upload_is_never_touched(client: TestClient, tmp_path: Path) -> None:
    outside = tmp_path / "outside.xacro"
    outside.write_text(INCLUDED)
    before = outside.stat()
    top = attacks.xacro(f'<xacro:include filename="{outside}"/>')
    for unsafe in ("false", "true"):
        data = fix(client, top, "robot.xacro", unsafe_fixes=unsafe).json()
        assert data["fixed"] == top and data["applied"] == 0 and data["diff"] == ""
        assert "X010" in codes(data)
        assert "elbow" not in str(data["findings"])  # its content never reached a rule
    after = outside.stat()
    assert outside.read_text() == INCLUDED
    assert (after.st_mtime_ns, after.st_size) == (before.st_mtime_ns, before.st_size)


def test_jobs_never_see_another_jobs_file(client: TestClient) -> None:
    """The same upload name with other content, one after the other: each fix is computed
    on its own file (the engine's source cache is emptied around every lint)."""
    text = ARM.replace('<robot name="arm">', f'<robot name="arm" {XACRO_NS}>')
    moved = text.replace("<!-- kept", "\n\n<!-- kept")
    for _ in range(3):
        for source, line in ((text, 9), (moved, 11)):
            r = client.post("/v1/check", files={"urdf": ("same.xacro", source.encode())})
            j008 = next(f for f in r.json()["findings"] if f["code"] == "J008")
            assert j008["autofix"]["edits"][0]["start"]["line"] == line
            assert fix(client, source, "same.xacro").json()["fixed"] == source.replace(
                "0 0 2", "0 0 1"
            )


# -- refusals, limits -----------------------------------------------------------------------------


def test_every_attack_is_refused_as_by_check(client: TestClient, folders: Path) -> None:
    with attacks.network_trap() as (url, hits):
        for case in attacks.cases(url):
            r = client.post("/v1/fix", **case.request())  # type: ignore[arg-type]
            attacks.check_answer(case, r, str(folders))
            if r.status_code == 200:
                data = r.json()
                sent = case.raw if case.raw is not None else (case.urdf or ("", ""))[1]
                assert data["fixed"] == sent and data["applied"] == 0, case.id
        assert hits() == []
    assert list(folders.iterdir()) == []  # every request folder was removed


@pytest.mark.parametrize(
    ("params", "word"),
    [
        ({"format": "sarif"}, "JSON only"),
        ({"format": "text"}, "JSON only"),
        ({"unsafe_fixes": "maybe"}, "unsafe_fixes"),
        ({"select": "Z999"}, "Z999"),
        ({"confirm": "mujoco"}, "allow-confirm"),
    ],
)
def test_bad_options_are_422(client: TestClient, params: dict[str, str], word: str) -> None:
    r = client.post(
        "/v1/fix", content=ARM.encode(), headers={"content-type": "text/xml"}, params=params
    )
    assert r.status_code == 422 and word in r.json()["detail"], r.text


def test_check_refuses_unsafe_fixes_and_keeps_its_formats(client: TestClient) -> None:
    r = client.post(
        "/v1/check", files={"urdf": ("a.urdf", ARM.encode())}, data={"unsafe_fixes": "1"}
    )
    assert r.status_code == 422 and "/v1/fix" in r.json()["detail"]
    r = client.post("/v1/check", files={"urdf": ("a.urdf", ARM.encode())}, data={"format": "text"})
    assert r.status_code == 200 and "fixed" not in r.text


def test_types_sizes_and_encodings(client: TestClient) -> None:
    r = client.post("/v1/fix", content=ARM.encode(), headers={"content-type": "text/plain"})
    assert r.status_code == 415
    r = client.post("/v1/fix", files={"urdf": ("arm.txt", ARM.encode())})
    assert r.status_code == 415
    big = ARM.replace("</robot>", "<!--" + "x" * (70 * KiB) + "--></robot>")
    r = client.post("/v1/fix", content=big.encode(), headers={"content-type": "application/xml"})
    assert r.status_code == 413
    r = client.post("/v1/fix", files={"urdf": ("arm.urdf", big.encode())})
    assert r.status_code == 413
    latin = ARM.replace("kept as written", "gardé tel quel").encode("latin-1")
    r = client.post("/v1/fix", files={"urdf": ("arm.urdf", latin)})
    assert r.status_code == 422 and "UTF-8" in r.json()["detail"]
    r = client.post("/v1/fix", files={"urdf": ("arm.urdf", b"")})  # an empty file: linted
    assert r.status_code == 200 and r.json()["fixed"] == "" and r.json()["applied"] == 0


def test_the_guard_admits_fix_requests_like_checks() -> None:
    """Body limits and admission control (503 when saturated) cover /v1/fix."""
    sent: list[dict[str, Any]] = []

    async def app(scope: Any, receive: Any, send: Any) -> None:  # never reached
        raise AssertionError("admitted")

    async def send(message: dict[str, Any]) -> None:
        sent.append(message)

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b"", "more_body": False}

    guard = Guard(app, Limits(max_urdf_bytes=100, jobs=1, queue=0))
    guard.active = 1  # every worker and queue place taken
    scope = {"type": "http", "path": "/v1/fix", "headers": [(b"content-type", b"text/xml")]}
    asyncio.run(guard(scope, receive, send))
    assert sent[0]["status"] == 503 and (b"retry-after", b"1") in sent[0]["headers"]
    sent.clear()
    guard.active = 0
    headers = [(b"content-type", b"text/xml"), (b"content-length", b"101")]
    asyncio.run(guard({**scope, "headers": headers}, receive, send))
    assert sent[0]["status"] == 413


def test_openapi_and_capabilities_describe_the_fix(client: TestClient) -> None:
    spec = client.get("/openapi.json").json()
    operation = spec["paths"]["/v1/fix"]["post"]
    form = operation["requestBody"]["content"]["multipart/form-data"]["schema"]["properties"]
    assert "unsafe_fixes" in form and "meshes" in form
    assert "unsafe_fixes" in {p["name"] for p in operation["parameters"]}
    assert client.get("/v1/capabilities").json()["fix"] is True


# -- units ----------------------------------------------------------------------------------------


def _fix(*paths: str, applicability: str = "safe") -> Autofix:
    edits = tuple(Edit(path, 0, 1, "x") for path in paths)
    return Autofix(applicability, "test", edits)  # type: ignore[arg-type]


def test_a_fix_is_kept_only_when_every_edit_is_in_the_upload(tmp_path: Path) -> None:
    target = tmp_path / "files" / "robot.urdf"
    kept = fixing.mine(_fix("robot.urdf", "robot.urdf"), "robot.urdf", target)
    assert kept is not None and {e.path for e in kept.edits} == {str(target)}
    for paths in (
        ("robot.urdf", "pkg/inc.xacro"),  # part of it elsewhere: left out whole
        ("/etc/passwd",),
        ("../robot.urdf",),
        (str(target),),  # findings name the upload by its name, never by a server path
        ("./robot.urdf",),
    ):
        assert fixing.mine(_fix(*paths), "robot.urdf", target) is None, paths
    unavailable = Autofix("safe", "t", (), "computed by xacro")
    assert fixing.mine(unavailable, "robot.urdf", target) is None
    assert fixing.mine(None, "robot.urdf", target) is None


class _Finding:
    def __init__(self, autofix: Autofix | None) -> None:
        self.autofix = autofix


class _Result:
    def __init__(self, *fixes: Autofix | None) -> None:
        self.findings = [_Finding(f) for f in fixes]


def test_rounds_never_write_outside_the_upload(tmp_path: Path) -> None:
    target = tmp_path / "robot.urdf"
    target.write_bytes(b"abcdef")
    outside = tmp_path / "outside.urdf"
    outside.write_bytes(b"abcdef")
    lints = iter(
        [
            _Result(
                _fix(str(outside)),
                _fix("outside.urdf"),
                Autofix("safe", "s", (Edit("robot.urdf", 0, 1, "A"),)),
                Autofix("unsafe", "u", (Edit("robot.urdf", 2, 3, "C"),)),
            ),
            _Result(Autofix("safe", "s", (Edit("robot.urdf", 1, 2, "B"),))),
            _Result(),
        ]
    )
    forget_files()
    result, original, applied = fixing.rounds(lambda: next(lints), target, "robot.urdf", False)
    assert original == b"abcdef" and applied == 2 and target.read_bytes() == b"ABcdef"
    assert outside.read_bytes() == b"abcdef"
    assert result.findings == []


def test_rounds_stop_after_four(tmp_path: Path) -> None:
    target = tmp_path / "robot.urdf"
    target.write_bytes(b"0")
    counter = iter(range(100))

    def lint() -> _Result:
        n = next(counter)
        return _Result(Autofix("safe", "s", (Edit("robot.urdf", 0, len(str(n)), str(n + 1)),)))

    _result, _original, applied = fixing.rounds(lint, target, "robot.urdf", True)
    assert applied == fixing.MAX_ROUNDS == 4 and target.read_bytes() == b"4"


def test_the_diff_marks_a_missing_last_newline() -> None:
    assert fixing.unified(b"a\n", b"a\n", "x") == ""
    diff = fixing.unified(b"a\nb", b"a\nc", "x.urdf")
    assert diff == (
        "--- x.urdf\n+++ x.urdf\n@@ -1,2 +1,2 @@\n a\n-b\n\\ No newline at end of file\n"
        "+c\n\\ No newline at end of file\n"
    )
