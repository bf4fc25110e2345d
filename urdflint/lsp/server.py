"""``urdflint lsp``: the Language Server Protocol over stdio (pygls).

Diagnostics on open, on change (debounced, from the unsaved buffer) and on save, in every file
the defects are written in; code actions (the finding's fix, a suppression comment); hover (the
rule, a link's inertia, the robot's mass and centre of mass); the link/joint outline. Linting
runs on one worker thread, so the editor's requests are answered while a robot is checked.
"""

from __future__ import annotations

import asyncio
import os
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from lsprotocol import types as T
from pygls.lsp.server import LanguageServer

from urdflint import __version__
from urdflint.engine import config
from urdflint.lsp import convert, describe
from urdflint.lsp.analysis import Analyzer, wanted

MAX_ANALYSES = 12  # entries analysed for one change, through nested macro files
DEBOUNCE = 0.025  # s after the last keystroke before a buffer is linted


class UrdflintServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__(
            "urdflint", __version__, text_document_sync_kind=T.TextDocumentSyncKind.Full
        )
        self.analyzer = Analyzer()
        self.worker = ThreadPoolExecutor(1, thread_name_prefix="urdflint-lint")
        self.pending: dict[str, asyncio.Task[None]] = {}
        self.shown: set[str] = set()  # files whose published diagnostics are not empty

    # -- diagnostics ----------------------------------------------------------------------

    def schedule(self, path: str, delay: float) -> None:
        """Lint what ``path`` affects after ``delay`` (a newer change restarts the wait)."""
        old = self.pending.pop(path, None)
        if old is not None:
            old.cancel()
        self.pending[path] = asyncio.get_running_loop().create_task(self._later(path, delay))

    async def _later(self, path: str, delay: float) -> None:
        await asyncio.sleep(delay)
        self.pending.pop(path, None)
        loop = asyncio.get_running_loop()
        touched = await loop.run_in_executor(self.worker, self._analyse, path)
        for file in sorted(touched):
            self.publish(file)

    def _analyse(self, path: str) -> set[str]:
        """Run the analyses ``path`` affects; the files whose diagnostics may have changed."""
        touched = {path}
        todo, done = self.analyzer.affected(path), set()
        while todo:
            entry = todo.pop(0)
            if entry in done:
                continue
            done.add(entry)
            before = self.analyzer.analyses.get(entry)
            after = self.analyzer.analyse(entry)
            touched |= set(after.findings) | {entry}
            if before is not None:
                touched |= set(before.findings)
            if after.library and len(done) <= MAX_ANALYSES and not self.analyzer.reached(entry):
                # a macro file: through the files that include it (a macro file included by
                # another macro file: through that one's, and so on)
                todo += self.analyzer.entries_of(entry)
        return touched

    def publish(self, path: str) -> None:
        findings = self.analyzer.findings_for(path)
        if not findings and path not in self.shown:
            return
        text = self.analyzer.text(path) or ""
        lines = convert.lines_of(text)
        diagnostics = [convert.diagnostic(lines, f) for f in findings]
        (self.shown.add if diagnostics else self.shown.discard)(path)
        self.text_document_publish_diagnostics(
            T.PublishDiagnosticsParams(uri=convert.uri_of(path), diagnostics=diagnostics)
        )

    # -- requests -------------------------------------------------------------------------

    def finding_for(self, path: str, diagnostic: T.Diagnostic) -> Any:
        data = diagnostic.data if isinstance(diagnostic.data, dict) else {}
        for finding in self.analyzer.findings_for(path):
            if finding.code != diagnostic.code:
                continue
            if (finding.line, finding.column) == (data.get("line"), data.get("column")):
                return finding
            if not data and finding.line - 1 == diagnostic.range.start.line:
                return finding
        return None

    def actions(self, params: T.CodeActionParams) -> list[T.CodeAction]:
        path = convert.path_of(params.text_document.uri)
        if path is None:
            return []
        lines = convert.lines_of(self.analyzer.text(path) or "")
        found: list[T.CodeAction] = []
        for diagnostic in params.context.diagnostics:
            if diagnostic.source != convert.SOURCE:
                continue
            finding = self.finding_for(os.path.abspath(path), diagnostic)
            if finding is None:
                continue
            fix = finding.autofix
            if fix is not None and fix.edits and not fix.unavailable:
                edit = convert.fix_edit(fix, self.analyzer.text)
                if edit is not None:
                    unsafe = (
                        " (unsafe: changes the physics)" if fix.applicability == "unsafe" else ""
                    )
                    found.append(
                        T.CodeAction(
                            f"Fix {finding.code}: {fix.description}{unsafe}",
                            kind=T.CodeActionKind.QuickFix,
                            diagnostics=[diagnostic],
                            edit=edit,
                            is_preferred=fix.applicability == "safe",
                        )
                    )
            found.append(
                T.CodeAction(
                    f"Suppress {finding.code} ({finding.name}) with a comment",
                    kind=T.CodeActionKind.QuickFix,
                    diagnostics=[diagnostic],
                    edit=convert.suppression(lines, params.text_document.uri, finding),
                )
            )
        return found

    def hover(self, params: T.HoverParams) -> T.Hover | None:
        path = convert.path_of(params.text_document.uri)
        text = self.analyzer.text(path) if path else None
        if path is None or text is None:
            return None
        path = os.path.abspath(path)
        lines = convert.lines_of(text)
        found = describe.tag_at(text, lines, params.position)
        if found is None:
            return None
        tag, start, end = found
        here = [f for f in self.analyzer.findings_for(path) if start <= (f.line, f.column) <= end]
        covering = self.analyzer.document_for(path)
        doc = covering[0] if covering else None
        element = describe.element_at(doc, path, *start)
        value = describe.hover(doc, here, element, tag)
        if value is None:
            return None
        return T.Hover(T.MarkupContent(T.MarkupKind.Markdown, value))

    def outline(self, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
        path = convert.path_of(params.text_document.uri)
        if path is None:
            return []
        path = os.path.abspath(path)
        covering = self.analyzer.document_for(path)
        lines = convert.lines_of(self.analyzer.text(path) or "")
        return describe.symbols(covering[0] if covering else None, path, lines)


def initialized(ls: UrdflintServer, params: T.InitializedParams) -> None:
    found = (convert.path_of(f.uri) for f in ls.workspace.folders.values())
    roots = [Path(p) for p in found if p]
    if not roots and ls.workspace.root_path:
        roots = [Path(ls.workspace.root_path)]
    ls.analyzer = Analyzer(roots)


def did_open(ls: UrdflintServer, params: T.DidOpenTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        ls.analyzer.open(path, params.text_document.text)
        ls.schedule(os.path.abspath(path), 0)


def did_change(ls: UrdflintServer, params: T.DidChangeTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        text = ls.workspace.get_text_document(params.text_document.uri).source
        ls.analyzer.open(path, text)
        ls.schedule(os.path.abspath(path), DEBOUNCE)


def did_save(ls: UrdflintServer, params: T.DidSaveTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and os.path.basename(path) in config.FILENAMES:
        ls.analyzer.configuration_changed()  # the rules to run may have changed
        for open_path in list(ls.analyzer.buffers):
            ls.schedule(open_path, 0)
    elif path and wanted(path):
        ls.schedule(os.path.abspath(path), 0)


def did_close(ls: UrdflintServer, params: T.DidCloseTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        path = os.path.abspath(path)
        ls.analyzer.close(path)
        if not ls.analyzer.reached(path):
            ls.analyzer.forget(path)
            ls.publish(path)  # clears what it showed


def code_action(ls: UrdflintServer, params: T.CodeActionParams) -> list[T.CodeAction]:
    return ls.actions(params)


def hover(ls: UrdflintServer, params: T.HoverParams) -> T.Hover | None:
    return ls.hover(params)


def document_symbol(ls: UrdflintServer, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
    return ls.outline(params)


HANDLERS: list[tuple[str, Any, Any]] = [
    (T.INITIALIZED, initialized, None),
    (T.TEXT_DOCUMENT_DID_OPEN, did_open, None),
    (T.TEXT_DOCUMENT_DID_CHANGE, did_change, None),
    (T.TEXT_DOCUMENT_DID_SAVE, did_save, None),
    (T.TEXT_DOCUMENT_DID_CLOSE, did_close, None),
    (
        T.TEXT_DOCUMENT_CODE_ACTION,
        code_action,
        T.CodeActionOptions(code_action_kinds=[T.CodeActionKind.QuickFix]),
    ),
    (T.TEXT_DOCUMENT_HOVER, hover, None),
    (T.TEXT_DOCUMENT_DOCUMENT_SYMBOL, document_symbol, None),
]


def build() -> UrdflintServer:
    server = UrdflintServer()
    for method, handler, options in HANDLERS:
        server.feature(method, options)(handler)
    return server


def main() -> int:
    build().start_io()
    return 0
