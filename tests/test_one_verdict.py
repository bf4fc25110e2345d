"""One file, one verdict: the CLI, the pre-commit hook, the HTTP API (what the page shows)
and the language server give the same findings for the same file and settings, with the
same defaults: targets given nowhere are inferred alike (issue 24, 8).

The page renders the API's answer; tests/server/test_browser.py checks it shows what the API
says (``test_corpus_robot_matches_the_api``) and sends no target of its own by default.
The pre-commit hook is its entry in .pre-commit-hooks.yaml, run as pre-commit runs it: the
console script with the staged file names, from the repository's root.
"""

from __future__ import annotations

import asyncio
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import FIXTURES

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
pytest.importorskip("fastapi")
yaml = pytest.importorskip("yaml")

from fastapi.testclient import TestClient  # noqa: E402
from lsprotocol import types as T  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402

from tests.test_lsp import start  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MODELS = [
    FIXTURES / "models" / "broken_arm.urdf",  # no evidence: targets assumed
    FIXTURES / "targets" / "sim_plugin" / "arm.urdf",  # a Gazebo Sim plugin: inferred
    FIXTURES / "targets" / "mujoco_block" / "arm.urdf",  # a <mujoco> block: inferred
    FIXTURES / "rules" / "C009" / "bad_drake.urdf",  # with its configuration: given
]
SEVERITY = {1: "error", 2: "warning", 3: "info", 4: "info"}

Verdict = set[tuple[str, int, str, str]]  # (code, line, severity, message)


def _placed(model: Path, where: Path) -> Path:
    """``model`` copied into ``where`` with the meshes beside it; a fixture's own settings
    (``<stem>.toml``) become the folder's ``urdflint.toml``, which every surface reads."""
    shutil.copytree(model.parent, where, dirs_exist_ok=True)
    settings = model.with_suffix(".toml")
    if settings.is_file():
        (where / "urdflint.toml").write_text(settings.read_text())
    return where / model.name


def _from_json(data: dict) -> Verdict:
    return {(f["code"], f["line"], f["severity"], f["message"]) for f in data["findings"]}


def cli(path: Path, *options: str) -> Verdict:
    done = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "json", "--no-cache", *options,
         path.name],
        cwd=path.parent, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert done.returncode in (0, 1), done.stderr
    return _from_json(json.loads(done.stdout))


def precommit(path: Path) -> Verdict:
    """The hook's entry with the file name appended, from the repository root (pre-commit
    passes paths relative to it), plus the JSON format a user may add in ``args``."""
    (hook,) = [h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
               if h["id"] == "urdflint"]  # fmt: skip
    program, *entry = hook["entry"].split()
    script = Path(sys.executable).parent / program
    repo = path.parent.parent
    rel = path.relative_to(repo)
    done = subprocess.run(
        [str(script), *entry, "--format", "json", "--no-cache", str(rel)],
        cwd=repo, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert done.returncode in (0, 1), done.stderr
    verdict = _from_json(json.loads(done.stdout))
    return verdict


@pytest.fixture(scope="module")
def service() -> object:
    from urdflint.server.app import create_app

    with TestClient(create_app()) as client:
        yield client


def api(service: TestClient, path: Path) -> Verdict:
    """``/v1/check`` with the file (and its configuration as the ``config`` option, as the
    page's "More options" sends it), meshes zipped beside it."""
    import io
    import tomllib
    import zipfile

    files = {"urdf": (path.name, path.read_bytes(), "application/xml")}
    meshes = path.parent / "meshes"
    if meshes.is_dir():
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w") as zf:
            for item in sorted(meshes.rglob("*")):
                if item.is_file():
                    zf.write(item, f"meshes/{item.relative_to(meshes).as_posix()}")
        files["meshes"] = ("meshes.zip", buffer.getvalue(), "application/zip")
    data = {}
    settings = path.parent / "urdflint.toml"
    if settings.is_file():
        data["config"] = json.dumps(tomllib.loads(settings.read_text()))
    answer = service.post("/v1/check", files=files, data=data)
    assert answer.status_code == 200, answer.text
    return _from_json(answer.json())


SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "urdflint", "lsp", "--no-cache"])


@pytest_lsp.fixture(config=SERVER)
async def client(lsp_client: LanguageClient, tmp_path: Path):
    await start(lsp_client, tmp_path)
    yield
    await lsp_client.shutdown_session()


async def editor(client: LanguageClient, path: Path) -> Verdict:
    uri = path.as_uri()
    client.text_document_did_open(
        T.DidOpenTextDocumentParams(T.TextDocumentItem(uri, "xml", 1, path.read_text()))
    )

    async def wait() -> None:
        while uri not in client.diagnostics:
            await asyncio.sleep(0.02)

    await asyncio.wait_for(wait(), 120)
    return {
        (
            str(d.code),
            int((d.data or {})["line"]),
            SEVERITY[int(d.severity or 1)],
            d.message.split("\nFix: ")[0],
        )
        for d in client.diagnostics[uri]
    }


@pytest.mark.asyncio
@pytest.mark.parametrize("model", MODELS, ids=lambda p: f"{p.parent.name}/{p.name}")
async def test_cli_hook_api_and_editor_agree(
    client: LanguageClient, service: TestClient, tmp_path: Path, model: Path
) -> None:
    path = _placed(model, tmp_path / "repo" / "robot")
    subprocess.run(["git", "init", "-q", str(tmp_path / "repo")], check=True)
    expected = cli(path)
    assert expected, "a model with no finding proves nothing"
    assert precommit(path) == expected
    assert api(service, path) == expected
    assert await editor(client, path) == expected


@pytest.mark.parametrize(
    "statics",
    [{"payload": "2@tool"}, {"payload": "2@tool", "gravity": "0,0,-12"}, {"gravity": "0,0,-30"}],
    ids=["payload", "payload-and-gravity", "gravity"],
)
def test_statics_options_give_the_cli_s_d001_through_the_api(
    service: TestClient, tmp_path: Path, statics: dict[str, str]
) -> None:
    """``payload`` and ``gravity`` on ``/v1/check`` are ``--payload`` and ``--gravity``: the
    same D001 findings (the fixture's own payload configuration is left behind)."""
    path = tmp_path / "arm.urdf"
    shutil.copy(FIXTURES / "rules" / "D001" / "bad_payload.urdf", path)
    flags = [f"--{name}={value}" for name, value in statics.items()]
    expected = {f for f in cli(path, "--isolated", *flags) if f[0] == "D001"}
    assert expected, "no D001 with these statics proves nothing"
    files = {"urdf": (path.name, path.read_bytes(), "application/xml")}
    answer = service.post("/v1/check", files=files, data=statics)
    assert answer.status_code == 200, answer.text
    assert {f for f in _from_json(answer.json()) if f[0] == "D001"} == expected
    plain = service.post("/v1/check", files=files)  # without them: the elbow holds
    assert [f for f in _from_json(plain.json()) if f[0] == "D001"] == []
