"""Configuration discovery, validation and effect."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.test_cli import NO_LIMIT, run
from urdflint.engine import config


@pytest.fixture
def project(tmp_path: Path) -> Path:
    (tmp_path / "robots" / "arm").mkdir(parents=True)
    (tmp_path / "robots" / "arm" / "arm.urdf").write_text(NO_LIMIT)
    return tmp_path


def findings(capsys, *args: str) -> tuple[int, list[dict]]:
    code, out, _ = run(capsys, "check", "--format", "json", *args)
    return code, json.loads(out)["findings"] if out.strip() else []


def test_pyproject_table_is_discovered_upward(capsys, project: Path) -> None:
    (project / "pyproject.toml").write_text('[tool.urdflint]\nignore = ["J001", "P001"]\n')
    code, found = findings(capsys, str(project / "robots"))
    assert code == 0 and all(f["code"] != "J001" for f in found)


def test_pyproject_without_table_is_skipped(capsys, project: Path) -> None:
    (project / "robots" / "pyproject.toml").write_text('[project]\nname = "x"\n')
    (project / "urdflint.toml").write_text('ignore = ["J001", "P001"]\n')
    code, _ = findings(capsys, str(project / "robots"))
    assert code == 0


def test_nearest_config_wins(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text('ignore = ["J001"]\n')
    (project / "robots" / "arm" / "urdflint.toml").write_text('fail-on = "never"\n')
    code, found = findings(capsys, str(project / "robots"))
    assert code == 0 and any(f["code"] == "J001" for f in found)


def test_severity_override_and_off(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text(
        '[severity]\nJ001 = "warning"\nP001 = "warning"\nmissing-joint-origin = "off"\n'
    )
    code, found = findings(capsys, str(project))
    j001 = [f for f in found if f["code"] == "J001"]
    assert code == 0 and j001 and j001[0]["severity"] == "warning"
    assert all(f["code"] != "J011" for f in found)


def test_fail_on_from_config(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text('fail-on = "never"\n')
    assert findings(capsys, str(project))[0] == 0


def test_per_file_ignores(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text('[per-file-ignores]\n"robots/**/*.urdf" = ["J", "P"]\n')
    code, found = findings(capsys, str(project))
    assert code == 0 and all(not f["code"].startswith("J") for f in found)


def test_select_in_config_and_cli_override(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text('select = ["X"]\n')
    assert findings(capsys, str(project))[0] == 0
    assert findings(capsys, "--select", "J001", str(project))[0] == 1


def test_explicit_config_and_isolated(capsys, project: Path, tmp_path: Path) -> None:
    (project / "urdflint.toml").write_text('ignore = ["J001"]\n')
    other = tmp_path / "strict.toml"
    other.write_text('select = ["J001"]\n')
    assert findings(capsys, "--config", str(other), str(project))[0] == 1
    assert findings(capsys, "--isolated", str(project))[0] == 1


def test_targets_from_config(capsys, project: Path) -> None:
    (project / "urdflint.toml").write_text('targets = ["gz-sim"]\n')
    assert findings(capsys, str(project))[0] == 1


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ('selec = ["X"]\n', "unknown configuration key 'selec'"),
        ('ignore = ["Q999"]\n', "Q999"),
        ('fail-on = "sometimes"\n', "fail-on"),
        ('targets = ["webots"]\n', "webots"),
        ('[severity]\nJ001 = "fatal"\n', "severity.J001"),
        ('[severity]\nZ001 = "error"\n', "Z001"),
        ("[rules.I007]\nmax-ratoi = 3\n", "rules.I007.max-ratoi"),
        ("this is = not toml", "invalid TOML"),
    ],
)
def test_invalid_config_exits_2_naming_the_key(
    capsys, project: Path, text: str, needle: str
) -> None:
    (project / "urdflint.toml").write_text(text)
    code, out, err = run(capsys, "check", str(project))
    assert code == 2
    assert needle in err
    assert out == ""


def test_rule_options_reach_the_rule(project: Path) -> None:
    settings = config.from_mapping({"rules": {"I007": {"max-ratio": 3}}})
    assert settings.options("I007")["max-ratio"] == 3
    with pytest.raises(config.ConfigError, match="must be a number"):
        config.from_mapping({"rules": {"I007": {"max-ratio": "big"}}})
