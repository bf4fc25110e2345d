"""The analysis cache (urdflint.cache): same findings with and without it, exactly what
depends on a changed input is computed again, and a broken, shared or read-only cache
folder never breaks a run."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES, ROOT
from urdflint.cache import Cache, deps, keys
from urdflint.cache.store import MAGIC, Store
from urdflint.cli import parallel
from urdflint.engine.config import Settings
from urdflint.engine.context import Context
from urdflint.sources import workspace

MESH_RULE = FIXTURES / "rules" / "C005"  # a URDF with real meshes beside it
PACKAGES = FIXTURES / "packages"


def lint(
    path: Path,
    cache: Cache | None,
    settings: Settings | None = None,
    package_paths: dict[str, Path] | None = None,
    roots: list[Path] | None = None,
    environ: dict[str, str] | None = None,
) -> list[dict[str, Any]]:
    """One file checked as ``urdflint check`` checks it, as JSON findings."""
    context = Context(
        package_paths=package_paths or {},
        workspace=workspace.Packages(roots or [path], cache),
        cache=cache,
        environ=environ,
    )
    task = parallel.Task(str(path), str(path), settings or Settings())
    outcome = parallel.lint_one(task, context, parallel.Flags())
    assert outcome.error is None, outcome.error
    return [f.to_dict() for f in outcome.findings]


@pytest.fixture
def replay_only(monkeypatch: pytest.MonkeyPatch) -> None:
    """From here on, a lint that is not replayed from the cache fails the test."""

    def computed(*args: Any) -> Any:
        raise AssertionError("computed again, expected a replay from the cache")

    monkeypatch.setattr(parallel, "_lint_one", computed)


def computed_count(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """A counter of the lints actually computed (not replayed)."""
    count = [0]
    original = parallel._lint_one

    def counting(*args: Any) -> Any:
        count[0] += 1
        return original(*args)

    monkeypatch.setattr(parallel, "_lint_one", counting)
    return count


def copy_tree(source: Path, target: Path) -> Path:
    shutil.copytree(source, target)
    old = time.time() - 60  # out of the "racily clean" window: stat alone decides
    for folder, _, files in os.walk(target):
        for name in files:
            os.utime(os.path.join(folder, name), (old, old))
    return target


# -- the same findings -------------------------------------------------------------------------


def _fixture_files() -> list[Path]:
    found = sorted((FIXTURES / "models").glob("*.urdf"))
    found += sorted((FIXTURES / "rules").glob("*/*.urdf"))
    found += sorted((FIXTURES / "rules").glob("*/*.xacro"))
    return found


def test_fixtures_same_findings_cold_warm_and_without(tmp_path: Path) -> None:
    """Every rule fixture: the cold run with the cache, the replay and a run without it."""
    cache = Cache(tmp_path / "cache")
    files = _fixture_files()
    assert len(files) > 200
    cold = {f: lint(f, cache) for f in files}
    plain = {f: lint(f, None) for f in files}
    assert cold == plain
    warm = {f: lint(f, Cache(tmp_path / "cache")) for f in files}
    assert warm == cold


def _entries() -> list[tuple[str, dict[str, str]]]:
    data = json.loads((PACKAGES / "entries.json").read_text(encoding="utf-8"))
    return [(item["entry"], item["args"]) for item in data]


@pytest.mark.slow  # real packages end to end
@pytest.mark.parametrize(("entry", "args"), _entries(), ids=lambda v: str(v)[:40])
def test_real_packages_same_findings(
    entry: str, args: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The real description packages: xacro expanded, packages found in the workspace."""
    pytest.importorskip("xacro")
    path = PACKAGES / entry
    settings = Settings(xacro_args=dict(args))
    plain = lint(path, None, settings, roots=[PACKAGES])
    cold = lint(path, Cache(tmp_path), settings, roots=[PACKAGES])
    assert cold == plain
    count = computed_count(monkeypatch)
    assert lint(path, Cache(tmp_path), settings, roots=[PACKAGES]) == plain
    assert count == [0]


def _corpus_with_meshes() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    return sorted(p.parent / "model.urdf" for p in CORPUS.glob("*/package_map.json"))


def _package_paths(model: Path) -> dict[str, Path]:
    mapping = json.loads((model.parent / "package_map.json").read_text())
    return {name: model.parent / folder for name, folder in mapping.items()}


@pytest.mark.slow  # real robots with their meshes
@pytest.mark.skipif(not _corpus_with_meshes(), reason="../shared/corpus is not present")
@pytest.mark.parametrize("model", _corpus_with_meshes(), ids=lambda p: p.parent.name)
def test_corpus_meshes_same_findings_from_stored_facts(model: Path, tmp_path: Path) -> None:
    """Real robots with their meshes: findings from mesh facts stored by an earlier run
    (another robot file, same meshes: the results miss, the meshes hit) are the findings of
    a run that reads every mesh."""
    pytest.importorskip("trimesh")
    packages = _package_paths(model)
    plain = lint(model, None, package_paths=packages)
    first = Cache(tmp_path)
    lint(model, first, package_paths=packages)
    assert first.store.size()[0] > 0
    # the same robot under another name: no result to replay, every mesh known
    other = tmp_path / "robot" / "model.urdf"
    other.parent.mkdir()
    shutil.copy(model, other)
    again = Cache(tmp_path)
    shown = lint(other, again, package_paths=packages)
    assert renamed(shown, other, model) == renamed(plain, model, model)
    from urdflint.cache import MEMORY

    MEMORY.clear()  # also from disk alone, as in a new process
    third = tmp_path / "third" / "model.urdf"
    third.parent.mkdir()
    shutil.copy(model, third)
    shown = lint(third, Cache(tmp_path), package_paths=packages)
    assert renamed(shown, third, model) == renamed(plain, model, model)


def renamed(findings: list[dict[str, Any]], old: Path, new: Path) -> Any:
    """The findings of a copy, as if they were of the original file (paths in fixes too)."""
    text = json.dumps(findings).replace(json.dumps(str(old))[1:-1], str(new))
    return json.loads(text.replace(json.dumps(str(old.parent))[1:-1], str(new.parent)))


# -- what invalidates what ---------------------------------------------------------------------


def test_unchanged_inputs_are_replayed_without_running_a_rule(
    tmp_path: Path, replay_only: None
) -> None:
    # replay_only patches after this point: the first run below must not be computed...
    # so prime the cache in a subprocess, as the previous run of a user would have.
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    env = {**os.environ, "URDFLINT_CACHE_DIR": str(tmp_path / "cache")}
    command = [sys.executable, "-m", "urdflint", "check", str(robot), "--format", "json"]
    first = subprocess.run(command, capture_output=True, env=env, check=False)
    assert first.returncode == 1, first.stderr
    replayed = lint(robot, Cache(tmp_path / "cache"))
    assert [f["code"] for f in replayed] == [
        f["code"] for f in json.loads(first.stdout)["findings"]
    ]


def test_a_touched_file_is_compared_by_content(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    cache = Cache(tmp_path / "cache")
    first = lint(robot, cache)
    os.utime(robot)  # a git checkout, an editor saving the same text
    count = computed_count(monkeypatch)
    assert lint(robot, Cache(tmp_path / "cache")) == first
    assert count == [0]


def test_an_edit_in_the_urdf_computes_again_and_reuses_the_meshes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytest.importorskip("trimesh")
    from urdflint.cache import MEMORY

    MEMORY.clear()  # facts an earlier test of this process kept would not reach this folder
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "good.urdf"
    lint(robot, Cache(tmp_path / "cache"))
    text = robot.read_text()
    assert "<mass value=" in text
    robot.write_text(text.replace('<mass value="', '<mass value="-', 1))
    count = computed_count(monkeypatch)
    loads: list[Any] = []
    from urdflint.sources import mesh_cache

    original = mesh_cache.trimesh_load
    monkeypatch.setattr(mesh_cache, "trimesh_load", lambda *a: loads.append(a) or original(*a))
    MEMORY.clear()
    found = lint(robot, Cache(tmp_path / "cache"))
    assert count == [1]
    assert "I002" in {f["code"] for f in found}
    assert loads == []  # every mesh described from its stored facts
    assert found == lint(robot, None)


def test_a_changed_mesh_is_read_again(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("trimesh")
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "good.urdf"
    first = lint(robot, Cache(tmp_path / "cache"))
    box = robot.parent / "meshes" / "box.obj"
    box.write_text(box.read_text().replace("v -0.05 -0.05 0\n", "v 1000 -0.05 0\n", 1))  # 1 km
    count = computed_count(monkeypatch)
    after = lint(robot, Cache(tmp_path / "cache"))
    assert count == [1]
    assert after != first
    assert after == lint(robot, None)


def test_a_missing_mesh_that_appears_makes_the_result_stale(tmp_path: Path) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "good.urdf"
    meshes = robot.parent / "meshes"
    hidden = tmp_path / "hidden"
    shutil.move(meshes, hidden)
    missing = lint(robot, Cache(tmp_path / "cache"))
    assert "C004" in {f["code"] for f in missing}
    shutil.move(hidden, meshes)
    found = lint(robot, Cache(tmp_path / "cache"))
    assert "C004" not in {f["code"] for f in found}
    assert found == lint(robot, None)


def _xacro_robot(folder: Path) -> tuple[Path, Path]:
    folder.mkdir()
    macro = folder / "arm.xacro"
    macro.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="arm" params="name">\n'
        '    <link name="${name}">\n'
        '      <inertial><mass value="1.0"/>\n'
        '        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>\n'
        "      </inertial>\n"
        "    </link>\n"
        "  </xacro:macro>\n"
        "</robot>\n"
    )
    entry = folder / "robot.urdf.xacro"
    entry.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="second" default="b"/>\n'
        '  <xacro:include filename="arm.xacro"/>\n'
        '  <xacro:arm name="a"/>\n'
        '  <xacro:arm name="$(arg second)"/>\n'
        '  <joint name="j" type="fixed"><parent link="a"/><child link="$(arg second)"/></joint>\n'
        "</robot>\n"
    )
    old = time.time() - 60
    for path in (macro, entry):
        os.utime(path, (old, old))
    return entry, macro


def test_an_edited_include_or_a_xacro_argument_computes_again(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytest.importorskip("xacro")
    entry, macro = _xacro_robot(tmp_path / "robot")
    cache_dir = tmp_path / "cache"
    first = lint(entry, Cache(cache_dir))
    assert not [f for f in first if f["code"] == "I002"]
    count = computed_count(monkeypatch)
    assert lint(entry, Cache(cache_dir)) == first
    assert count == [0]
    macro.write_text(macro.read_text().replace('value="1.0"', 'value="-1.0"'))
    edited = lint(entry, Cache(cache_dir))
    assert count == [1]
    i002 = [f for f in edited if f["code"] == "I002"]
    assert i002 and i002[0]["path"].endswith("arm.xacro") and i002[0]["line"] == 4
    assert lint(entry, Cache(cache_dir), Settings(xacro_args={"second": "c"})) != edited
    assert count == [2]
    assert lint(entry, Cache(cache_dir), Settings(xacro_args={"second": "b"})) == edited
    assert count == [3]  # another key (an explicit argument): computed once, then replayed
    assert lint(entry, Cache(cache_dir), Settings(xacro_args={"second": "b"})) == edited
    assert count == [3]


def test_an_environment_variable_read_by_xacro_is_an_input(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytest.importorskip("xacro")
    entry = tmp_path / "robot.urdf.xacro"
    entry.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="$(optenv URDFLINT_TEST_LINK base)"/>\n'
        "</robot>\n"
    )
    cache_dir = tmp_path / "cache"
    base = lint(entry, Cache(cache_dir), environ={})
    other = lint(entry, Cache(cache_dir), environ={"URDFLINT_TEST_LINK": "bad name!"})
    assert base != other
    assert other == lint(entry, None, environ={"URDFLINT_TEST_LINK": "bad name!"})


def test_a_setting_or_the_code_version_computes_again(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    cache_dir = tmp_path / "cache"
    everything = lint(robot, Cache(cache_dir))
    count = computed_count(monkeypatch)
    only = lint(robot, Cache(cache_dir), Settings(select=("C005",)))
    assert count == [1]
    assert {f["code"] for f in only} <= {"C005"} and only != everything
    lint(robot, Cache(cache_dir))
    assert count == [1]
    keys.code_version.cache_clear()
    monkeypatch.setattr("urdflint.__version__", "99.0.0")
    assert lint(robot, Cache(cache_dir)) == everything
    assert count == [2]
    keys.code_version.cache_clear()


def test_a_new_package_in_the_workspace_makes_the_result_stale(tmp_path: Path) -> None:
    robot = tmp_path / "ws" / "robot.urdf"
    robot.parent.mkdir()
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry>'
        '<mesh filename="package://late_pkg/meshes/a.stl"/></geometry></visual></link></robot>\n'
    )
    cache_dir = tmp_path / "cache"
    before = lint(robot, Cache(cache_dir), roots=[robot.parent])
    package = robot.parent / "late_pkg"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>late_pkg</name></package>")
    shutil.copy(next((MESH_RULE / "meshes").glob("*.stl")), package / "meshes" / "a.stl")
    workspace._LIVE.clear()
    after = lint(robot, Cache(cache_dir), roots=[robot.parent])
    assert after != before
    assert after == lint(robot, None, roots=[robot.parent])


def test_the_package_index_is_kept_and_checked(tmp_path: Path) -> None:
    ws = copy_tree(PACKAGES, tmp_path / "ws")
    cache = Cache(tmp_path / "cache")
    first = workspace.Packages([ws], cache)
    assert "pr2_description" in first
    walks: list[Any] = []
    original = workspace.discover
    try:
        workspace.discover = lambda paths: walks.append(paths) or original(paths)  # type: ignore[assignment]
        again = workspace.Packages([ws], Cache(tmp_path / "cache"))
        assert dict(again) == dict(first)
        assert walks == []  # the index came from the cache
        (ws / "new_pkg").mkdir()
        (ws / "new_pkg" / "package.xml").write_text("<package><name>new_pkg</name></package>")
        third = workspace.Packages([ws], Cache(tmp_path / "cache"))
        assert "new_pkg" in third and len(walks) == 1
    finally:
        workspace.discover = original  # type: ignore[assignment]


# -- a safe store -----------------------------------------------------------------------------


def test_a_truncated_or_foreign_entry_is_ignored_and_rewritten(tmp_path: Path) -> None:
    store = Store(tmp_path)
    assert store.put("x", "ab" * 20, {"value": 1})
    path = store.path("x", "ab" * 20)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) - 3])
    assert store.get("x", "ab" * 20) is None
    assert not path.exists()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"not an entry at all")
    assert store.get("x", "ab" * 20) is None
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(MAGIC + b"\xff" * 40)
    assert store.get("x", "ab" * 20) is None
    assert store.put("x", "ab" * 20, {"value": 2})
    assert store.get("x", "ab" * 20) == {"value": 2}


def test_corrupt_result_entries_still_give_the_right_findings(tmp_path: Path) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    cache_dir = tmp_path / "cache"
    first = lint(robot, Cache(cache_dir))
    for folder, _, files in os.walk(cache_dir / "analysis-v1"):
        for name in files:
            path = Path(folder) / name
            path.write_bytes(path.read_bytes()[:-1])
    assert lint(robot, Cache(cache_dir)) == first
    assert lint(robot, Cache(cache_dir)) == first


def test_the_folder_is_private_and_a_shared_one_is_not_used(tmp_path: Path) -> None:
    cache = Cache(tmp_path / "new")
    assert cache.usable
    assert (tmp_path / "new").stat().st_mode & 0o777 == 0o700
    assert (tmp_path / "new" / "CACHEDIR.TAG").read_text().startswith("Signature: 8a477f597d28")
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    refused = Cache(shared)
    assert not refused.usable and "others may write" in (refused.store.problem or "")
    robot = FIXTURES / "models" / "broken_arm.urdf"
    assert lint(robot, refused) == lint(robot, None)
    assert list(shared.iterdir()) == []


def test_a_read_only_cache_is_read_and_never_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    cache_dir = tmp_path / "cache"
    first = lint(robot, Cache(cache_dir))
    before = sorted(p for p in cache_dir.rglob("*") if p.is_file())
    monkeypatch.setattr(os, "access", lambda path, mode: mode != os.W_OK)  # as a CI restore
    readonly = Cache(cache_dir)
    assert readonly.usable and not readonly.store.writable
    count = computed_count(monkeypatch)
    assert lint(robot, readonly) == first
    assert count == [0]
    edited = robot.with_name("edited.urdf")
    edited.write_text(robot.read_text().replace("<robot", "<robot ", 1))
    assert lint(edited, readonly) == lint(edited, None)
    assert sorted(p for p in cache_dir.rglob("*") if p.is_file()) == before


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes anyway")
def test_a_read_only_folder_really_read_only(tmp_path: Path) -> None:
    robot = FIXTURES / "models" / "broken_arm.urdf"
    cache_dir = tmp_path / "cache"
    first = lint(robot, Cache(cache_dir))
    for folder, dirs, _ in os.walk(cache_dir):
        for name in dirs:
            os.chmod(os.path.join(folder, name), 0o500)
    os.chmod(cache_dir, 0o500)
    try:
        assert lint(robot, Cache(cache_dir)) == first
    finally:
        for folder, _dirs, _ in os.walk(cache_dir):
            os.chmod(folder, 0o700)


def test_the_size_stays_under_the_limit_least_recently_used_first(tmp_path: Path) -> None:
    store = Store(tmp_path, max_bytes=20_000)
    for i in range(40):
        store.put("x", f"{i:040x}", b"x" * 1000)
        os.utime(store.path("x", f"{i:040x}"), (1000 + i, 1000 + i))
    store.get("x", f"{0:040x}")  # used recently: kept
    removed = store.collect(force=True)
    assert removed > 0
    _count, size = store.size()
    assert size <= 20_000
    assert store.get("x", f"{0:040x}") is not None
    assert store.get("x", f"{1:040x}") is None


@pytest.mark.slow  # two processes race
def test_two_processes_writing_the_same_entries_at_once(tmp_path: Path) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    env = {**os.environ, "URDFLINT_CACHE_DIR": str(tmp_path / "cache")}
    command = [sys.executable, "-m", "urdflint", "check", str(robot), "--format", "json"]
    outputs = []
    for _ in range(3):
        runs = [
            subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
            for _ in range(3)
        ]
        for run in runs:
            out, err = run.communicate(timeout=300)
            assert run.returncode == 1, err
            outputs.append(json.loads(out)["findings"])
        shutil.rmtree(tmp_path / "cache" / "analysis-v1" / "check", ignore_errors=True)
    assert all(found == outputs[0] for found in outputs)
    assert not [p for p in (tmp_path / "cache").rglob(".tmp-*")]
    assert lint(robot, Cache(tmp_path / "cache")) == lint(robot, None)


def test_nothing_is_written_outside_the_cache_folder(tmp_path: Path) -> None:
    robot = copy_tree(MESH_RULE, tmp_path / "robot") / "bad.urdf"
    home = tmp_path / "home"
    home.mkdir()
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")}
    env = {**os.environ, "HOME": str(home), "XDG_CACHE_HOME": str(home / ".cache")}
    env.pop("URDFLINT_CACHE_DIR", None)
    command = [sys.executable, "-m", "urdflint", "check", str(robot.parent)]
    for _ in range(2):
        subprocess.run(command, capture_output=True, env=env, check=False, cwd=tmp_path)
    after = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")}
    changed = {p for p in after if before.get(p) != after[p]}
    cache = home / ".cache" / "urdflint"
    assert cache.is_dir()
    assert {p for p in changed if not p.is_relative_to(cache)} <= {home, home / ".cache"}


# -- the command line --------------------------------------------------------------------------


def run_cli(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "urdflint", *args],
        capture_output=True,
        text=True,
        env={**os.environ, **(env or {})},
        check=False,
        cwd=ROOT,
    )


def test_cli_cache_dir_no_cache_info_and_clean(tmp_path: Path) -> None:
    robot = str(FIXTURES / "models" / "broken_arm.urdf")
    folder = tmp_path / "c"
    first = run_cli("check", robot, "--format", "json", "--cache-dir", str(folder))
    second = run_cli("check", robot, "--format", "json", "--cache-dir", str(folder))
    plain = run_cli("check", robot, "--format", "json", "--no-cache", env={
        "URDFLINT_CACHE_DIR": str(tmp_path / "never")})  # fmt: skip
    assert first.returncode == second.returncode == plain.returncode == 1
    assert json.loads(first.stdout) == json.loads(second.stdout) == json.loads(plain.stdout)
    assert not (tmp_path / "never").exists()
    info = run_cli("cache", "info", "--cache-dir", str(folder), "--format", "json")
    data = json.loads(info.stdout)
    assert data["folder"] == str(folder) and data["entries"] > 0 and data["usable"]
    assert "check" in data["kinds"]
    text = run_cli("cache", "info", "--cache-dir", str(folder))
    assert f"folder:  {folder} (usable)" in text.stdout
    clean = run_cli("cache", "clean", "--cache-dir", str(folder))
    assert clean.returncode == 0 and "removed" in clean.stdout
    assert (
        json.loads(run_cli("cache", "info", "--cache-dir", str(folder), "--format", "json").stdout)[
            "entries"
        ]
        == 0
    )


def test_cache_dir_from_the_configuration(tmp_path: Path) -> None:
    project = tmp_path / "project"
    project.mkdir()
    shutil.copy(FIXTURES / "models" / "broken_arm.urdf", project / "arm.urdf")
    (project / "urdflint.toml").write_text('cache-dir = ".lintcache"\ncache-max-size = "64M"\n')
    result = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "arm.urdf"],
        capture_output=True, text=True, cwd=project, check=False,
        env={k: v for k, v in os.environ.items() if k != "URDFLINT_CACHE_DIR"},
    )  # fmt: skip
    assert result.returncode == 1, result.stderr
    assert (project / ".lintcache" / "analysis-v1" / "check").is_dir()
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "urdflint.toml").write_text('cache-max-size = "lots"\n')
    shutil.copy(FIXTURES / "models" / "broken_arm.urdf", bad / "arm.urdf")
    result = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "arm.urdf"],
        capture_output=True, text=True, cwd=bad, check=False,
    )  # fmt: skip
    assert result.returncode == 2 and "cache-max-size" in result.stderr


def test_racy_same_size_edit_is_seen(tmp_path: Path) -> None:
    """A file rewritten with the same size within the file system's time resolution: the
    content decides, not the modification time."""
    robot = tmp_path / "r.urdf"
    text = (FIXTURES / "models" / "broken_arm.urdf").read_text()
    robot.write_text(text)
    info = robot.stat()
    first = lint(robot, Cache(tmp_path / "cache"))
    assert 'value="-1.0"' in text
    robot.write_text(text.replace('value="-1.0"', 'value="+1.0"', 1))
    os.utime(robot, ns=(info.st_atime_ns, info.st_mtime_ns))  # same size, same time
    assert robot.stat().st_size == info.st_size
    found = lint(robot, Cache(tmp_path / "cache"))
    assert found != first and found == lint(robot, None)


def test_deps_record_reads_listings_and_explicit_inputs(tmp_path: Path) -> None:
    (tmp_path / "a.txt").write_text("a")
    with deps.recording() as rec:
        (tmp_path / "a.txt").read_text()
        os.listdir(tmp_path)
        deps.note_absent(tmp_path / "later.txt")
        with open(tmp_path / "out.txt", "w") as handle:  # a write is no input
            handle.write("x")
    found = {(d.kind, Path(d.name).name) for d in rec.deps()}
    assert ("file", "a.txt") in found and ("absent", "later.txt") in found
    assert ("dir", tmp_path.name) in found and ("file", "out.txt") not in found
    recorded = rec.deps()
    assert deps.unchanged(recorded)
    (tmp_path / "later.txt").write_text("now")
    assert not deps.unchanged(recorded)


@pytest.mark.slow  # a process pool
def test_jobs_replay_in_the_parent_and_pool_only_the_rest(tmp_path: Path) -> None:
    """A warm --jobs run gives the --jobs 1 output byte for byte; after an edit, only the
    edited file is linted again (the others are replayed)."""
    folder = copy_tree(FIXTURES / "rules" / "J009", tmp_path / "robots")
    for i in range(8):
        shutil.copy(FIXTURES / "models" / "broken_arm.urdf", folder / f"arm{i}.urdf")
    env = {**os.environ, "URDFLINT_CACHE_DIR": str(tmp_path / "cache")}
    command = [sys.executable, "-m", "urdflint", "check", str(folder), "--format", "json"]

    def run(*extra: str) -> str:
        done = subprocess.run([*command, *extra], capture_output=True, text=True, env=env)
        assert done.returncode == 1, done.stderr
        return done.stdout

    serial = run("--jobs", "1", "--no-cache")
    assert run("--jobs", "2") == serial  # cold, in the pool
    assert run("--jobs", "2") == serial  # warm, no pool
    edited = folder / "arm3.urdf"
    edited.write_text(edited.read_text().replace('value="-1.0"', 'value="-2.0"'))
    after = run("--jobs", "2")
    assert after == run("--jobs", "1", "--no-cache")
    assert after != serial and "mass -2" in after


def test_a_kept_expansion_is_patched_after_a_value_edit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The CLI keeps each entry's expansion with its source map: a value typed into a macro
    file patches it (no xacro runs) and gives the findings of a full expansion; a change of
    structure expands in full."""
    pytest.importorskip("xacro")
    entry, macro = _xacro_robot(tmp_path / "robot")
    cache_dir = tmp_path / "cache"
    lint(entry, Cache(cache_dir))
    from urdflint.sources.xacro import expansion

    runs: list[Any] = []
    original = expansion.Expansion.run
    monkeypatch.setattr(expansion.Expansion, "run", lambda self: runs.append(1) or original(self))
    macro.write_text(macro.read_text().replace('value="1.0"', 'value="-2.5"'))
    patched = lint(entry, Cache(cache_dir))
    assert runs == []
    assert patched == lint(entry, None)
    assert [(f["code"], Path(f["path"]).name, f["line"]) for f in patched if f["code"] == "I002"]
    assert len(runs) == 1  # the run without the cache
    macro.write_text(macro.read_text().replace("<inertial>", "<inertial><!-- moved -->\n", 1))
    moved = lint(entry, Cache(cache_dir))
    assert len(runs) == 2 and moved == lint(entry, None)


def test_an_srdf_written_beside_the_urdf_makes_the_result_stale(tmp_path: Path) -> None:
    robot = tmp_path / "bad.urdf"
    shutil.copy(FIXTURES / "rules" / "M001" / "bad.urdf", robot)
    cache_dir = tmp_path / "cache"
    alone = lint(robot, Cache(cache_dir))
    assert "M001" not in {f["code"] for f in alone}
    shutil.copy(FIXTURES / "rules" / "M001" / "bad.srdf", tmp_path / "bad.srdf")
    paired = lint(robot, Cache(cache_dir))
    assert "M001" in {f["code"] for f in paired}
    assert paired == lint(robot, None)
