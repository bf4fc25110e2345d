"""Hostile uploads for the service tests, shared by the TestClient and the live-server tests.

Each :class:`Case` is one request; ``status`` is the answer it must get and ``codes`` the
finding codes that must be among the findings (a 200 answer). Every answer is also checked
for leaks (:func:`leaks`): nothing of ``/etc/passwd``, of the server's environment, of an
expanded entity bomb, or of the server's own folders may appear in it. ``trap`` is the URL
of a listening socket the server must never connect to.
"""

from __future__ import annotations

import io
import socket
import stat
import threading
import warnings
import zipfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from urdflint.server.worker import TETRA

from tests.test_hostile_input import BILLION_LAUGHS

SECRET = "s3cr3t-do-not-leak"  # set in the live server's environment
LEAK_MARKERS = ("root:x:0:0", "root:*:0:0", "/bin/bash", "/usr/sbin/nologin", SECRET, "lollollol")

ROBOT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1.57" upper="1.57" effort="30" velocity="2"/>
  </joint>
  <link name="upper_arm">
    <inertial>
      <origin xyz="0 0 0.15" rpy="0 0 0"/>
      <mass value="1.0"/>
      <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.00833" iyz="0" izz="0.00167"/>
    </inertial>
    <visual>
      <origin xyz="0 0 0.15" rpy="0 0 0"/>
      <geometry>{geometry}</geometry>
    </visual>
  </link>
</robot>
"""
BOX = '<box size="0.1 0.1 0.3"/>'

STL = TETRA.encode()  # the tetrahedron /readyz loads, as a mesh file

LAUGHS = BILLION_LAUGHS


def robot(geometry: str = BOX) -> str:
    return ROBOT.replace("{geometry}", geometry)


def mesh_robot(uri: str) -> str:
    return robot(f'<mesh filename="{uri}"/>')


def xacro(body: str) -> str:
    return (
        '<?xml version="1.0"?>\n<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'{body}\n  <link name="base"/>\n</robot>\n'
    )


# -- zips ---------------------------------------------------------------------------------------


def make_zip(members: list[tuple[str, bytes]], compression: int = zipfile.ZIP_DEFLATED) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression) as zf, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a duplicate name is one of the attacks
        for name, data in members:
            zf.writestr(zipfile.ZipInfo(name), data, compress_type=compression)
    return buf.getvalue()


def symlink_zip(name: str = "pkg/meshes/box.stl", target: str = "/etc/passwd") -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        info = zipfile.ZipInfo(name)
        info.create_system = 3
        info.external_attr = (stat.S_IFLNK | 0o777) << 16
        zf.writestr(info, target)
    return buf.getvalue()


def encrypted_zip() -> bytes:
    """A member flagged as encrypted (zipfile cannot write one: the flag bits are patched)."""
    data = bytearray(make_zip([("pkg/meshes/box.stl", STL)]))
    for magic, offset in ((b"PK\x03\x04", 6), (b"PK\x01\x02", 8)):
        at = data.find(magic)
        data[at + offset] |= 0x1
    return bytes(data)


def bomb_zip(megabytes: int = 40) -> bytes:
    """One member of zeros: a few tens of kB that inflate to ``megabytes`` MiB."""
    buf = io.BytesIO()
    with (
        zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as zf,
        zf.open("pkg/meshes/huge.stl", "w") as out,
    ):
        chunk = bytes(2**20)
        for _ in range(megabytes):
            out.write(chunk)
    return buf.getvalue()


MESHES = make_zip([("pkg/meshes/box.stl", STL)])


# -- cases ------------------------------------------------------------------------------------


@dataclass
class Case:
    id: str
    status: int
    codes: tuple[str, ...] = ()
    raw: str | None = None  # a raw application/xml body
    urdf: tuple[str, str] | None = None  # (file name, text) as the multipart 'urdf' part
    meshes: bytes | None = None
    params: dict[str, str] = field(default_factory=dict)
    absent: tuple[str, ...] = ()  # finding codes that must NOT be reported
    detail: str = ""  # words (a|b) one of which the 422 reason must contain

    def request(self) -> dict[str, Any]:
        if self.raw is not None:
            return {
                "content": self.raw.encode(),
                "headers": {"content-type": "application/xml"},
                "params": self.params,
            }
        files: dict[str, tuple[str, bytes]] = {}
        if self.urdf is not None:
            files["urdf"] = (self.urdf[0], self.urdf[1].encode())
        if self.meshes is not None:
            files["meshes"] = ("meshes.zip", self.meshes)
        return {"files": files, "params": self.params}


def cases(trap: str) -> list[Case]:
    """Every attack, with ``trap`` (``http://127.0.0.1:PORT``) as the network bait."""
    xml = [
        Case("billion-laughs", 200, ("X002",), raw=LAUGHS),
        Case(
            "xxe-file",
            200,
            ("X002",),
            raw='<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n'
            '<robot name="&x;"><link name="&x;"/></robot>\n',
        ),
        Case(
            "xxe-http",
            200,
            ("X002",),
            raw=f'<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "{trap}/xxe">]>\n'
            '<robot name="r"><link name="&x;"/></robot>\n',
        ),
        Case(
            "dtd-retrieval",
            200,
            ("X002",),
            raw=f'<?xml version="1.0"?>\n<!DOCTYPE robot SYSTEM "{trap}/robot.dtd">\n'
            '<robot name="r"><link name="a"/></robot>\n',
        ),
        Case(
            "parameter-entity",
            200,
            ("X002",),
            raw=f'<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY % p SYSTEM "{trap}/p.dtd"> %p;]>\n'
            '<robot name="r"><link name="a"/></robot>\n',
        ),
        Case(
            "xinclude",
            200,
            raw='<robot name="r" xmlns:xi="http://www.w3.org/2001/XInclude"><link name="a"/>'
            '<xi:include href="file:///etc/passwd" parse="text"/></robot>\n',
        ),
        Case(
            "xxe-in-xacro",
            200,
            ("X002",),
            urdf=(
                "robot.xacro",
                '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n'
                '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="&x;"/>'
                "</robot>\n",
            ),
        ),
    ]
    meshes = [
        Case("mesh-file-uri", 200, ("C004",), urdf=("r.urdf", mesh_robot("file:///etc/passwd"))),
        Case(
            "mesh-dotdot",
            200,
            ("C004",),
            urdf=("r.urdf", mesh_robot("../../../../../../../../etc/passwd")),
            meshes=MESHES,
        ),
        Case("mesh-absolute", 200, ("C004",), urdf=("r.urdf", mesh_robot("/etc/passwd"))),
        Case(
            "mesh-package-not-uploaded",
            200,
            ("C004",),
            urdf=("r.urdf", mesh_robot("package://not_uploaded/meshes/box.stl")),
            meshes=MESHES,
        ),
        Case(
            "mesh-package-escape",
            200,
            ("C004",),
            urdf=("r.urdf", mesh_robot("package://pkg/../../../../../../etc/passwd")),
            meshes=MESHES,
        ),
        Case("mesh-http", 200, ("C004",), urdf=("r.urdf", mesh_robot(f"{trap}/m.stl"))),
        Case(
            "mesh-symlinked-folder",
            422,
            urdf=("r.urdf", mesh_robot("package://pkg/meshes/box.stl")),
            meshes=symlink_zip("pkg", "/etc"),
            detail="symbolic link",
        ),
    ]
    xacros = [
        Case(
            f"xacro-{name}",
            200,
            ("X010",),
            urdf=("robot.xacro", xacro(body)),
        )
        for name, body in (
            ("include-absolute", '<xacro:include filename="/etc/passwd"/>'),
            ("include-dotdot", '<xacro:include filename="../../../../../../../etc/passwd"/>'),
            ("include-file-uri", '<xacro:include filename="file:///etc/passwd"/>'),
            ("include-http", f'<xacro:include filename="{trap}/x.xacro"/>'),
            ("find-missing", '<xacro:include filename="$(find secret_pkg)/x.xacro"/>'),
            ("yaml", "<link name=\"${xacro.load_yaml('/etc/passwd')}\"/>"),
            ("sandbox", "<link name=\"${''.__class__.__mro__}\"/>"),
            (
                "env",
                '<xacro:property name="y" value="$(env URDFLINT_TEST_SECRET)"/><link name="${y}"/>',
            ),
        )
    ]
    xacros.append(
        Case(
            "xacro-optenv",
            200,
            urdf=(
                "robot.xacro",
                xacro('<link name="$(optenv URDFLINT_TEST_SECRET hidden)"/>'),
            ),
        )
    )
    zips = [
        Case(f"zip-{name}", 422, urdf=("r.urdf", robot()), meshes=data, detail=word)
        for name, data, word in (
            ("slip-dotdot", make_zip([("../evil.stl", STL)]), "out of its folder"),
            ("slip-inner-dotdot", make_zip([("pkg/../../evil.stl", STL)]), "out of its folder"),
            ("slip-absolute", make_zip([("/tmp/evil.stl", STL)]), "absolute"),
            ("slip-backslash", make_zip([("..\\..\\evil.stl", STL)]), "illegal name"),
            ("slip-drive", make_zip([("C:/evil.stl", STL)]), "drive"),
            ("symlink", symlink_zip(), "symbolic link"),
            ("encrypted", encrypted_zip(), "encrypted"),
            ("nested-by-name", make_zip([("pkg/inner.zip", MESHES)]), "another archive"),
            ("nested-by-content", make_zip([("pkg/meshes/box.stl", MESHES)]), "another archive"),
            ("nested-gzip", make_zip([("pkg/m.stl", b"\x1f\x8b\x08\x00" + bytes(64))]), "archive"),
            ("bomb", bomb_zip(40), "zip bomb|expands to more than"),
            ("duplicate", make_zip([("pkg/a.stl", STL), ("pkg/a.stl", STL)]), "twice"),
            ("not-a-zip", b"this is not a zip file at all", "not a readable zip"),
        )
    ]
    return xml + meshes + xacros + zips


def leaks(text: str, *folders: str) -> list[str]:
    """What of the forbidden content appears in an answer."""
    found = [m for m in LEAK_MARKERS if m in text]
    found += [f for f in folders if f and f in text]
    return found


def check_answer(case: Case, response: Any, *folders: str) -> None:
    text = response.text
    assert response.status_code == case.status, (case.id, response.status_code, text[:500])
    assert not leaks(text, *folders), (case.id, leaks(text, *folders))
    if case.status == 200:
        data = response.json()
        codes = {f["code"] for f in data["findings"]}
        assert set(case.codes) <= codes, (case.id, sorted(codes))
        assert not set(case.absent) & codes, (case.id, sorted(codes))
        assert "U001" not in codes, (case.id, data["findings"])
    elif case.detail:
        words = case.detail.split("|")
        assert any(w in response.json()["detail"] for w in words), (case.id, text)


# -- a network trap ---------------------------------------------------------------------------


@contextmanager
def network_trap() -> Iterator[tuple[str, Callable[[], list[Any]]]]:
    """A listening socket on loopback; yields its URL and a function listing connections."""
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(16)
    server.settimeout(0.2)
    hits: list[Any] = []
    stop = threading.Event()

    def accept() -> None:
        while not stop.is_set():
            try:
                conn, peer = server.accept()
            except OSError:
                continue
            hits.append(peer)
            conn.close()

    thread = threading.Thread(target=accept, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.getsockname()[1]}", lambda: list(hits)
    finally:
        stop.set()
        thread.join(2)
        server.close()
