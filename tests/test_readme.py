"""README's examples are real: the configuration parses, the commands it shows exist."""

from __future__ import annotations

import re
import tomllib

from tests.conftest import ROOT
from urdflint.cli import build_parser
from urdflint.engine import config

README = (ROOT / "README.md").read_text(encoding="utf-8")


def test_configuration_example_is_valid() -> None:
    block = re.search(r"## Configuration.*?```toml\n(.*?)```", README, re.S)
    assert block, "README has no TOML example under ## Configuration"
    data = tomllib.loads(block.group(1))["tool"]["urdflint"]
    settings = config.from_mapping(data)
    assert settings.expect.mass == 12.3 and settings.expect.q == {"elbow": 0.5}
    assert "my_robot_description" in settings.package_paths


def test_documented_check_options_exist() -> None:
    check = build_parser()._subparsers._group_actions[0].choices["check"]  # type: ignore[union-attr]
    known = {opt for action in check._actions for opt in action.option_strings}
    documented = set(re.findall(r"^\| `(--[a-z-]+)", README, re.M))
    assert documented and documented <= known, documented - known


def test_setup_and_test_commands_are_marked() -> None:
    assert re.search(r"<!-- test-command -->\n```sh\n\.venv/bin/python -m pytest -q\n```", README)
    assert 'pip install -e ".[full,test]" && .venv/bin/urdflint check fixtures/models/' in README
