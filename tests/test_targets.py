"""Targets change the messages and severities of target rules, never structural validity."""

from __future__ import annotations

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.engine import config
from urdflint.model.finding import Severity

BROKEN = FIXTURES / "models" / "broken_arm.urdf"
COLOUR = FIXTURES / "rules" / "G002" / "bad.urdf"


def run(path, *targets: str, select=None):
    settings = config.from_mapping({"targets": list(targets)})
    return lint_file(path, select=select, settings=settings)


def test_colour_rule_follows_the_target() -> None:
    classic = [f for f in run(COLOUR, "gazebo-classic", select=("G002",))]
    sim = [f for f in run(COLOUR, "gz-sim", select=("G002",))]
    assert classic and all(f.severity is Severity.WARNING for f in classic)
    assert "Gazebo Classic" in classic[0].message
    assert sim and all(f.severity is Severity.INFO for f in sim)
    assert (
        run(COLOUR, "mujoco", select=("G002",)) == []
    )  # not aimed at Gazebo: the rule does not run


def test_structural_errors_do_not_depend_on_the_target() -> None:
    def errors(*targets: str) -> set[tuple[int, str]]:
        return {(f.line, f.code) for f in run(BROKEN, *targets) if f.severity is Severity.ERROR}

    assert errors("gazebo-classic") == errors("gz-sim") == errors("mujoco")
