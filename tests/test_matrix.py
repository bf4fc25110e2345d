"""Targets, per-target effects on findings, and the compatibility matrix (``--matrix``)."""

from __future__ import annotations

import json

import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.cli import main
from urdflint.engine import config, docs, matrix, registry
from urdflint.model import effects as fx
from urdflint.model import targets

ENGINES = FIXTURES / "engines"
BROKEN = FIXTURES / "models" / "broken_arm.urdf"
GOOD = FIXTURES / "models" / "example_arm.urdf"


def run_json(capsys, *argv: str) -> dict:
    main(["check", "--format", "json", *argv])
    return json.loads(capsys.readouterr().out)


def test_all_selects_every_target_in_order() -> None:
    assert targets.validate(["mujoco", "all"]) == (
        "mujoco",
        "gazebo-classic",
        "gz-sim",
        "drake",
        "pybullet",
        "isaac",
        "pinocchio",
        "ros",
    )
    with pytest.raises(ValueError, match=r"unknown target 'gazebo'.*all"):
        targets.validate(["gazebo"])
    assert config.from_mapping({"targets": ["all"]}).targets == tuple(targets.TARGETS)


def test_every_target_has_a_label_and_an_engine_entry() -> None:
    assert set(targets.LABELS) == set(targets.TARGETS) == set(targets.ENGINE)
    assert set(targets.BASIS) == set(targets.TARGETS)
    runnable = {e for e in targets.ENGINE.values() if e}
    assert runnable <= {*config.ENGINES, "sdformat"}


def test_effects_tables_name_known_targets_only() -> None:
    for rule in registry.load_rules().values():
        for variant, table in rule.effects.items():
            assert set(table) <= set(targets.TARGETS), (rule.code, variant)
            assert all(isinstance(e, fx.Effect) for e in table.values()), rule.code


def test_a_finding_carries_the_effects_of_the_selected_targets_only() -> None:
    settings = config.Settings(targets=("mujoco", "pybullet"))
    (finding,) = lint_file(ENGINES / "two_roots.urdf", select=("S004",), settings=settings)
    assert [(t, e.consequence) for t, e in finding.effects] == [
        ("mujoco", fx.Consequence.JOINT_CHANGED),
        ("pybullet", fx.Consequence.CRASH),
    ]
    data = finding.to_dict()
    assert data["effects"]["pybullet"]["consequence"] == "crash"
    assert data["engine"] is None


def test_variants_choose_the_table() -> None:
    settings = config.Settings(targets=("drake",))
    found = lint_file(ENGINES / "inverted_limits.urdf", select=("J009",), settings=settings)
    assert [(f.line, f.effects[0][1].consequence) for f in found] == [(13, fx.Consequence.CRASH)]


def test_matrix_predicts_the_worst_effect_per_target() -> None:
    settings = config.Settings(targets=tuple(targets.TARGETS))
    findings = lint_file(ENGINES / "two_roots.urdf", settings=settings)
    rows = {r["target"]: r for r in matrix.rows(findings, settings.targets, ())}
    assert list(rows) == list(targets.TARGETS)
    outcome = {t: r["predicted"]["outcome"] for t, r in rows.items()}
    assert outcome["pybullet"] == "crashes"
    assert outcome["pinocchio"] == outcome["gz-sim"] == outcome["ros"] == "refused"
    assert outcome["mujoco"] == "changes"
    (deciding,) = rows["pybullet"]["predicted"]["findings"]
    assert (deciding["code"], deciding["line"], deciding["consequence"]) == ("S004", 39, "crash")
    assert all(r["confirmed"] is None for r in rows.values())
    assert rows["isaac"]["basis"] == "source and documentation"
    assert rows["drake"]["basis"] == "engine"


def test_measurable_ignores_ignored_tags() -> None:
    row = {"predicted": {"outcome": "changes", "findings": [{"consequence": "tag ignored"}]}}
    assert matrix.measurable(row) == "loads"
    row["predicted"]["findings"].append({"consequence": "joint unlimited"})
    assert matrix.measurable(row) == "changes"


def test_cli_matrix_json_has_one_row_per_target(capsys) -> None:
    data = run_json(capsys, "--matrix", str(ENGINES / "inverted_limits.urdf"))
    rows = data["matrix"]
    assert [r["target"] for r in rows] == list(targets.TARGETS)  # no --target: every one
    assert {r["path"] for r in rows} == {str(ENGINES / "inverted_limits.urdf")}
    drake = next(r for r in rows if r["target"] == "drake")
    assert drake["predicted"]["outcome"] == "crashes"


def test_cli_matrix_shows_every_target_and_marks_the_chosen_ones(capsys) -> None:
    data = run_json(capsys, "--matrix", "--target", "mujoco", str(ENGINES / "inverted_limits.urdf"))
    assert [r["target"] for r in data["matrix"]] == list(targets.ordered(tuple(targets.TARGETS)))
    assert [r["target"] for r in data["matrix"] if r["selected"]] == ["mujoco"]
    (mujoco,) = [r for r in data["matrix"] if r["target"] == "mujoco"]
    assert mujoco["predicted"]["outcome"] == "changes"
    (drake,) = [r for r in data["matrix"] if r["target"] == "drake"]
    assert drake["predicted"]["outcome"] == "crashes"  # a row for comparison only:
    assert {f["code"] for f in drake["predicted"]["findings"]} == {"J009"}
    assert not [f for f in data["findings"] if "Drake" in f["message"]]  # not reported


@pytest.mark.parametrize(
    "model", [BROKEN, GOOD, ENGINES / "inverted_limits.urdf"], ids=lambda p: p.name
)
@pytest.mark.parametrize("chosen", [[], ["--target", "mujoco"], ["--target", "all"]])
def test_display_options_never_change_findings_or_exit_code(capsys, model, chosen) -> None:
    """One file, one verdict: --matrix and --show-info only show more (issue 24, 8)."""

    def run(*extra: str) -> tuple[list, int]:
        code = main(["check", "--format", "json", *chosen, *extra, str(model)])
        return json.loads(capsys.readouterr().out)["findings"], code

    plain = run()
    assert run("--matrix") == plain
    assert run("--show-info") == plain
    assert run("--matrix", "--show-info") == plain


def test_cli_targets_comma_separated_or_repeated(capsys) -> None:
    path = str(ENGINES / "inverted_limits.urdf")
    data = run_json(capsys, "--matrix", "--target", "mujoco, drake", "--target", "ros", path)
    assert [r["target"] for r in data["matrix"] if r["selected"]] == ["mujoco", "drake", "ros"]
    with pytest.raises(SystemExit) as exit_:
        main(["check", "--target", "mujoco,gazebo", path])
    assert exit_.value.code == 2
    assert "unknown target 'gazebo' (known: gazebo-classic," in capsys.readouterr().err


def test_cli_without_matrix_has_no_matrix_key(capsys) -> None:
    assert "matrix" not in run_json(capsys, str(GOOD))


def test_text_matrix_table(capsys) -> None:
    main(["check", "--matrix", str(BROKEN)])
    out = capsys.readouterr().out
    assert f"{BROKEN}: what each target does with the model (--matrix)" in out
    lines = {line.split()[0]: line for line in out.splitlines() if line.startswith("  ")}
    assert "crashes" in lines["Drake"] and "J009 (line 61)" in lines["Drake"]
    assert "crashes" in lines["PyBullet"] and "S005 (line 76)" in lines["PyBullet"]
    assert "Isaac" in out and "* not run here" in out
    assert out.rstrip().splitlines()[-1].startswith("urdflint: ")


def test_text_effects_line_names_the_targets(capsys) -> None:
    main(["check", "--target", "all", "--select", "S004", str(ENGINES / "two_roots.urdf")])
    out = capsys.readouterr().out.splitlines()
    finding = next(i for i, line in enumerate(out) if " S004 " in line)
    assert out[finding + 1] == (
        "    refused: Gazebo Classic, Gazebo Sim, Pinocchio, ROS (KDL, MoveIt) · "
        "joint changed: MuJoCo · as written: Drake · crash: PyBullet · link dropped: Isaac Sim"
    )


def test_the_default_run_shows_no_effects_line(capsys) -> None:
    main(["check", "--select", "S004", str(ENGINES / "two_roots.urdf")])
    out = capsys.readouterr().out.splitlines()
    assert not any(line.startswith("    Gazebo") for line in out)


def test_rule_page_lists_the_effects() -> None:
    page = docs.page(registry.lookup("S004"))  # type: ignore[arg-type]
    assert "## What each target does" in page
    assert "- PyBullet (observed with PyBullet 3.2.7): crash, error: segmentation fault" in page
    ros = "- ROS (KDL, MoveIt) (from the source of urdfdom, kdl_parser and MoveIt): refused"
    assert ros in page


def test_consequences_order_outcomes() -> None:
    assert fx.Consequence.CRASH.outcome > fx.Consequence.REFUSED.outcome
    assert fx.Consequence.REFUSED.outcome > fx.Consequence.TAG_IGNORED.outcome
    assert fx.Consequence.AS_WRITTEN.outcome is fx.Outcome.LOADS
    assert fx.Consequence.parse("joint unlimited") is fx.Consequence.JOINT_UNLIMITED
    with pytest.raises(ValueError):
        fx.Consequence.parse("vanished")
