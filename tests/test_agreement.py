"""The predictions kept honest: every planted defect, loaded in the real engines.

For each base robot of ``fixtures/planted/`` and each defect of :mod:`tests.planted` that
applies to it, and for the unplanted robot (``none``, the control), the planted model is
loaded in every engine whose test was selected (installed through ``urdflint[engines]``;
sdformat needs ``libsdformat-dev`` and ``g++``): one batch per engine over all the models
(:func:`urdflint.engines.runner.confirm_many`, the engines in parallel; a crash restarts the
batch after the model it crashed on). Each model is then linted once, with every rule,
every target (``--target all``) and those outcomes as its confirmation (the E rules). For
each target with an engine (:data:`urdflint.model.targets.ENGINE`), the prediction an
engine's load can show (:func:`urdflint.engine.matrix.measurable` of its
:func:`~urdflint.engine.matrix.rows` row) must be what that engine did
(:func:`urdflint.engine.matrix.confirm` of the E findings: crashes E005, refused E001,
changes E002 to E004, else loads), but for the disagreements listed in :data:`KNOWN`,
each with its reason; a listed disagreement that no longer happens fails too, so the list
stays short and true. A failure lists every disagreement of the engine with its messages.

``bench/engine_agreement.py`` runs the same cases and prints recall and precision.
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from tests import planted
from tests.conftest import FIXTURES
from tests.helpers import fixture_settings
from tests.test_engines import EXPECTED, MODELS
from urdflint.engine import config, linter, matrix
from urdflint.engines import batch, runner
from urdflint.engines.probe import MARK, MUJOCO_LOG
from urdflint.model import targets
from urdflint.model.finding import Finding

pytestmark = pytest.mark.slow  # the real engines

ENGINES = runner.ENGINES
CONTROL = "none"
TARGETS = tuple(targets.TARGETS)  # --target all

# (robot, defect, target) -> why the prediction and the engine disagree there
KNOWN: dict[tuple[str, str, str], str] = {
    ("arm", "two_parents", "pinocchio"): (
        "urdfdom keeps one of a link's two parent joints, which one depending on their order "
        "in the file; in the arm the joint it drops leaves wrist_link out of the tree, so "
        "Pinocchio refuses the model ('Model does not have any body named wrist_link'), "
        "while in the other robots it loads: the prediction cannot tell from the rule"
    ),
}


@dataclass(repr=False)
class Case:
    """One planted model: its outcomes in the engines that ran, and its findings."""

    robot: str
    defect: str
    outcomes: dict[str, Any]
    findings: list[Finding]

    def __repr__(self) -> str:
        return f"{self.robot}/{self.defect}"


def planted_models() -> Iterator[tuple[str, str, Any]]:
    """``(robot, defect, tree)`` for every base robot and every defect that applies to it,
    the control first."""
    for robot in planted.ROBOTS:
        yield robot, CONTROL, planted.load(robot)
        for defect in planted.DEFECTS:
            tree, element = planted.plant(robot, defect)
            if element is not None:
                yield robot, defect, tree


def needs(engine: str) -> pytest.MarkDecorator:
    return pytest.mark.skipif(not runner.installed(engine), reason=f"{engine} is not installed")


def selected(request: pytest.FixtureRequest, test: str) -> tuple[str, ...]:
    """The installed engines with which this session runs ``test`` (all, in a full run)."""
    wanted = {
        item.callspec.params.get("engine")
        for item in request.session.items
        if isinstance(item, pytest.Function)
        and item.originalname == test
        and item.path == Path(__file__)
    }
    return tuple(e for e in ENGINES if e in wanted and runner.installed(e))


@pytest.fixture(scope="module")
def cases(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> list[Case]:
    """Every planted model, loaded in the selected engines (one batch each) and linted."""
    engines = selected(request, "test_every_prediction_is_what_the_engine_did")
    settings = config.Settings(targets=TARGETS, confirm=engines)
    folder = tmp_path_factory.mktemp("planted")
    names, docs = [], []
    for robot, defect, tree in planted_models():
        path = folder / f"{robot}-{defect}.urdf"
        tree.write(str(path), xml_declaration=True, encoding="utf-8")
        names.append((robot, defect))
        docs.append(linter.load(path, path.name, settings))
    outcomes = runner.confirm_many(docs, engines)
    return [
        Case(
            robot,
            defect,
            {o.engine: o for o in found},
            linter.lint_document(doc, settings).findings,
        )
        for (robot, defect), doc, found in zip(names, docs, outcomes, strict=True)
    ]


def comparisons(case: Case, engine: str) -> list[tuple[str, str, str]]:
    """``(target, predicted, observed)`` for each of the engine's targets."""
    observed = matrix.confirm(case.findings, engine)["outcome"]
    mine = tuple(t for t in TARGETS if targets.ENGINE[t] == engine)
    found = []
    for row in matrix.rows(case.findings, mine, (engine,)):
        predicted = matrix.measurable(row)
        found.append((row["target"], predicted, observed))
    return found


def describe(case: Case, target: str, predicted: str, observed: str, engine: str) -> str:
    """One disagreement: the findings behind the prediction, the engine's messages."""
    (row,) = matrix.rows(case.findings, (target,), (engine,))
    why = ", ".join(f"{d['code']}({d['consequence']})" for d in row["predicted"]["findings"])
    said = [f"{f.code} line {f.line}: {f.message}" for f in case.findings if f.engine == engine]
    lines = [f"{case.robot}/{case.defect}/{target}: predicted {predicted} (findings: "
             f"{why or '-'}), {engine} {observed}"]  # fmt: skip
    return "\n".join([*lines, *(f"    {text[:300]}" for text in said or ["(no E finding)"])])


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
def test_every_prediction_is_what_the_engine_did(engine: str, cases: list[Case]) -> None:
    unusable = cases[0].outcomes[engine]
    if not unusable.installed:  # sdformat: its probe did not compile here
        pytest.skip(f"{engine}: {unusable.reason or 'not installed'}")
    wrong, stale, compared = [], [], 0
    for case in cases:
        for target, predicted, observed in comparisons(case, engine):
            compared += 1
            known = (case.robot, case.defect, target) in KNOWN
            if predicted != observed and not known:
                wrong.append(describe(case, target, predicted, observed, engine))
            elif predicted == observed and known:
                stale.append(f"{case.robot}/{case.defect}/{target}: now {observed} as predicted")
    assert compared, f"no target of {engine} was compared"
    report = [f"{engine}: {len(wrong)} of {compared} predictions disagree", *wrong]
    if stale:
        report += ["listed in KNOWN but agreeing now (remove them):", *stale]
    assert not wrong and not stale, "\n".join(report)


# Files cut down from real ones (issue 29: the mesh formats of Drake's models, Poppy's
# package that is a folder, a terrain welded to the world), each loaded as it is, with its
# fixture settings and every target: each target's prediction is what its engine did.
REAL_FIXTURES = tuple(
    FIXTURES / "rules" / name
    for name in (
        "C009/bad_bowl.urdf",
        "C009/good_bowl.urdf",
        "C009/bad_pybullet.urdf",
        "C009/good_pybullet.urdf",
        "C004/bad_poppy.urdf",
        "C004/good_poppy.urdf",
        "C006/good_terrain.urdf",
    )
)


@pytest.fixture(scope="module")
def real_cases(request: pytest.FixtureRequest) -> list[Case]:
    """Each of :data:`REAL_FIXTURES`, loaded in the selected engines (one batch each)."""
    engines = selected(request, "test_the_real_files_predictions_are_what_the_engines_did")
    found = []
    for path in REAL_FIXTURES:
        base = fixture_settings(path)
        settings = config.Settings(**{**base.__dict__, "targets": TARGETS, "confirm": engines})
        found.append((path, settings, linter.load(path, path.name, settings)))
    outcomes = runner.confirm_many([doc for _, _, doc in found], engines)
    return [
        Case(f"{path.parent.name}/{path.name}", CONTROL, {o.engine: o for o in loaded},
             linter.lint_document(doc, settings).findings)
        for (path, settings, doc), loaded in zip(found, outcomes, strict=True)
    ]  # fmt: skip


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
def test_the_real_files_predictions_are_what_the_engines_did(engine: str, real_cases) -> None:
    if not real_cases[0].outcomes[engine].installed:  # sdformat: its probe did not compile
        pytest.skip(f"{engine}: not usable here")
    wrong = [
        describe(case, target, predicted, observed, engine)
        for case in real_cases
        for target, predicted, observed in comparisons(case, engine)
        if predicted != observed
    ]
    assert not wrong, "\n".join(wrong)


def test_the_known_disagreements_are_planted_cases() -> None:
    found = {(robot, defect) for robot, defect, _ in planted_models()}
    for robot, defect, target in KNOWN:
        assert (robot, defect) in found and targets.ENGINE.get(target) is not None


# --- the batch itself -------------------------------------------------------------------


@pytest.fixture(scope="module")
def batched(request: pytest.FixtureRequest) -> dict[str, list[Finding]]:
    """The E findings on each model of ``fixtures/engines/``, all loaded in one batch per
    engine (Drake crashes on inverted_limits and PyBullet on two_roots, mid-batch)."""
    engines = selected(request, "test_a_batch_reports_what_one_process_per_model_does")
    settings = config.Settings(select=("E",), confirm=engines)
    paths = [MODELS / f"{name}.urdf" for name in sorted(EXPECTED)]
    docs = [linter.load(path, str(path), settings) for path in paths]
    runner.confirm_many(docs, engines)
    return {
        p.stem: linter.lint_document(d, settings).findings for p, d in zip(paths, docs, strict=True)
    }


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in ENGINES])
def test_a_batch_reports_what_one_process_per_model_does(engine, batched) -> None:
    """What tests/test_engines.py observes with one process per model and engine."""
    for model, findings in batched.items():
        found = {(f.line, f.code, f.element) for f in findings if f.engine == engine}
        assert found == EXPECTED[model].get(engine, set()), model


FAKE_PROBE = f"""
import json, os, sys, time
for index, path in enumerate(sys.argv[1:]):
    name = os.path.basename(path)
    print("\\n{MARK}", index, file=sys.stderr, flush=True)
    print(f"Warning: loading {{name}}", file=sys.stderr, flush=True)
    if name == "abort.urdf":
        open("{MUJOCO_LOG}", "w").write("WARNING: in the log of abort.urdf")
        os.abort()
    if name == "hang.urdf":
        time.sleep(60)
    if name == "exit.urdf":
        sys.exit(3)
    print(json.dumps({{"path": path, "ok": True}}), flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="os.abort() is not a signal on Windows")
def test_a_batch_restarts_after_the_file_its_process_died_or_hung_on(tmp_path: Path) -> None:
    script = tmp_path / "probe.py"
    script.write_text(FAKE_PROBE)
    names = ["a", "abort", "b", "hang", "c", "exit"]
    paths = [tmp_path / f"{name}.urdf" for name in names]
    found = batch.load(lambda p: [sys.executable, str(script), *map(str, p)], paths, 2.0, tmp_path)
    assert [f.path for f in found] == paths
    assert [f.report is not None for f in found] == [True, False, True, False, True, False]
    assert [(f.status, f.hung) for f in found] == [
        (None, False), (-signal.SIGABRT, False), (None, False), (-signal.SIGKILL, True),
        (None, False), (3, False),
    ]  # fmt: skip
    for name, loaded in zip(names, found, strict=True):  # what each printed, on its file
        assert f"Warning: loading {name}.urdf" in loaded.printed
        assert loaded.printed.count("Warning: loading") == 1
    assert "WARNING: in the log of abort.urdf" in found[1].printed
    assert not (tmp_path / MUJOCO_LOG).exists()


def test_a_crash_in_a_batch_is_reported_as_one_process_per_model_reports_it(tmp_path) -> None:
    doc = linter.load(MODELS / "good_arm.urdf", "good_arm.urdf", config.Settings())
    path = tmp_path / "good_arm.urdf"
    died = batch.Loaded(path, printed="Error: no way\n", status=-signal.SIGSEGV)
    assert runner.outcome(doc, "pinocchio", died, 60).crash == (
        "was killed by SIGSEGV after printing 'no way'"
    )
    hung = batch.Loaded(path, printed="Warning: slow\n", hung=True)
    assert runner.outcome(doc, "drake", hung, 2).crash == (
        "did not finish loading the model within 2 s"
    )


def test_remembered_outcomes_are_what_the_e_rules_report(monkeypatch) -> None:
    monkeypatch.setattr(runner, "run", lambda *a: pytest.fail("an engine was started"))
    settings = config.Settings(select=("E",), confirm=("pybullet",))
    doc = linter.load(MODELS / "good_arm.urdf", "good_arm.urdf", settings)
    runner.remember(doc, [runner.Outcome("pybullet", crash="was killed by SIGSEGV")])
    (found,) = linter.lint_document(doc, settings).findings
    assert (found.code, found.engine) == ("E005", "pybullet")
