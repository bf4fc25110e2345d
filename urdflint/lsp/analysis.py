"""What the language server knows about the files: open buffers, analyses, findings per file.

An *analysis* lints one entry file (a URDF, or a xacro file that expands to a robot) from the
editor's unsaved buffers (every file xacro reads comes from an open buffer when there is one).
Its findings land in the files where the defects are written, so one analysis can put
diagnostics in several files, and a file's diagnostics are the union of the analyses that
reach it. A xacro macro file that is not a robot by itself is analysed through the entry files
of its package that include it.

Every buffer change takes a new *stamp*; an analysis remembers the stamp of each file it read.
It is *current* while none of them changed since, and a file shows only the findings of the
analyses that read its current text (*fresh* for it): the line numbers of a finding belong to
the text it was computed from, and the edit may have fixed (or moved) what an older analysis
found there. The findings of an analysis in the files that did not change stay shown until it
is redone.
"""

from __future__ import annotations

import argparse
import itertools
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.engine.options import SettingsFinder
from urdflint.model.finding import Finding

SUFFIXES = (".urdf", ".xacro")
MAX_SCAN = 4000  # files looked at when searching a package for a macro file's entries
MAX_ENTRIES = 4  # entry files analysed for one macro file


def wanted(path: str) -> bool:
    return path.lower().endswith(SUFFIXES)


@dataclass
class Analysis:
    """The last lint of one entry file."""

    entry: str
    findings: dict[str, list[Finding]] = field(default_factory=dict)  # file -> its findings
    files: frozenset[str] = frozenset()  # every file the lint read (entry and includes)
    document: Any = None
    library: bool = False  # the entry is a macro file, not a robot
    seen: dict[str, int] = field(default_factory=dict)  # file read -> its stamp then
    read: dict[str, bytes] = field(default_factory=dict)  # buffer read -> its bytes then
    epoch: int = 0  # the configuration it was linted with
    gone: bool = False  # the entry could not be read
    replayed: bool = False  # from the analysis cache: findings only, no document yet


@dataclass(frozen=True)
class Snapshot:
    """The buffers at one moment: their bytes (for the lint) and their stamps."""

    overlay: dict[str, bytes]
    stamps: dict[str, int]
    epoch: int


class Analyzer:
    """Open buffers, settings per folder, and the analyses that reach each file."""

    def __init__(self, roots: Iterable[Path] = (), cache: Any = None) -> None:
        from urdflint.sources import workspace

        self.cache = cache  # the analysis cache (urdflint.cache.Cache), or None
        self.roots = [r.resolve() for r in roots] or [Path.cwd()]
        self.buffers: dict[str, str] = {}
        self.stamps: dict[str, int] = {}  # file -> stamp of its last change (absent: 0)
        self.epoch = 0  # configuration changes
        self._clock = itertools.count(1)
        self.analyses: dict[str, Analysis] = {}
        self.workspace = workspace.Packages(self.roots, cache)
        self.finder = self._finder()

    @staticmethod
    def _finder() -> SettingsFinder:
        args = argparse.Namespace(command="lsp", q=[], isolated=False, config=None)
        return SettingsFinder(args)

    def configuration_changed(self) -> None:
        self.finder = self._finder()
        self.epoch += 1

    # -- buffers ------------------------------------------------------------------------

    def open(self, path: str, text: str) -> bool:
        """Take ``text`` as ``path``'s buffer; whether the file's text changed (new stamp)."""
        full = os.path.abspath(path)
        changed = text != self.text(full)
        self.buffers[full] = text
        if changed:
            self.stamps[full] = next(self._clock)
        return changed

    def close(self, path: str) -> bool:
        """Drop ``path``'s buffer (back to the file on disk); whether its text changed."""
        full = os.path.abspath(path)
        text = self.buffers.pop(full, None)
        changed = text is not None and text != self.text(full)
        if changed:
            self.stamps[full] = next(self._clock)
        return changed

    def text(self, path: str) -> str | None:
        """A file's current text: the open buffer, else the file on disk."""
        full = os.path.abspath(path)
        if full in self.buffers:
            return self.buffers[full]
        try:
            return Path(full).read_text(encoding="utf-8", errors="replace")
        except OSError:
            return None

    def overlay(self) -> dict[str, bytes]:
        return {path: text.encode("utf-8") for path, text in list(self.buffers.items())}

    def snapshot(self) -> Snapshot:
        return Snapshot(self.overlay(), dict(self.stamps), self.epoch)

    # -- analyses -----------------------------------------------------------------------

    def analyse(self, entry: str) -> Analysis:
        """Lint ``entry`` from the buffers and remember what it found where."""
        entry = os.path.abspath(entry)
        return self.commit(self.compute(entry, self.snapshot(), None, self.analyses.get(entry)))

    def compute(
        self,
        entry: str,
        snapshot: Snapshot,
        stop: Callable[[], bool] | None = None,
        previous: Analysis | None = None,
    ) -> Analysis:
        """Lint ``entry`` from ``snapshot`` (on a worker thread: it changes nothing here).
        With ``stop``, raises :class:`linter.Superseded` before the xacro expansion and
        between rules once ``stop()`` is true. With ``previous`` (the entry's last analysis),
        an edit of one value in one file it read patches its expansion instead of running
        xacro again (:mod:`urdflint.sources.xacro.patch`)."""
        entry = os.path.abspath(entry)
        settings = self._settings(entry)
        context = Context(workspace=self.workspace, overlay=snapshot.overlay, cache=self.cache)
        if stop is not None and stop():
            raise linter.Superseded(entry)
        parts = self._cache_parts(entry, settings, context) if previous is None else None
        if parts is not None:  # a first analysis (a cold open): from the disk cache if it can
            hit, value = self.cache.replayed("lsp", parts, overlay=snapshot.overlay)
            if hit:
                known, listed, was_library = value
                return self._analysis(entry, known, set(listed), None, was_library, snapshot, True)
        recorder = _recording(self.cache if parts is not None else None)
        try:  # the open buffers come through the context (xacro includes too)
            with linter.stoppable(stop or _never), recorder as inputs:
                doc = _patched(previous, snapshot, context)
                if doc is None:
                    doc = linter.load(Path(entry), entry, settings, context)
                result = linter.lint_document(doc, settings)
        except OSError:
            return Analysis(entry, seen={entry: snapshot.stamps.get(entry, 0)}, gone=True)
        found: dict[str, list[Finding]] = {}
        for finding in result.findings:
            found.setdefault(os.path.abspath(finding.path), []).append(finding)
        doc = result.document
        files = {entry, *found}
        if doc is not None and doc.origin is not None:
            files |= {os.path.abspath(f.path) for f in getattr(doc.origin, "files", ())}
        library = bool(doc and doc.library)
        if parts is not None and inputs is not None and not result.crashed:
            self.cache.keep("lsp", parts, inputs.deps(), (found, sorted(files), library))
        return self._analysis(entry, found, files, doc, library, snapshot, False)

    def _analysis(
        self,
        entry: str,
        found: dict[str, list[Finding]],
        files: set[str],
        doc: Any,
        library: bool,
        snapshot: Snapshot,
        replayed: bool,
    ) -> Analysis:
        seen = {f: snapshot.stamps.get(f, 0) for f in files}
        read = {f: snapshot.overlay[f] for f in files if f in snapshot.overlay}
        return Analysis(
            entry, found, frozenset(files), doc, library, seen, read, snapshot.epoch,
            replayed=replayed,
        )  # fmt: skip

    def _cache_parts(self, entry: str, settings: Any, context: Context) -> Any:
        """The key of an entry's findings in the analysis cache (None: no cache)."""
        if self.cache is None:
            return None
        from urdflint.cache import keys

        return (entry, keys.settings_key(settings), keys.context_key(context))

    def commit(self, analysis: Analysis) -> Analysis:
        """Remember ``analysis`` as its entry's (an unreadable entry: forget the entry)."""
        if analysis.gone:
            self.analyses.pop(analysis.entry, None)
        else:
            self.analyses[analysis.entry] = analysis
        return analysis

    def current(self, analysis: Analysis) -> bool:
        """Whether nothing ``analysis`` read changed since (nor the configuration)."""
        return analysis.epoch == self.epoch and all(
            self.stamps.get(f, 0) == stamp for f, stamp in analysis.seen.items()
        )

    def fresh(self, analysis: Analysis, path: str) -> bool:
        """Whether ``analysis`` read ``path``'s current text."""
        return analysis.seen.get(path, 0) == self.stamps.get(path, 0)

    def _settings(self, entry: str) -> config.Settings:
        try:
            return self.finder.for_folder(Path(entry).parent)
        except config.ConfigError:
            return config.Settings()  # a broken configuration: the defaults, still linting

    def affected(self, path: str) -> list[str]:
        """The entries to analyse again when ``path`` changes: itself (if it is a robot),
        every analysed entry that read it, and for a macro file its package's entries."""
        path = os.path.abspath(path)
        entries = [e for e, a in list(self.analyses.items()) if path in a.files and e != path]
        own = self.analyses.get(path)
        if own is None or not own.library:
            entries.insert(0, path)
        elif not entries:
            entries = self.entries_of(path)
        return entries

    def entries_of(self, path: str) -> list[str]:
        """Robot files of ``path``'s package whose text names ``path``'s file (xacro includes
        name it), robots first (``*.urdf.xacro``), nearest first."""
        package = _package_root(Path(path))
        needle = os.path.basename(path)
        found: list[str] = []
        for i, candidate in enumerate(sorted(package.rglob("*.xacro"))):
            if i > MAX_SCAN:
                break
            full = str(candidate.resolve())
            if full == os.path.abspath(path) or candidate.name.endswith(".srdf.xacro"):
                continue
            text = self.text(full) or ""
            if needle in text and "<robot" in text:
                found.append(full)
        found.sort(key=lambda f: (not f.endswith(".urdf.xacro"), f.count(os.sep), f))
        return found[:MAX_ENTRIES]

    def findings_for(self, path: str) -> list[Finding]:
        """A file's diagnostics: the union of every analysis's findings there. A defect in a
        macro file that several entries expand is shown once: the finding that names the
        most instances, with the macro calls of every entry as its related locations."""
        path = os.path.abspath(path)
        found: dict[tuple[int, int, str], Finding] = {}
        for analysis in list(self.analyses.values()):
            if analysis.library and analysis.entry == path and self.reached(path):
                continue  # the macro file's own "library" note: its entries speak for it
            if not self.fresh(analysis, path):
                continue  # from an older text of the file: hidden until redone
            for finding in analysis.findings.get(path, []):
                key = (finding.line, finding.column, finding.code)
                known = found.get(key)
                found[key] = finding if known is None else _together(known, finding)
        return sorted(found.values(), key=Finding.sort_key)

    def reached(self, path: str) -> bool:
        """Whether another analysis reads ``path`` (an entry that includes it)."""
        return any(path in a.files for e, a in list(self.analyses.items()) if e != path)

    def pending(self, path: str) -> bool:
        """Whether ``path``'s diagnostics wait for a redo: every analysis that read it read an
        older text of it (publishing now would show none of its findings)."""
        path = os.path.abspath(path)
        readers = [a for a in list(self.analyses.values()) if path in a.files]
        return bool(readers) and not any(self.fresh(a, path) for a in readers)

    def forget(self, entry: str) -> None:
        self.analyses.pop(os.path.abspath(entry), None)

    def document_for(self, path: str) -> tuple[Any, str] | None:
        """The linted document that covers ``path`` (its own, else an entry's), and whether it
        is the file itself (``"self"``) or an expansion that includes it (``"entry"``)."""
        path = os.path.abspath(path)
        own = self.analyses.get(path)
        if own is not None and own.document is not None and not own.library:
            return own.document, "self"
        covering = [
            a
            for e, a in list(self.analyses.items())
            if e != path and path in a.files and a.document is not None
        ]
        covering.sort(key=lambda a: not self.fresh(a, path))  # from the current text first
        return (covering[0].document, "entry") if covering else None


def _together(known: Finding, other: Finding) -> Finding:
    """One finding for one defect seen by two entries: the message naming more instances,
    the calls of both (each entry's chain, as related locations)."""
    import dataclasses

    first = known if len(known.message) >= len(other.message) else other
    calls = tuple(dict.fromkeys((*known.trace, *other.trace)))
    return dataclasses.replace(first, trace=calls, severity=max(known.severity, other.severity))


def _never() -> bool:
    return False


def _recording(cache: Any) -> Any:
    """What the lint reads, for the cache (a do-nothing block without one)."""
    import contextlib

    if cache is None:
        return contextlib.nullcontext(None)
    from urdflint.cache import deps

    return deps.recording(cache.ignore)


def _patched(previous: Analysis | None, snapshot: Snapshot, context: Context) -> Any:
    """``previous``'s expansion patched for the one file that changed since, if it can be."""
    doc = previous.document if previous is not None else None
    if previous is None or doc is None or doc.origin is None or doc.library:
        return None
    if previous.epoch != snapshot.epoch:
        return None
    changed = [f for f, stamp in previous.seen.items() if snapshot.stamps.get(f, 0) != stamp]
    if len(changed) != 1:
        return None
    (path,) = changed
    old, new = previous.read.get(path), snapshot.overlay.get(path)
    try:
        old = old if old is not None else Path(path).read_bytes()
        new = new if new is not None else Path(path).read_bytes()
    except OSError:
        return None
    try:
        from urdflint.sources.xacro import patch
    except ImportError:  # pragma: no cover - an older tree
        return None
    return patch.apply(doc, path, old, new, context)


def _package_root(path: Path) -> Path:
    """The nearest folder above ``path`` with a ``package.xml`` (else the file's folder)."""
    for folder in path.resolve().parents:
        if (folder / "package.xml").is_file():
            return folder
    return path.resolve().parent
