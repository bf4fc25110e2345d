"""The VS Code extension in editors/vscode: what it starts, and the .vsix that vsce packages.

The launch tests run ``extension.js`` under node with stand-ins for the ``vscode`` and
``vscode-languageclient`` modules (no VS Code, no npm), and hand the command it would start
to the real ``urdflint lsp``. The packaging tests run ``npm ci`` and ``npm run package``
once, in a copy of the folder (the checkout stays clean; network to the npm registry), and
read the .vsix. Skipped when node or npm is missing.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.slow  # npm and vsce package the extension

EXTENSION = ROOT / "editors" / "vscode"
NODE = shutil.which("node")
NPM = shutil.which("npm")
needs_node = pytest.mark.skipif(NODE is None, reason="node missing")
NETWORK_ERRORS = ("ENOTFOUND", "EAI_AGAIN", "ECONNREFUSED", "ECONNRESET", "ETIMEDOUT")
PATTERNS = {"**/*.urdf", "**/*.xacro", "**/*.urdf.xacro"}


def manifest() -> dict[str, Any]:
    return json.loads((EXTENSION / "package.json").read_text())


def test_manifest() -> None:
    pkg = manifest()
    assert pkg["name"] == "urdflint" and pkg["version"] == "0.1.0"
    assert pkg["main"] == "./extension.js"
    assert pkg["engines"]["vscode"] == "^1.82.0"
    assert {"onLanguage:urdf", "onLanguage:xacro", "onLanguage:xml"} <= set(pkg["activationEvents"])
    assert {"workspaceContains:**/*.urdf", "workspaceContains:**/*.xacro"} <= set(
        pkg["activationEvents"]
    )
    languages = {lang["id"]: lang["extensions"] for lang in pkg["contributes"]["languages"]}
    assert languages == {"urdf": [".urdf"], "xacro": [".xacro"]}
    settings = pkg["contributes"]["configuration"]["properties"]
    assert settings["urdflint.path"]["type"] == "array"
    assert settings["urdflint.path"]["default"] == ["urdflint"]
    assert "urdflint.trace.server" in settings
    assert pkg["dependencies"]["vscode-languageclient"].startswith("^9")
    assert "@vscode/vsce" in pkg["devDependencies"]
    assert "--allow-missing-repository" in pkg["scripts"]["package"]
    # every file the manifest points at is in the folder
    referenced = [pkg["main"], *(g["path"] for g in pkg["contributes"]["grammars"])]
    referenced += [lang["configuration"] for lang in pkg["contributes"]["languages"]]
    for name in [*referenced, "README.md", "LICENSE", "CHANGELOG.md", ".vscodeignore"]:
        assert (EXTENSION / name).is_file(), name


def test_lockfile_matches_manifest() -> None:
    """`npm ci` refuses a package-lock.json that disagrees with package.json."""
    pkg = manifest()
    lock = json.loads((EXTENSION / "package-lock.json").read_text())
    root = lock["packages"][""]
    assert lock["lockfileVersion"] >= 2
    assert root["dependencies"] == pkg["dependencies"]
    assert root["devDependencies"] == pkg["devDependencies"]
    assert "node_modules/vscode-languageclient" in lock["packages"]
    assert not lock["packages"]["node_modules/vscode-languageclient"].get("dev", False)
    assert lock["packages"]["node_modules/@vscode/vsce"]["dev"] is True


def test_build_outputs_are_ignored() -> None:
    ignored = (EXTENSION / ".gitignore").read_text().split()
    assert "node_modules/" in ignored and "*.vsix" in ignored


@needs_node
def test_extension_js_parses() -> None:
    proc = subprocess.run(
        [NODE, "--check", str(EXTENSION / "extension.js")], capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr


# -- the launch, with stand-ins for VS Code --------------------------------------------------

HARNESS = r"""
const Module = require('module');
const scenario = JSON.parse(process.argv[3]);
const record = { clients: [], errors: [], starts: 0, stops: 0, commands: [] };
const listeners = [];
const vscode = {
  workspace: {
    workspaceFolders: scenario.folder ? [{ uri: { fsPath: scenario.folder } }] : undefined,
    getConfiguration: (section) => ({
      get: (key, fallback) => {
        const value = scenario.config[`${section}.${key}`];
        return value === undefined ? fallback : value;
      },
    }),
    onDidChangeConfiguration: (listener) => { listeners.push(listener); return { dispose() {} }; },
  },
  window: {
    createOutputChannel: (name) => ({ name, show() {}, appendLine() {}, dispose() {} }),
    showErrorMessage: async (message) => { record.errors.push(message); return undefined; },
  },
  commands: {
    registerCommand: (id) => { record.commands.push(id); return { dispose() {} }; },
    executeCommand: async () => undefined,
  },
};
class LanguageClient {
  constructor(id, name, server, options) {
    record.clients.push({ id, name, server, documentSelector: options.documentSelector });
  }
  async start() {
    record.starts += 1;
    if (scenario.startError !== undefined) throw scenario.startError;
  }
  async stop() { record.stops += 1; }
}
const load = Module._load;
Module._load = function (request, ...rest) {
  if (request === 'vscode') return vscode;
  if (request === 'vscode-languageclient/node') return { LanguageClient };
  return load.call(this, request, ...rest);
};
(async () => {
  const extension = require(process.argv[2]);
  await extension.activate({ subscriptions: [] });
  if (scenario.changePath !== undefined) {
    scenario.config['urdflint.path'] = scenario.changePath;
    const event = { affectsConfiguration: (name) => name === 'urdflint.path' };
    listeners.forEach((listener) => listener(event));
    await new Promise((resolve) => setTimeout(resolve, 50));
  }
  record.stopsBeforeDeactivate = record.stops;
  await extension.deactivate();
  process.stdout.write(JSON.stringify(record));
})().catch((error) => { console.error(error); process.exit(1); });
"""


def activate(tmp_path: Path, **scenario: Any) -> dict[str, Any]:
    """Activate extension.js in node with fake VS Code modules; what it did."""
    assert NODE is not None
    harness = tmp_path / "harness.js"
    harness.write_text(HARNESS)
    scenario.setdefault("config", {})
    proc = subprocess.run(
        [NODE, str(harness), str(EXTENSION / "extension.js"), json.dumps(scenario)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def lsp_frames(*messages: dict[str, Any]) -> bytes:
    out = b""
    for message in messages:
        body = json.dumps({"jsonrpc": "2.0", **message}).encode()
        out += b"Content-Length: %d\r\n\r\n" % len(body) + body
    return out


def lsp_replies(data: bytes) -> list[dict[str, Any]]:
    replies = []
    while data:
        header, _, rest = data.partition(b"\r\n\r\n")
        length = next(
            int(line.split(b":")[1])
            for line in header.split(b"\r\n")
            if line.lower().startswith(b"content-length")
        )
        replies.append(json.loads(rest[:length]))
        data = rest[length:]
    return replies


@needs_node
def test_launches_urdflint_lsp_over_stdio(tmp_path: Path) -> None:
    record = activate(
        tmp_path, folder=str(tmp_path), config={"urdflint.path": [sys.executable, "-m", "urdflint"]}
    )
    assert record["errors"] == []
    assert "urdflint.restartServer" in record["commands"]
    (client,) = record["clients"]
    assert client["id"] == "urdflint"  # so urdflint.trace.server applies
    server = client["server"]
    assert server["command"] == sys.executable
    assert server["args"] == ["-m", "urdflint", "lsp"]
    assert "transport" not in server  # the client would append --stdio
    assert server["options"]["cwd"] == str(tmp_path)
    selector = client["documentSelector"]
    assert all(entry["scheme"] == "file" for entry in selector)
    assert {e["language"] for e in selector if "language" in e} == {"urdf", "xacro"}
    assert {e["pattern"] for e in selector if "pattern" in e} >= PATTERNS
    assert record["starts"] == 1 and record["stops"] == 1  # deactivate stopped it

    # what the extension starts is the language server
    pytest.importorskip("pygls")
    proc = subprocess.run(
        [server["command"], *server["args"]],
        input=lsp_frames(
            {"id": 1, "method": "initialize", "params": {"processId": None, "capabilities": {}}},
            {"method": "initialized", "params": {}},
            {"id": 2, "method": "shutdown"},
            {"method": "exit"},
        ),
        capture_output=True,
        cwd=server["options"]["cwd"],
        timeout=120,
    )
    replies = {r.get("id"): r for r in lsp_replies(proc.stdout)}
    result = replies[1]["result"]
    assert result["serverInfo"]["name"] == "urdflint"
    capabilities = result["capabilities"]
    assert {"hoverProvider", "codeActionProvider", "documentSymbolProvider"} <= set(capabilities)


@needs_node
def test_workspace_folder_and_a_string_path(tmp_path: Path) -> None:
    program = tmp_path / "venv" / "bin" / "urdflint"
    program.parent.mkdir(parents=True)
    program.write_text("#!/bin/sh\n")
    program.chmod(0o755)
    record = activate(
        tmp_path,
        folder=str(tmp_path),
        config={"urdflint.path": "${workspaceFolder}/venv/bin/urdflint"},
    )
    (client,) = record["clients"]
    assert client["server"]["command"] == str(program)
    assert client["server"]["args"] == ["lsp"]


@needs_node
def test_default_path_is_urdflint_on_path(tmp_path: Path) -> None:
    record = activate(tmp_path)  # no setting, no workspace folder
    if shutil.which("urdflint") is None:
        assert record["clients"] == []
        assert record["errors"] and record["errors"][0].startswith("urdflint not found")
    else:
        (client,) = record["clients"]
        assert client["server"]["command"] == "urdflint"
        assert client["server"]["args"] == ["lsp"]


@needs_node
def test_missing_command_explains_the_install(tmp_path: Path) -> None:
    missing = str(tmp_path / "nowhere" / "urdflint")
    record = activate(tmp_path, config={"urdflint.path": [missing]})
    assert record["clients"] == []  # nothing started
    (message,) = record["errors"]
    assert message.startswith(f"urdflint not found ({missing})")
    assert "pip install -e '.[lsp]'" in message and "urdflint.path" in message


@needs_node
@pytest.mark.parametrize(
    ("error", "expected"),
    [
        (
            "Launching server using command urdflint failed. Error: spawn urdflint ENOENT",
            "urdflint not found",
        ),
        (
            {"message": "Pending response rejected since connection got disposed"},
            "urdflint lsp could not start",
        ),
    ],
    ids=["spawn-ENOENT", "initialize-failed"],
)
def test_start_failure_is_reported(tmp_path: Path, error: object, expected: str) -> None:
    record = activate(
        tmp_path,
        config={"urdflint.path": [sys.executable, "-m", "urdflint"]},
        startError=error,
    )
    (message,) = record["errors"]
    assert message.startswith(f"{expected} ({sys.executable} -m urdflint lsp): ")
    assert "urdflint.path" in message
    assert record["stops"] == 0  # nothing to stop on deactivate


@needs_node
def test_changing_the_path_restarts_the_server(tmp_path: Path) -> None:
    record = activate(
        tmp_path,
        config={"urdflint.path": [sys.executable, "-m", "urdflint"]},
        changePath=[sys.executable, "-X", "utf8", "-m", "urdflint"],
    )
    first, second = record["clients"]
    assert first["server"]["args"] == ["-m", "urdflint", "lsp"]
    assert second["server"]["args"] == ["-X", "utf8", "-m", "urdflint", "lsp"]
    assert record["stopsBeforeDeactivate"] == 1 and record["stops"] == 2


# -- the package ------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def vsix(tmp_path_factory: pytest.TempPathFactory) -> zipfile.ZipFile:
    if NPM is None:
        pytest.skip("npm missing")
    work = tmp_path_factory.mktemp("vscode") / "vscode"
    shutil.copytree(EXTENSION, work, ignore=shutil.ignore_patterns("node_modules", "*.vsix"))
    env = {**os.environ, "npm_config_audit": "false", "npm_config_fund": "false"}
    env["npm_config_update_notifier"] = "false"

    def npm(*args: str) -> subprocess.CompletedProcess[str]:
        assert NPM is not None
        return subprocess.run(
            [NPM, *args], cwd=work, env=env, capture_output=True, text=True, timeout=900
        )

    ci = npm("ci")
    if ci.returncode != 0:
        if any(error in ci.stdout + ci.stderr for error in NETWORK_ERRORS):
            pytest.skip(f"npm ci cannot reach the registry: {ci.stderr.strip()[-300:]}")
        pytest.fail(f"npm ci failed:\n{ci.stdout}\n{ci.stderr}")
    package = npm("run", "package")
    assert package.returncode == 0, package.stdout + package.stderr
    return zipfile.ZipFile(work / "urdflint.vsix")


def test_vsix_manifest(vsix: zipfile.ZipFile) -> None:
    pkg = json.loads(vsix.read("extension/package.json"))
    assert pkg["main"] == "./extension.js"
    assert {"onLanguage:urdf", "onLanguage:xacro", "onLanguage:xml"} <= set(pkg["activationEvents"])
    assert pkg["contributes"]["configuration"]["properties"]["urdflint.path"]["default"] == [
        "urdflint"
    ]
    identity = vsix.read("extension.vsixmanifest").decode()
    assert 'Id="urdflint"' in identity and 'Publisher="urdflint"' in identity
    assert 'Version="0.1.0"' in identity


def test_vsix_files(vsix: zipfile.ZipFile) -> None:
    names = set(vsix.namelist())
    pkg = json.loads(vsix.read("extension/package.json"))
    assert vsix.read("extension/extension.js") == (EXTENSION / "extension.js").read_bytes()
    for grammar in pkg["contributes"]["grammars"]:
        assert "extension/" + grammar["path"].removeprefix("./") in names
    for language in pkg["contributes"]["languages"]:
        assert "extension/" + language["configuration"].removeprefix("./") in names
    assert {"extension/README.md", "extension/CHANGELOG.md", "extension/LICENSE.txt"} <= names
    assert not any(n.endswith((".vsix", "package-lock.json", ".gitignore")) for n in names)


def test_vsix_bundles_runtime_dependencies_only(vsix: zipfile.ZipFile) -> None:
    names = vsix.namelist()
    modules = {n.split("/")[2] for n in names if n.startswith("extension/node_modules/")}
    assert "extension/node_modules/vscode-languageclient/package.json" in names
    assert "extension/node_modules/vscode-languageclient/node.js" in names
    assert {"vscode-jsonrpc", "vscode-languageserver-protocol"} <= modules
    assert "@vscode" not in modules  # vsce and the rest of the dev dependencies stay out
    assert not any("/node_modules/@vscode/vsce" in n for n in names)
    assert len(names) < 600 and sum(i.file_size for i in vsix.infolist()) < 5_000_000
