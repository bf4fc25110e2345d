"""The real robots in ../shared/corpus: no crash, valid JSON, only reviewed errors.

``REVIEWED_ERRORS`` is the set of error-level codes each robot is allowed to
produce: every one was read and judged a real defect (see the comments). A new
error code on a real robot fails this test until someone reviews it.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.conftest import CORPUS, corpus_models, needs_corpus

pytestmark = needs_corpus

REVIEWED_ERRORS: dict[str, set[str]] = {}


@pytest.fixture(scope="module")
def report() -> dict:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "json", str(CORPUS)],
        capture_output=True, text=True, timeout=600,
    )
    assert proc.returncode in (0, 1), proc.stderr
    assert proc.stderr == ""
    return json.loads(proc.stdout)


def test_every_robot_is_checked_without_internal_errors(report: dict) -> None:
    assert report["summary"]["files"] == len(corpus_models()) == 36
    assert not [f for f in report["findings"] if f["code"].startswith("U00") and f["code"] != "U002"]


def test_findings_are_well_formed(report: dict) -> None:
    for f in report["findings"]:
        assert f["line"] >= 1 and f["column"] >= 1
        assert f["element"].startswith("/robot")
        assert f["message"] and not f["message"].endswith(".")


@pytest.mark.parametrize("model", corpus_models(), ids=lambda p: p.parent.name)
def test_only_reviewed_errors(report: dict, model) -> None:
    robot = model.parent.name
    errors = {f["code"] for f in report["findings"] if f["path"] == str(model) and f["severity"] == "error"}
    assert errors == REVIEWED_ERRORS.get(robot, set()), f"{robot}: review these error codes"
