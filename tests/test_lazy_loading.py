"""A run imports only what its selected rules need (cold start; issue 14)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import FIXTURES

SMALL = FIXTURES / "models" / "example_arm.urdf"


def imported_after(code: str) -> set[str]:
    probe = f"import sys\n{code}\nprint(' '.join(sorted(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return set(done.stdout.split())


def test_selecting_a_family_imports_only_that_family_and_urdflints_own() -> None:
    loaded = imported_after(
        "from urdflint.engine import config, linter\n"
        "s = config.Settings(select=('X', 'J001'))\n"
        f"linter.lint_bytes(open({str(SMALL)!r}, 'rb').read(), 'x.urdf', s)"
    )
    from urdflint.rules import PACKAGES

    families = {f"urdflint.rules.{name}" for name in PACKAGES.values()}
    assert families & loaded == {
        "urdflint.rules.document",
        "urdflint.rules.joints",
        "urdflint.rules.meta",
    }


@pytest.mark.parametrize("select", [("invalid-number",), ("ALL",)], ids=["rule name", "ALL"])
def test_a_rule_name_or_all_loads_the_whole_catalogue(select: tuple[str, ...]) -> None:
    loaded = imported_after(
        "from urdflint.engine import config\n"
        f"print(sorted(config.Settings(select={select!r}).enabled()))"
    )
    assert "urdflint.rules.gazebo" in loaded


def test_a_static_check_imports_no_heavy_module_no_formatter_it_does_not_use() -> None:
    loaded = imported_after(
        "from urdflint.cli import main\n"
        f"main(['check', '--isolated', '--exit-zero', '--select', 'X,S,J', {str(SMALL)!r}])"
    )
    heavy = {
        "numpy",
        "trimesh",
        "pinocchio",
        "fastapi",
        "tomllib",
        "xml.sax.saxutils",
        "urllib.request",
    }
    assert heavy & loaded == set()
    formatters = {m for m in loaded if m.startswith("urdflint.outputs.formatters.")}
    assert formatters == {"urdflint.outputs.formatters.run", "urdflint.outputs.formatters.text"}


def test_ignoring_an_unloaded_family_still_validates_the_selector() -> None:
    from urdflint.engine import config

    assert config.Settings(select=("X",), ignore=("G001",)).enabled()
    with pytest.raises(ValueError, match="Q9"):
        config.Settings(select=("X",), ignore=("Q9",)).enabled()
