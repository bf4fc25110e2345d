"""GitHub Actions annotations: every line of a real run is a well-formed workflow command."""

from __future__ import annotations

import re
import subprocess
import sys

from tests.conftest import FIXTURES, ROOT, corpus_models, needs_corpus
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.formatters import RunInfo, github

BROKEN = (FIXTURES / "models" / "broken_arm.urdf").relative_to(ROOT)

# ::error file=...,line=N,endLine=N,col=N,title=...::message  (values escaped, one line each)
COMMAND = re.compile(
    r"::(?P<level>error|warning|notice) "
    r"file=(?P<file>[^,:\r\n]+),line=(?P<line>[1-9]\d*),endLine=(?P=line),col=[1-9]\d*,"
    r"title=urdflint \((?P<code>[A-Z]\d{3})\)"
    r"::(?P<message>[^\r\n]+)"
)
ESCAPES = {"%25": "%", "%0D": "\r", "%0A": "\n", "%3A": ":", "%2C": ","}
RAW_PERCENT = {  # a raw % would be misread as the start of an escape
    "data": re.compile(r"%(?!25|0D|0A)"),
    "property": re.compile(r"%(?!25|0D|0A|3A|2C)"),
}


def _unescape(text: str) -> str:
    return re.sub("%25|%0D|%0A|%3A|%2C", lambda m: ESCAPES[m.group()], text)


def _check(out: str) -> list[re.Match[str]]:
    lines = out.splitlines()
    assert lines and lines[-1].startswith("urdflint: ")
    commands = []
    group = None
    for line in lines[:-1]:
        if line.startswith("::group::"):
            assert group is None, "groups do not nest"
            group = _unescape(line[len("::group::") :])
            continue
        if line == "::endgroup::":
            assert group is not None
            group = None
            continue
        match = COMMAND.fullmatch(line)
        assert match, f"malformed annotation: {line!r}"
        assert not RAW_PERCENT["data"].search(match["message"])
        assert not RAW_PERCENT["property"].search(match["file"])
        assert _unescape(match["file"]) == group
        assert _unescape(match["message"]).startswith(f"{match['code']} ")
        commands.append(match)
    assert group is None
    return commands


def test_escaping_round_trips() -> None:
    message = "50% of 'a,b' :: bad\r\nsecond line"
    finding = Finding("r,1:x%.urdf", 2, 3, "X001", "invalid-xml", Severity.ERROR, message, "/r")
    (match,) = _check(github.render([finding], RunInfo("0", ("r,1:x%.urdf",))))
    assert _unescape(match["file"]) == "r,1:x%.urdf"
    assert _unescape(match["message"]) == f"X001 invalid-xml: {message}"


def test_broken_model_annotations_are_well_formed() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "github", str(BROKEN)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert proc.returncode == 1, proc.stderr
    levels = {m["level"] for m in _check(proc.stdout)}
    assert levels == {"error", "warning", "notice"}


@needs_corpus
def test_corpus_annotations_are_well_formed() -> None:
    models = corpus_models()
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "github", *map(str, models)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    assert proc.returncode in (0, 1), proc.stderr
    commands = _check(proc.stdout)
    assert commands, "the corpus has findings"
    assert {_unescape(m["file"]) for m in commands} <= {str(m) for m in models}
