"""Mesh resolution and loading on the real robots of ../shared/corpus (skipped without it).

For every robot with a ``package_map.json``, the mesh references are resolved here
independently of urdflint (lxml and the map only), and C004 must report exactly the
references whose file does not exist; every file that exists must load (no C005) and
no rule may crash (no U001).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import CORPUS, needs_corpus
from urdflint.engine import config, linter
from urdflint.engine.context import Context

pytestmark = [needs_corpus, pytest.mark.filterwarnings("error")]
pytest.importorskip("trimesh")


def mapped_robots() -> list[Path]:
    return sorted(p.parent / "model.urdf" for p in CORPUS.glob("*/package_map.json"))


def package_paths(model: Path) -> dict[str, Path]:
    mapping = json.loads((model.parent / "package_map.json").read_text())
    return {name: model.parent / folder for name, folder in mapping.items()}


def expected_files(model: Path) -> list[tuple[int, str, Path | None]]:
    """``(line, filename, file or None)`` of every visual/collision mesh, resolved by hand."""
    root = etree.parse(str(model)).getroot()
    packages = package_paths(model)
    found = []
    for el in root.iterfind("link/*/geometry/mesh"):
        if el.getparent().getparent().tag not in ("visual", "collision"):
            continue
        uri = (el.get("filename") or "").strip()
        if not uri or "${" in uri or "$(" in uri:
            continue
        path: Path | None
        if uri.startswith("package://"):
            name, _, rest = uri[len("package://") :].lstrip("/").partition("/")
            path = packages[name] / rest if name in packages else None
        elif uri.startswith("file://"):
            path = Path(uri[len("file://") :])
        else:
            path = model.parent / uri
        found.append((el.sourceline, uri, path if path is not None and path.is_file() else None))
    return found


@pytest.fixture(scope="module")
def results() -> dict[Path, tuple[linter.Result, Context]]:
    settings = config.Settings(select=("C", "I"))
    out = {}
    for model in mapped_robots():
        context = Context(package_paths=package_paths(model), environ={})
        out[model] = (linter.lint_path(model, str(model), settings, context), context)
    return out


def test_corpus_has_the_mapped_robots() -> None:
    assert len(mapped_robots()) >= 16


@pytest.mark.parametrize("model", mapped_robots(), ids=lambda p: p.parent.name)
def test_c004_reports_exactly_the_missing_files(results, model: Path) -> None:
    result, _ = results[model]
    missing = {(line, uri) for line, uri, path in expected_files(model) if path is None}
    reported = {
        (f.line, uri)
        for f in result.findings
        if f.code == "C004"
        for line, uri, _ in expected_files(model)
        if line == f.line and repr(uri) in f.message
    }
    assert len([f for f in result.findings if f.code == "C004"]) == len(missing)
    assert reported == missing


@pytest.mark.parametrize("model", mapped_robots(), ids=lambda p: p.parent.name)
def test_every_existing_mesh_loads(results, model: Path) -> None:
    result, context = results[model]
    assert not [f for f in result.findings if f.code in ("C005", "U001")]
    files = {path.resolve() for _, _, path in expected_files(model) if path is not None}
    loaded = {path for path, _ in context.meshes._cache} if files else set()
    assert files <= loaded
    assert all(info.error is None for info in context.meshes._cache.values())


def test_robots_with_missing_meshes() -> None:
    """eve_r3 (qb_hand_description is not shipped) and robotiq_3f (stale .STL names)."""
    for name, count in (("eve_r3", 9), ("robotiq_3f", 5)):
        model = CORPUS / name / "model.urdf"
        files = {uri for _, uri, path in expected_files(model) if path is None}
        assert len(files) == count, (name, sorted(files))


def test_triple_slash_package_uris_resolve() -> None:
    """talos writes package:///example-robot-data/...; tiago ships that package's folder."""
    model = CORPUS / "talos" / "model.urdf"
    package = CORPUS / "tiago" / "meshes" / "example-robot-data"
    context = Context(package_paths={"example-robot-data": package}, environ={})
    result = linter.lint_path(model, str(model), config.Settings(select=("C004",)), context)
    root = etree.parse(str(model)).getroot()
    uris = [el.get("filename", "") for el in root.iterfind("link/*/geometry/mesh")]
    assert sum(uri.startswith("package:///") for uri in uris) > 90
    assert len(result.findings) == len(uris)
    talos = package / "robots" / "talos_data"
    assert all(f"no file at {talos}" in f.message for f in result.findings)
    assert {f.severity.name for f in result.findings} == {"ERROR"}
