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


def _options_table() -> set[str]:
    """Every ``--option`` in the first column of README's table of ``check`` options."""
    table = re.search(r"Options of `check`:\n\n((?:\|.*\n)+)", README)
    assert table, "README has no options table for check"
    cells = [row.split(" | ")[0] for row in table.group(1).splitlines()[2:]]
    return {opt for cell in cells for opt in re.findall(r"`(--[a-z-]+)", cell)}


def test_the_options_table_is_check_s_options() -> None:
    """README's table and ``urdflint check -h`` name the same options, aliases included."""
    check = build_parser()._subparsers._group_actions[0].choices["check"]  # type: ignore[union-attr]
    known = {opt for action in check._actions for opt in action.option_strings}
    known = {opt for opt in known if opt.startswith("--")} - {"--help"}
    documented = _options_table()
    assert documented - known == set(), "documented but not an option"
    assert known - documented == set(), "an option README's table does not mention"


def test_the_folder_help_says_what_a_folder_selects() -> None:
    """check -h, action.yml and README agree: a folder means its URDF and entry xacro files."""
    check = build_parser()._subparsers._group_actions[0].choices["check"]  # type: ignore[union-attr]
    helps = " ".join(a.help or "" for a in check._actions)
    action = (ROOT / "action.yml").read_text(encoding="utf-8")
    for text in (helps, action, README):
        assert "every *.urdf and entry *.xacro below" in text
    assert "every *.urdf below" not in helps + action


def test_install_lines_are_what_works_today() -> None:
    """urdflint is not on PyPI: no line tells to pip install it by name from an index."""
    import shlex

    commands = [c.split("&&")[0].split("#")[0] for c in re.findall(r"pip install [^\n`]*", README)]
    words = [(c, w) for c in commands for w in shlex.split(c)[2:]]
    by_name = [c for c, w in words if re.fullmatch(r"urdflint(\[[a-z,]+\])?(==.*)?", w)]
    assert len(commands) > 3 and by_name == []
    assert "pip install 'urdflint[model,dynamics]'" not in README


def test_setup_and_test_commands_are_marked() -> None:
    assert re.search(r"<!-- test-command -->\n```sh\n\.venv/bin/python -m pytest -q\n```", README)
    assert 'pip install -e ".[full,test]" && .venv/bin/urdflint check fixtures/models/' in README
