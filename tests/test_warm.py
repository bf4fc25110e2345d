"""Warm probes (:mod:`urdflint.engines.warm`): one engine process kept from one model to
the next answers what a new process per model answers, crashes included; a dead or hung
probe costs only its model; probes are recycled, stopped when idle and not shared with a
forked child."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.conftest import FIXTURES
from urdflint.engine import config, linter
from urdflint.engines import batch, runner, warm

pytestmark = pytest.mark.slow  # the real engines


def needs(engine: str) -> pytest.MarkDecorator:
    return pytest.mark.skipif(not runner.installed(engine), reason=f"{engine} is not installed")


PYTHON_ENGINES = [e for e in runner.ENGINES if e not in runner.NATIVE]
MODELS = sorted((FIXTURES / "engines").glob("*.urdf"))
CRASHER = FIXTURES / "rules" / "E005" / "bad.urdf"  # PyBullet dies on it (E005's fixture)


def written(tmp_path: Path, source: Path, index: int) -> tuple[object, Path]:
    doc = linter.load(source, source.name, config.Settings())
    folder = tmp_path / str(index)
    folder.mkdir()
    return doc, runner.write_model(doc, folder)


@pytest.fixture(autouse=True)
def fresh() -> object:
    warm.close_all()
    yield
    warm.close_all()


@pytest.mark.parametrize("engine", [pytest.param(e, marks=needs(e)) for e in PYTHON_ENGINES])
def test_a_warm_probe_answers_what_a_new_process_per_model_answers(engine, tmp_path) -> None:
    models = [*MODELS, CRASHER, *MODELS[:2]]
    for index, source in enumerate(models):
        doc, path = written(tmp_path, source, index)
        fresh_answer = batch.load(runner.command(engine), [path], 60.0, path.parent)[0]
        expected = runner.outcome(doc, engine, fresh_answer, 60.0)
        assert runner.run(doc, engine, path, 60.0) == expected, source.name


@needs("pybullet")
def test_a_model_the_probe_dies_on_is_a_crash_and_the_next_model_a_new_process(
    tmp_path,
) -> None:
    _, good = written(tmp_path, MODELS[0], 0)
    doc, bad = written(tmp_path, CRASHER, 1)
    with warm.borrowed("pybullet", runner.MEMORY) as probe:
        assert probe.load(good, 60.0).report["ok"]
        first = probe.proc.pid
        died = probe.load(bad, 60.0)
        assert died.report is None and died.status is not None and not died.hung
        assert probe.proc is None
        assert probe.load(good, 60.0).report["ok"]
        assert probe.proc.pid != first
    outcome = runner.run(doc, "pybullet", bad, 60.0)  # tried twice, then the crash
    assert outcome.crash and not outcome.built


@needs("mujoco")
def test_a_hung_model_is_killed_and_reported_as_hung(tmp_path) -> None:
    _, good = written(tmp_path, MODELS[0], 0)
    with warm.borrowed("mujoco", runner.MEMORY) as probe:
        loaded = probe.load(good, 0.001)  # a new process: MuJoCo's import counts
        assert loaded.hung and loaded.report is None
        assert probe.proc is None
        assert probe.load(good, 60.0).report["ok"]


@needs("mujoco")
def test_probes_are_recycled_and_stopped_when_idle(tmp_path, monkeypatch) -> None:
    monkeypatch.setattr(warm, "RECYCLE", 2)
    _, good = written(tmp_path, MODELS[0], 0)
    pids = []
    for _ in range(3):
        with warm.borrowed("mujoco", runner.MEMORY) as probe:
            assert probe.load(good, 60.0).report["ok"]
            pids.append(probe.proc.pid)
    assert pids[0] == pids[1] != pids[2]  # one probe, a new process after 2 models
    (kept,) = warm._IDLE["mujoco"]
    proc, folder = kept.proc, kept.folder
    assert folder.is_dir()
    monkeypatch.setattr(warm, "IDLE", 0.0)
    with warm._LOCK:
        warm._reap()
    assert warm._IDLE["mujoco"] == [] and proc.poll() is not None and not folder.exists()


@needs("mujoco")
def test_a_probe_whose_parent_goes_removes_its_folder(tmp_path) -> None:
    _, good = written(tmp_path, MODELS[0], 0)
    probe = warm.Probe("mujoco", runner.MEMORY)
    assert probe.load(good, 60.0).report["ok"]
    proc, folder = probe.proc, probe.folder
    proc.stdin.close()  # as when the parent exits, even killed
    assert proc.wait(timeout=30) == 0
    assert not folder.exists()
    probe.close()


@needs("mujoco")
@pytest.mark.skipif(not hasattr(os, "fork"), reason="fork")
def test_a_forked_child_does_not_use_its_parents_probes(tmp_path) -> None:
    _, good = written(tmp_path, MODELS[0], 0)
    with warm.borrowed("mujoco", runner.MEMORY) as probe:
        assert probe.load(good, 60.0).report["ok"]
    parent = probe.proc.pid
    read, write = os.pipe()
    child = os.fork()
    if child == 0:  # pragma: no cover (the child)
        try:
            ok = warm._IDLE == {} or not any(warm._IDLE.values())
            os.write(write, b"1" if ok else b"0")
        finally:
            os._exit(0)
    os.close(write)
    assert os.read(read, 1) == b"1"
    os.waitpid(child, 0)
    os.close(read)
    with warm.borrowed("mujoco", runner.MEMORY) as again:  # the parent's probe lives on
        assert again is probe and again.proc.pid == parent
        assert again.load(good, 60.0).report["ok"]
