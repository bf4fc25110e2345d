// urdflint for VS Code: a thin language client that starts `urdflint lsp` over stdio.
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');
const vscode = require('vscode');
const { LanguageClient } = require('vscode-languageclient/node');

const DEFAULT_COMMAND = ['urdflint'];
const INSTALL_HINT =
  "pip install -e '.[lsp]' in a urdflint checkout and set urdflint.path " +
  '(e.g. ["/path/to/.venv/bin/urdflint"])';

const DOCUMENT_SELECTOR = [
  { scheme: 'file', language: 'urdf' },
  { scheme: 'file', language: 'xacro' },
  { scheme: 'file', pattern: '**/*.urdf' },
  { scheme: 'file', pattern: '**/*.xacro' },
  { scheme: 'file', pattern: '**/*.urdf.xacro' },
  // The server re-reads the project's configuration when one of these is saved.
  { scheme: 'file', pattern: '**/{urdflint.toml,.urdflint.toml,pyproject.toml}' },
];

let client;
let output;

function workspaceFolder() {
  const folders = vscode.workspace.workspaceFolders;
  return folders && folders.length > 0 ? folders[0].uri.fsPath : undefined;
}

function expand(part, folder) {
  let out = part;
  if (folder !== undefined) {
    out = out.split('${workspaceFolder}').join(folder);
  }
  if (out === '~' || out.startsWith('~/') || out.startsWith('~\\')) {
    out = path.join(os.homedir(), out.slice(1));
  }
  return out;
}

/** The process to start: `urdflint.path` (program, then its arguments) followed by `lsp`. */
function serverCommand() {
  let configured = vscode.workspace.getConfiguration('urdflint').get('path', DEFAULT_COMMAND);
  if (typeof configured === 'string') {
    configured = [configured];
  }
  let parts = Array.isArray(configured)
    ? configured.filter((part) => typeof part === 'string' && part.trim() !== '')
    : [];
  if (parts.length === 0) {
    parts = DEFAULT_COMMAND;
  }
  const folder = workspaceFolder();
  parts = parts.map((part) => expand(part, folder));
  const options = folder !== undefined ? { cwd: folder } : {};
  // No `transport`: the client would add `--stdio`, which `urdflint lsp` does not take.
  return { command: parts[0], args: [...parts.slice(1), 'lsp'], options };
}

/** Whether `command` names an executable file (as given, or on PATH). */
function findExecutable(command) {
  const isFile = (file) => {
    try {
      return fs.statSync(file).isFile();
    } catch {
      return false;
    }
  };
  const exts =
    process.platform === 'win32'
      ? ['', ...(process.env.PATHEXT || '.EXE;.CMD;.BAT;.COM').split(';')]
      : [''];
  if (path.isAbsolute(command) || command.includes('/') || command.includes('\\')) {
    return exts.some((ext) => isFile(command + ext));
  }
  const dirs = (process.env.PATH || '').split(path.delimiter).filter((dir) => dir !== '');
  return dirs.some((dir) => exts.some((ext) => isFile(path.join(dir, command + ext))));
}

async function reportFailure(message) {
  const settings = 'Open Settings';
  const showOutput = 'Show Output';
  const choice = await vscode.window.showErrorMessage(message, settings, showOutput);
  if (choice === settings) {
    await vscode.commands.executeCommand('workbench.action.openSettings', 'urdflint.path');
  } else if (choice === showOutput && output !== undefined) {
    output.show(true);
  }
}

async function startClient() {
  const server = serverCommand();
  if (!findExecutable(server.command)) {
    void reportFailure(`urdflint not found (${server.command}): ${INSTALL_HINT}.`);
    return;
  }
  const next = new LanguageClient(
    'urdflint',
    'urdflint',
    server,
    {
      documentSelector: DOCUMENT_SELECTOR,
      outputChannel: output,
    },
  );
  client = next;
  try {
    await next.start();
  } catch (error) {
    if (client === next) {
      client = undefined;
    }
    const line = [server.command, ...server.args].join(' ');
    const reason = String(error && error.message ? error.message : error);
    const what = reason.includes('ENOENT') ? 'urdflint not found' : 'urdflint lsp could not start';
    void reportFailure(`${what} (${line}): ${reason}. ${INSTALL_HINT}; see the urdflint output.`);
  }
}

async function stopClient() {
  const running = client;
  client = undefined;
  if (running !== undefined) {
    try {
      await running.stop();
    } catch {
      // it did not start, or is already gone
    }
  }
}

async function restart() {
  await stopClient();
  await startClient();
}

async function activate(context) {
  output = vscode.window.createOutputChannel('urdflint');
  context.subscriptions.push(
    output,
    vscode.commands.registerCommand('urdflint.restartServer', restart),
    vscode.workspace.onDidChangeConfiguration((event) => {
      if (event.affectsConfiguration('urdflint.path')) {
        void restart();
      }
    }),
  );
  await startClient();
}

function deactivate() {
  return stopClient();
}

module.exports = { activate, deactivate, serverCommand, DOCUMENT_SELECTOR };
