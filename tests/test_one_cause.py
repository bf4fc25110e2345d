"""One defect, one finding: P001 restates no reported finding; the cause carries the
Pinocchio effect, and the cause named is the first one urdfdom stops on (issue 24, 3)."""

from __future__ import annotations

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.engine import config

pytest.importorskip("pinocchio")

CASES = FIXTURES / "one_cause"


def _lint(name: str, **settings: object) -> list:
    base = {"targets": ("pinocchio", "gz-sim"), **settings}
    return lint_file(CASES / name, settings=config.Settings(**base))  # type: ignore[arg-type]


def test_an_unreadable_inertia_value_is_one_finding_with_pinocchio_s_effect() -> None:
    found = _lint("trailing_space.urdf")
    assert "P001" not in [f.code for f in found]
    (x004,) = [f for f in found if f.code == "X004"]
    assert (x004.line, x004.element) == (16, "/robot/link[@name='thumb']/inertial/inertia")
    assert "pinocchio" in dict(x004.effects)  # X004's own table: what the probe sees


def test_with_the_cause_ignored_p001_speaks_and_names_it() -> None:
    found = _lint("trailing_space.urdf", ignore=("X004",))
    (p001,) = [f for f in found if f.code == "P001"]
    assert "(X004 on line 16:" in p001.message


def test_urdfdom_stops_on_the_duplicate_link_before_any_loop() -> None:
    found = _lint("duplicate_and_loop.urdf")
    assert "P001" not in [f.code for f in found]
    (s001,) = [f for f in found if f.code == "S001"]
    assert s001.line == 24
    assert dict(s001.effects)["pinocchio"].consequence.key == "refused"
    (p001,) = [f for f in _lint("duplicate_and_loop.urdf", ignore=("S001",)) if f.code == "P001"]
    assert p001.message == (
        "Pinocchio refuses the model: urdfdom, its parser, stops at an error before the loop "
        "(see S001 duplicate-link on line 24)"
    )
