"""Bad and hostile input never gives a traceback: a finding or a one-line error."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_text

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<robot name="&lol9;"><link name="a"/></robot>
"""

XXE = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY xxe SYSTEM "file:///etc/passwd">]>
<robot name="r"><link name="&xxe;"/></robot>
"""

EXTERNAL_DTD = """<?xml version="1.0"?>
<!DOCTYPE robot SYSTEM "http://example.invalid/robot.dtd">
<robot name="r"><link name="a"/></robot>
"""


@pytest.mark.parametrize("text", [BILLION_LAUGHS, XXE, EXTERNAL_DTD], ids=["laughs", "xxe", "dtd"])
def test_doctype_documents_are_refused_not_expanded(text: str) -> None:
    found = lint_text(text)
    assert [f.code for f in found] == ["X002"]
    assert "passwd" not in found[0].message and "lollol" not in found[0].message


@pytest.mark.parametrize(
    "text",
    [
        "",
        "   ",
        "\x00\x01garbage",
        "<robot",
        "<robot name='a'><link></robot>",
        "<?xml version='1.0' encoding='klingon'?><robot/>",
        "<robot name='a'/><robot name='b'/>",
        "\ufeff<robot name='x'><link name='a'/></robot>",
    ],
)
def test_malformed_input_is_one_x001_finding(text: str) -> None:
    from urdflint.engine.linter import RECOVERED

    found = lint_text(text, targets=["ros"])  # not I013's lone links: a parsing test
    # what the recovered part of a broken file shows is marked as such (X001 stays the error)
    direct = [f for f in found if not f.message.endswith(RECOVERED)]
    assert [f.code for f in direct] in (["X001"], [])  # a BOM-prefixed robot is fine
    if found:
        assert found[0].line >= 1 and found[0].message
        assert all(f.code == "X001" or f.message.endswith(RECOVERED) for f in found)


def test_deep_nesting_is_refused_by_libxml2_limits() -> None:
    text = "<robot name='r'>" + "<a>" * 20000 + "</a>" * 20000 + "</robot>"
    assert [f.code for f in lint_text(text, select=("X001",))] == ["X001"]


def test_huge_file_is_refused_without_parsing(tmp_path: Path) -> None:
    from urdflint.engine import linter
    from urdflint.model import document

    data = b"<robot name='r'>" + b" " * (document.MAX_BYTES + 1) + b"</robot>"
    found = linter.lint_bytes(data, "huge.urdf").findings
    assert [f.code for f in found] == ["X001"] and "64 MiB" in found[0].message


def test_binary_garbage_file_from_cli(tmp_path: Path) -> None:
    path = tmp_path / "zip.urdf"
    path.write_bytes(b"PK\x03\x04" + bytes(range(256)) * 10)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "text", str(path)],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 1
    assert "X001" in proc.stdout and "Traceback" not in proc.stderr


def test_unreadable_file_is_one_line_error(tmp_path: Path) -> None:
    path = tmp_path / "secret.urdf"
    path.write_text((FIXTURES / "models" / "example_arm.urdf").read_text())
    path.chmod(0)
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", str(path)], capture_output=True, text=True
    )
    path.chmod(0o644)
    if proc.returncode == 0:  # running as root: permissions do not apply
        pytest.skip("file permissions are not enforced for this user")
    assert proc.returncode == 2 and "cannot read" in proc.stderr and "Traceback" not in proc.stderr
