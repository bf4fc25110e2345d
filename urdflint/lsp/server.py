"""``urdflint lsp``: the Language Server Protocol over stdio (pygls).

Diagnostics on open, on change (debounced, from the unsaved buffer) and on save, in every file
the defects are written in, scheduled as :class:`UrdflintServer` says; code actions, hover and
the outline are in :mod:`urdflint.lsp.requests`. Linting runs on one worker thread, so the
editor's requests are answered while a robot is checked."""

from __future__ import annotations

import asyncio
import logging
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lsprotocol import types as T
from pygls.lsp.server import LanguageServer

from urdflint import __version__
from urdflint.engine import config, linter
from urdflint.lsp import convert, requests
from urdflint.lsp.analysis import Analysis, Analyzer, Snapshot, wanted

MAX_NESTING = 3  # macro files included by macro files, followed up to their robots
DEBOUNCE = 0.025  # s after the last keystroke before a buffer is linted

log = logging.getLogger(__name__)


@dataclass
class Job:
    """One analysis on the worker thread: its entry, the buffers it reads, and whether a newer
    change made its answer useless (asked between rules, see :func:`linter.stoppable`)."""

    entry: str
    snapshot: Snapshot
    nesting: int = 0  # macro files followed to get here
    origin: str | None = None  # the macro file it is analysed for (published when done)
    previous: Analysis | None = None  # the entry's last analysis (its expansion may be patched)
    stopped: bool = False


class UrdflintServer(LanguageServer):
    """The scheduling of the analyses.

    One worker thread lints one entry file at a time from a snapshot of the buffers, so
    the editor's requests are answered meanwhile. There is at most one pending analysis per
    entry: a change queues the entries it affects (:meth:`Analyzer.affected`) once each, and a
    newer change to a file they read supersedes them: a queued one keeps its single place
    (moved to the front, the nearest first), a running one stops at the next rule boundary
    (or before its xacro expansion) and is queued again. A burst of typing thus costs at most
    the analysis running when it started plus one analysis of the last text per entry, not
    one per keystroke.

    Each entry's result is published as soon as it is done, the nearest first: the edited
    file itself, then the entries that include it in the order they are likely to finish
    (the fastest last time first). A result computed from buffers that changed meanwhile is
    dropped (and its entry queued again), so every publish comes from the newest text.

    What a file shows while its entries are redone: only the findings of the analyses that
    read its *current* text (:meth:`Analyzer.findings_for`). After an edit in a macro file
    included by three robots, the first robot done publishes the file with its findings
    alone; the other two robots' findings there (computed from the old text, at old line
    numbers, maybe about what the edit fixed) are hidden until each is redone, then their
    findings join. An error the edit fixed thus disappears with the first publish instead of
    lingering until the slowest robot is redone; an error only a later robot sees there comes
    back when that robot is done. A file whose every reader is still to be redone is not
    published (the editor keeps the previous set rather than showing none). The findings
    of the older analyses in files that did not change stay until those are redone.
    """

    def __init__(self, cache: Any = None) -> None:
        super().__init__(
            "urdflint", __version__, text_document_sync_kind=T.TextDocumentSyncKind.Full
        )
        self.cache = cache  # the analysis cache (urdflint.cache.Cache), or None
        self.analyzer = Analyzer(cache=cache)
        self.worker = ThreadPoolExecutor(1, thread_name_prefix="urdflint-lint")
        # entry -> (nesting, the macro file it is analysed for), in the order of analysis
        self.queue: dict[str, tuple[int, str | None]] = {}
        self.running: Job | None = None
        self.due = 0.0  # loop time before which no analysis starts (the debounce)
        self.cost: dict[str, float] = {}  # entry -> seconds its last analysis took
        self.versions: dict[str, int] = {}  # open file -> the editor's version of its buffer
        self.shown: set[str] = set()  # files whose published diagnostics are not empty
        self._wake: asyncio.Event | None = None
        self._drainer: asyncio.Task[None] | None = None

    # -- diagnostics ----------------------------------------------------------------------

    def request(self, path: str, *, changed: bool = True, delay: float = 0.0) -> None:
        """Analyse what ``path`` affects after ``delay`` s (a newer change restarts the wait).

        ``changed``: a file's text changed, so the affected entries' analyses (queued or
        running) are superseded. Otherwise (a save, an open with the text on disk) the
        entries with a current analysis, or one queued or running, are left as they are, and
        ``path`` is published now from what is known."""
        path = os.path.abspath(path)
        entries = self.order(path, self.analyzer.affected(path))
        wanted: list[str] = []
        for entry in entries:
            running = self.running is not None and self.running.entry == entry
            if not changed:
                known = self.analyzer.analyses.get(entry)
                if entry in self.queue or running:
                    continue
                if known is not None and self.analyzer.current(known):
                    continue
            if running and self.running is not None:
                self.running.stopped = True  # stops at the next rule boundary
            wanted.append(entry)
        if not changed and len(wanted) < len(entries):
            self.publish(path)
        if not wanted:
            return
        job = self.running
        again = {job.entry: (job.nesting, job.origin)} if job is not None else {}
        rest = {e: n for e, n in self.queue.items() if e not in wanted}
        self.queue = {e: self.queue.get(e) or again.get(e, (0, None)) for e in wanted} | rest
        if delay:
            self.due = asyncio.get_running_loop().time() + delay
        self._kick()

    def order(self, path: str, entries: list[str]) -> list[str]:
        """Nearest first: ``path`` itself, then the entries that include it by the time
        their last analysis took (the likely first to finish first; never analysed: after,
        in their given order: robots first, nearest folder first)."""
        index = {e: i for i, e in enumerate(entries)}
        return sorted(entries, key=lambda e: (e != path, self.cost.get(e, float("inf")), index[e]))

    def _kick(self) -> None:
        if self._wake is None:
            self._wake = asyncio.Event()
        self._wake.set()
        if self._drainer is None or self._drainer.done():
            self._drainer = asyncio.get_running_loop().create_task(self._drain())

    async def _drain(self) -> None:
        """The queue's consumer: one analysis at a time on the worker thread."""
        loop = asyncio.get_running_loop()
        assert self._wake is not None
        while True:
            if not self.queue:
                self._wake.clear()
                await self._wake.wait()
                continue
            wait = self.due - loop.time()
            if wait > 0:
                await asyncio.sleep(wait)  # a newer change may move ``due``: look again
                continue
            entry = next(iter(self.queue))
            nesting, origin = self.queue.pop(entry)
            previous = self.analyzer.analyses.get(entry)
            job = Job(entry, self.analyzer.snapshot(), nesting, origin, previous)
            self.running = job
            start = time.perf_counter()
            try:
                analysis = await loop.run_in_executor(self.worker, self._compute, job)
            except Exception:  # a crash in one analysis must not stop the server's linting
                log.exception("analysing %s failed", entry)
                analysis = None
            finally:
                self.running = None
            if analysis is not None:
                self.cost[entry] = time.perf_counter() - start
                self._commit(job, analysis)

    def _compute(self, job: Job) -> Analysis | None:
        """On the worker thread: the analysis, or None once a newer change superseded it."""
        try:
            return self.analyzer.compute(job.entry, job.snapshot, lambda: job.stopped, job.previous)
        except linter.Superseded:
            return None

    def _commit(self, job: Job, analysis: Analysis) -> None:
        """On the event loop: keep a current result and publish the files it reaches."""
        if job.stopped:
            return  # the change that stopped it queued the entry again
        if not self.analyzer.current(analysis):
            # a file it read changed meanwhile (one no earlier analysis of the entry read,
            # or the configuration): its result is stale, redo it
            self.queue.setdefault(job.entry, (job.nesting, job.origin))
            self._kick()
            return
        before = self.analyzer.analyses.get(job.entry)
        self.analyzer.commit(analysis)
        follow: list[str] = []
        if analysis.library and job.nesting < MAX_NESTING and not self.analyzer.reached(job.entry):
            # a macro file: through the files that include it (a macro file included by
            # another macro file: through that one's, and so on)
            follow = self.order(job.entry, self.analyzer.entries_of(job.entry))
            for entry in follow:
                self.queue.setdefault(entry, (job.nesting + 1, job.origin or job.entry))
            if follow:
                self._kick()
        touched = {job.entry, *analysis.findings}
        if before is not None:
            touched |= set(before.findings)
        if follow:  # its entries will speak for it (and for the file it was analysed for)
            touched -= {job.entry, job.origin}
        elif job.origin is not None:
            touched.add(job.origin)  # (even if this entry turned out not to include it)
        for file in sorted(touched, key=lambda f: (f not in self.versions, f)):
            self.publish(file)
        if analysis.replayed:  # from the disk cache: now build its document (hover, outline,
            self.queue.setdefault(job.entry, (job.nesting, job.origin))  # patched edits)
            self._kick()

    def publish(self, path: str) -> None:
        """Publish ``path``'s diagnostics: the findings of the analyses that read its
        current text (none yet, while some read an older one: nothing is published). An
        empty set goes to a file open in the editor, or one that showed findings."""
        if self.analyzer.pending(path):
            return
        findings = self.analyzer.findings_for(path)
        if not findings and path not in self.shown and path not in self.versions:
            return
        text = self.analyzer.text(path) or ""
        lines = convert.lines_of(text)
        diagnostics = [convert.diagnostic(lines, f) for f in findings]
        (self.shown.add if diagnostics else self.shown.discard)(path)
        self.text_document_publish_diagnostics(
            T.PublishDiagnosticsParams(
                uri=convert.uri_of(path), diagnostics=diagnostics, version=self.versions.get(path)
            )
        )

    def opened(self, path: str, text: str, version: int | None) -> None:
        path = os.path.abspath(path)
        if version is not None:
            self.versions[path] = version
        self.request(path, changed=self.analyzer.open(path, text))

    def changed(self, path: str, text: str, version: int | None) -> None:
        path = os.path.abspath(path)
        if version is not None:
            self.versions[path] = version
        if self.analyzer.open(path, text):
            self.request(path, delay=DEBOUNCE)


def initialized(ls: UrdflintServer, params: T.InitializedParams) -> None:
    found = (convert.path_of(f.uri) for f in ls.workspace.folders.values())
    roots = [Path(p) for p in found if p]
    if not roots and ls.workspace.root_path:
        roots = [Path(ls.workspace.root_path)]
    ls.analyzer = Analyzer(roots, ls.cache)


def did_open(ls: UrdflintServer, params: T.DidOpenTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        ls.opened(path, params.text_document.text, params.text_document.version)


def did_change(ls: UrdflintServer, params: T.DidChangeTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        document = ls.workspace.get_text_document(params.text_document.uri)
        ls.changed(path, document.source, params.text_document.version)


def did_save(ls: UrdflintServer, params: T.DidSaveTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and os.path.basename(path) in config.FILENAMES:
        ls.analyzer.configuration_changed()  # the rules to run may have changed
        for open_path in list(ls.analyzer.buffers):
            ls.request(open_path)
    elif path and wanted(path):
        ls.request(path, changed=False)


def did_close(ls: UrdflintServer, params: T.DidCloseTextDocumentParams) -> None:
    path = convert.path_of(params.text_document.uri)
    if path and wanted(path):
        path = os.path.abspath(path)
        ls.versions.pop(path, None)
        changed = ls.analyzer.close(path)  # unsaved edits dropped: back to the file on disk
        if not ls.analyzer.reached(path):
            ls.analyzer.forget(path)
            ls.queue.pop(path, None)
            if ls.running is not None and ls.running.entry == path:
                ls.running.stopped = True
            ls.publish(path)  # clears what it showed
        elif changed:
            ls.request(path)  # the entries that include it read the file on disk now


def code_action(ls: UrdflintServer, params: T.CodeActionParams) -> list[T.CodeAction]:
    return requests.actions(ls.analyzer, params)


def hover(ls: UrdflintServer, params: T.HoverParams) -> T.Hover | None:
    return requests.hover(ls.analyzer, params)


def document_symbol(ls: UrdflintServer, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
    return requests.outline(ls.analyzer, params)


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


def build(cache: Any = None) -> UrdflintServer:
    server = UrdflintServer(cache)
    for method, handler, options in HANDLERS:
        server.feature(method, options)(handler)
    return server


def main(cache: Any = None) -> int:
    build(cache).start_io()
    return 0
