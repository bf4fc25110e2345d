"""Dataset runs on this machine: ``--format jsonl`` records, ``--resume``, lean runs, and
``--executor ray`` without Ray (the runs on a Ray cluster are in ``tests/test_ray.py``)."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from urdflint.cli import main
from urdflint.outputs import records

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "fixtures" / "models"


def _records(path: Path) -> dict[str, dict]:
    return {item["path"]: item for item in records.read(path)[0]}


def _without_inputs(found: dict[str, dict]) -> dict[str, dict]:
    """Records as compared across runs: ``inputs`` lists a folder once per process (the
    first file a process checks lists it)."""
    return {path: {k: v for k, v in item.items() if k != "inputs"} for path, item in found.items()}


def _copy_models(tmp_path: Path) -> Path:
    folder = tmp_path / "models"
    shutil.copytree(MODELS, folder)
    return folder


def test_jsonl_has_one_record_per_file_with_what_json_says(tmp_path: Path, capsys) -> None:
    folder = _copy_models(tmp_path)
    out = tmp_path / "r.jsonl"
    code = main(["check", str(folder), "--isolated", "--format", "jsonl", "--output", str(out)])
    err = capsys.readouterr().err
    assert main(["check", str(folder), "--isolated", "--format", "json"]) == code == 1
    document = json.loads(capsys.readouterr().out)
    found = _records(out)
    assert sorted(found) == sorted(document["summary"] and document["models"])
    assert sum(len(r["findings"]) for r in found.values()) == len(document["findings"])
    for path, item in found.items():
        assert item["record"] == records.FORMAT and item["error"] is None
        mine = [f for f in document["findings"] if f["path"] == path]
        assert sorted(map(json.dumps, item["findings"])) == sorted(map(json.dumps, mine))
        assert item["summary"]["error"] == sum(f["severity"] == "error" for f in mine)
        assert len(item["hash"]) == 32 and item["settings"]
        assert item["links"] and item["matrix"] and all(r["selected"] for r in item["matrix"])
        assert any(i[0] == "file" and i[1] == str(Path(path).resolve()) for i in item["inputs"])
    # a lean run: the findings are counted, the summary on stderr, the exit code as ever
    errors = sum(r["summary"]["error"] for r in found.values())
    assert f"urdflint: {errors} errors" in err and "in 4 file(s)" in err


def test_records_read_back_into_the_same_findings(tmp_path: Path, capsys) -> None:
    """Lossless: every finding of a record becomes the Finding it was written from (the
    fix's byte offsets and an effect's own severity included)."""
    from urdflint.cli import parallel
    from urdflint.engine.options import SettingsFinder

    folder = _copy_models(tmp_path)
    out = tmp_path / "r.jsonl"
    main(["check", str(folder), "--isolated", "--format", "jsonl", "--output", str(out)])
    capsys.readouterr()
    assert any(f["autofix"] for r in _records(out).values() for f in r["findings"])
    from urdflint.cli import build_parser

    args = build_parser().parse_args(["check", "--isolated", str(folder)])
    settings = SettingsFinder(args).for_folder(folder)
    for path, item in _records(out).items():
        task = parallel.Task(path, path, settings)
        fresh = parallel.lint_one(task, None, parallel.Flags())
        assert [records.finding(f) for f in item["findings"]] == fresh.findings


def test_report_jsonl_beside_text_keeps_the_text_output(tmp_path: Path, capsys) -> None:
    folder = _copy_models(tmp_path)
    out = tmp_path / "r.jsonl"
    code = main(["check", str(folder), "--isolated", "--report", f"jsonl:{out}"])
    text = capsys.readouterr().out
    assert code == 1 and "broken_arm.urdf" in text and "error" in text
    assert len(_records(out)) == 4


def test_resume_reuses_unchanged_files_and_checks_changed_ones(tmp_path: Path, capsys) -> None:
    folder = _copy_models(tmp_path)
    results = tmp_path / "results.jsonl"
    command = ["check", str(folder), "--isolated", "--format", "json", "--resume", str(results)]
    assert main(command) == 1
    first = capsys.readouterr()
    assert len(_records(results)) == 4 and "resuming" not in first.err
    assert main(command) == 1  # nothing changed: every file reused, the same report
    second = capsys.readouterr()
    assert "4 file(s) already recorded; 0 to check" in second.err
    assert second.out == first.out
    arm = folder / "broken_arm.urdf"
    arm.write_text(arm.read_text() + "<!-- edited -->\n")
    assert main(command) == 1
    third = capsys.readouterr()
    assert "3 file(s) already recorded, 1 changed since; 1 to check" in third.err
    assert main(["check", str(folder), "--isolated", "--format", "json"]) == 1
    assert capsys.readouterr().out == third.out
    lines = results.read_text().splitlines()
    assert len(lines) == 5  # the changed file's new record after its old one
    assert json.loads(lines[-1])["path"] == str(arm)


def test_resume_ignores_records_of_other_settings(tmp_path: Path, capsys) -> None:
    folder = _copy_models(tmp_path)
    results = tmp_path / "results.jsonl"
    base = ["check", str(folder), "--isolated", "--format", "json", "--resume", str(results)]
    main(base)
    main([*base, "--ignore", "I"])
    err = capsys.readouterr().err
    assert "0 file(s) already recorded, 4 changed since; 4 to check" in err


def test_resume_after_a_killed_run_gives_the_same_records(tmp_path: Path) -> None:
    """A run killed mid-way (SIGKILL: its last line may be cut) is finished by the same
    command; the records are those of one uninterrupted run."""
    from tests import variants

    if not variants.CORPUS.is_dir():
        pytest.skip("../shared/corpus is absent")
    dataset = tmp_path / "dataset"
    variants.make(dataset, 40, largest=40_000)
    env = {**os.environ, "URDFLINT_NO_CACHE": "1"}
    whole = tmp_path / "whole.jsonl"
    command = [sys.executable, "-m", "urdflint", "check", str(dataset), "-j", "1"]
    subprocess.run([*command, "--format", "jsonl", "--output", str(whole)], env=env, check=False)
    results = tmp_path / "results.jsonl"
    resumed = [*command, "--format", "json", "--resume", str(results)]
    proc = subprocess.Popen(resumed, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if results.exists() and results.read_bytes().count(b"\n") >= 10:
            break
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    kept = records.read(results)[0]
    assert 10 <= len(kept) < 40, "the run was not stopped mid-way"
    with results.open("a") as handle:
        handle.write('{"record": 1, "path": "cut')  # the last line, cut by the stop
    done = subprocess.run(resumed, env=env, capture_output=True, text=True, check=False)
    assert done.returncode == 1, done.stderr
    # every record kept is reused, but the first file a process checks also records the
    # folders above the dataset it listed (a package.xml there would matter): where other
    # work changes them meanwhile (pytest's temporary folders), that one file is checked again
    said = re.search(
        r"(\d+) file\(s\) already recorded(?:, (\d+) changed since)?; (\d+) to", done.stderr
    )
    assert said is not None, done.stderr
    reused, stale, todo = int(said[1]), int(said[2] or 0), int(said[3])
    assert reused + stale == len(kept) and stale <= 1 and todo == 40 - reused
    assert _without_inputs(_records(results)) == _without_inputs(_records(whole))
    assert len(results.read_text().splitlines()) == 40  # the cut line is gone


def test_resume_refuses_a_file_that_is_not_records(tmp_path: Path, capsys) -> None:
    other = tmp_path / "other.json"
    other.write_text('{"version": 1}\n{"version": 1}\n')
    code = main(["check", str(MODELS), "--resume", str(other)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "not an urdflint record" in err and "other.json:1" in err


def test_a_cut_last_line_is_left_out(tmp_path: Path) -> None:
    path = tmp_path / "r.jsonl"
    path.write_text('{"record": 1, "path": "a.urdf"}\n{"record": 1, "pa')
    found, length = records.read(path)
    assert [r["path"] for r in found] == ["a.urdf"]
    assert length == len('{"record": 1, "path": "a.urdf"}\n')


def test_executor_ray_without_ray_names_the_extra(monkeypatch, capsys) -> None:
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray raises ImportError
    code = main(["check", str(MODELS), "--executor", "ray"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "--executor ray needs Ray" in err and "[cluster]" in err


def test_executor_ray_with_nobody_at_the_address_is_one_line(capsys) -> None:
    pytest.importorskip("ray")
    code = main(["check", str(MODELS), "--executor", "ray", "--ray-address", "127.0.0.1:9"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "no Ray cluster answers at 127.0.0.1:9" in err


def three_boxes(folder: Path) -> list[Path]:
    """Three copies of a box mesh: three files for the mesh cache."""
    box = ROOT / "fixtures" / "rules" / "C009" / "meshes" / "box.obj"
    paths = [folder / f"{name}.obj" for name in ("a", "b", "c")]
    for path in paths:
        shutil.copy(box, path)
    return paths


def test_a_run_keeps_a_bounded_number_of_meshes_loaded(monkeypatch, tmp_path: Path) -> None:
    """A worker of a dataset run meets thousands of meshes: the least recently used go."""
    pytest.importorskip("trimesh")
    from urdflint.sources import mesh_cache

    monkeypatch.setattr(mesh_cache, "KEPT", 2)
    paths = three_boxes(tmp_path)
    meshes = mesh_cache.MeshCache()
    first = meshes.load(paths[0])
    meshes.load(paths[1])
    assert meshes.load(paths[0]) is first  # used again: kept
    meshes.load(paths[2])
    assert len(meshes) == 2 and meshes.load(paths[0]) is first  # b went, not a
    assert meshes.loads == 3


def test_only_the_most_recent_meshes_keep_their_trimesh_data(monkeypatch, tmp_path) -> None:
    """Beyond the byte budget, older meshes keep their facts and let the trimesh data go;
    a fact never computed reads the file again, with the same answer."""
    pytest.importorskip("trimesh")
    from urdflint.sources import mesh_cache

    paths = three_boxes(tmp_path)
    meshes = mesh_cache.MeshCache()
    first = meshes.load(paths[0])
    weight = mesh_cache._weight(first._mesh)
    assert weight > 0
    monkeypatch.setattr(mesh_cache, "HEAVY_BYTES", 2 * weight)
    assert first.watertight  # a fact computed while its data is there
    meshes.load(paths[1])
    assert first._mesh is not None and meshes._heavy_bytes == 2 * weight
    meshes.load(paths[2])  # over the budget: a's data goes, its facts stay
    assert first._mesh is None and meshes._heavy_bytes == 2 * weight
    assert meshes.load(paths[0]) is first and meshes.loads == 3
    assert first.watertight and meshes.loads == 3  # known: not read again
    fresh = mesh_cache.MeshCache().load(paths[0])
    assert first.solid() == fresh.solid() and meshes.loads == 4  # read again, same answer
    assert first._mesh is not None and meshes._heavy_bytes == 2 * weight  # counted again
    assert meshes._cache[next(iter(meshes._heavy))].path == paths[2]  # b's data went


ROBOT_WITH_MISSING_PACKAGE = """<robot name="r">
  <link name="base">
    <collision><geometry><mesh filename="package://nowhere/m.stl"/></geometry></collision>
  </link>
</robot>
"""


def test_files_given_one_by_one_share_their_settings_and_a_message_names_three_folders(
    tmp_path: Path, capsys
) -> None:
    """A dataset given file by file (a shell glob, a list): the files of a folder share one
    settings object (digested once per run, not once per file), and where a package was
    looked for names the first three folders walked, then how many more."""
    import argparse

    from urdflint.engine.options import SettingsFinder

    files = []
    for index in range(5):
        folder = tmp_path / f"set{index}"
        folder.mkdir()
        for name in ("a.urdf", "b.urdf"):
            (folder / name).write_text(ROBOT_WITH_MISSING_PACKAGE)
            files.append(str(folder / name))
    main(["check", *files, "--isolated", "--select", "C004", "--show-info", "--format", "json"])
    found = json.loads(capsys.readouterr().out)["findings"]
    assert len(found) == 10 and {f["code"] for f in found} == {"C004"}
    assert all("and 2 more folders" in f["message"] for f in found), found[0]["message"]
    args = argparse.Namespace(command="check", select=[], ignore=[], exit_zero=False,
                              fail_on=None, target=None, xacro_arg=[], q=[], isolated=False,
                              config=None)  # fmt: skip
    finder = SettingsFinder(args)
    first, second = (finder.for_folder(Path(f).parent) for f in files[:2])
    assert first is second is finder.for_folder(tmp_path / "set1")  # none has a configuration
