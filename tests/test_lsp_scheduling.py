"""The language server's scheduling: one pending analysis per entry, a newer edit supersedes
(a running analysis stops at a rule boundary, or before its xacro expansion), a result from
older buffers is never published, entries are published one by one, the nearest first.

The server runs in this process (its publishes recorded, the lint gated with threading events
so the interleavings are exact), plus one run over stdio. Nothing here times anything."""

from __future__ import annotations

import asyncio
import itertools
import shutil
import sys
import threading
from collections.abc import AsyncIterator, Callable
from pathlib import Path
from typing import Any

import pytest
import pytest_asyncio

pytest.importorskip("pygls")

from lsprotocol import types as T

from tests.conftest import FIXTURES
from tests.test_lsp import ENTRY, MACRO
from urdflint.engine import linter
from urdflint.lsp import convert
from urdflint.lsp.analysis import Analyzer
from urdflint.lsp.server import UrdflintServer

J008 = FIXTURES / "rules" / "J008" / "bad.urdf"
BAD_AXIS, GOOD_AXIS = 'xyz="1 1 0"', 'xyz="0 0 1"'


class Recorder:
    """The server in this process: what it published, in order, and what it analysed."""

    def __init__(self, root: Path) -> None:
        self.server = UrdflintServer()
        self.server.analyzer = Analyzer([root])
        self.sent: list[T.PublishDiagnosticsParams] = []
        self.events: list[tuple[str, str]] = []  # ("compute", entry) / ("publish", path)
        self.server.text_document_publish_diagnostics = self._publish  # type: ignore[method-assign]
        compute = self.server.analyzer.compute
        self.gate: Callable[[str], None] = lambda entry: None

        def gated(entry: str, *args: Any) -> Any:
            self.events.append(("compute", entry))
            self.gate(entry)
            return compute(entry, *args)

        self.server.analyzer.compute = gated  # type: ignore[method-assign]

    def _publish(self, params: T.PublishDiagnosticsParams) -> None:
        self.sent.append(params)
        self.events.append(("publish", convert.path_of(params.uri) or ""))

    def computed(self) -> list[str]:
        return [what for kind, what in self.events if kind == "compute"]

    def published(self, path: Path) -> list[T.PublishDiagnosticsParams]:
        return [p for p in self.sent if p.uri == path.as_uri()]

    async def idle(self) -> None:
        async def wait() -> None:
            while self.server.queue or self.server.running is not None:
                await asyncio.sleep(0.005)

        await asyncio.wait_for(wait(), 60)


class Gate:
    """Holds the first analysis (of ``entry``) that passes until released."""

    def __init__(self) -> None:
        self.started = threading.Event()
        self.release = threading.Event()
        self.armed = True

    def __call__(self, entry: str) -> None:
        if self.armed:
            self.armed = False
            self.started.set()
            assert self.release.wait(30)

    async def entered(self) -> None:
        assert await asyncio.to_thread(self.started.wait, 30)


@pytest_asyncio.fixture
async def rec(tmp_path: Path) -> AsyncIterator[Recorder]:
    recorder = Recorder(tmp_path)
    yield recorder
    await recorder.idle()
    recorder.server.worker.shutdown(wait=True)


def j008_lines(params: T.PublishDiagnosticsParams) -> list[int]:
    return [d.range.start.line for d in params.diagnostics if d.code == "J008"]


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """``segment.xacro`` (a macro with a J008 axis) included by two robots."""
    root = tmp_path / "arm_description"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>arm_description</name>'
        "<version>0.1.0</version><description>arm</description>"
        '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n'
    )
    (root / "urdf" / "segment.xacro").write_text(MACRO)
    (root / "urdf" / "big.urdf.xacro").write_text(ENTRY)
    (root / "urdf" / "small.urdf.xacro").write_text(ENTRY.replace('name="arm"', 'name="small"'))
    return root


@pytest.mark.asyncio
async def test_edits_while_an_analysis_runs_supersede_it(rec: Recorder, tmp_path: Path):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    text = path.read_text()
    rec.server.opened(str(path), text, 1)
    await rec.idle()
    assert [p.version for p in rec.published(path)] == [1]
    assert j008_lines(rec.sent[-1]) == [6, 19, 32]

    gate = Gate()
    rec.gate = gate
    rec.sent.clear()
    rec.events.clear()
    rec.server.changed(str(path), text + "<!-- 2 -->\n", 2)
    await gate.entered()  # version 2 is being analysed
    fixed = text.replace(BAD_AXIS, 'xyz="1 0 0"', 1)
    for version in range(3, 8):  # quick typing: each edit supersedes the last
        rec.server.changed(str(path), fixed + f"<!-- {version} -->\n", version)
        await asyncio.sleep(0)
    assert list(rec.server.queue) == [str(path)]  # one pending analysis, not five
    gate.release.set()
    await rec.idle()
    # version 2 stopped before its lint; one more analysis, of the last text
    assert rec.computed() == [str(path), str(path)]
    assert [p.version for p in rec.published(path)] == [7]
    assert j008_lines(rec.sent[-1]) == [19, 32]


@pytest.mark.asyncio
async def test_a_running_lint_stops_at_the_next_rule_boundary(
    rec: Recorder, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
):
    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    text = path.read_text()
    started, release = threading.Event(), threading.Event()
    rules: dict[int, list[str]] = {}  # document -> the rules run on it
    docs: list[Any] = []  # kept alive: an id is not reused by the next document
    run = linter._run

    def slow_rule(rule: Any, doc: Any, settings: Any) -> Any:
        if not any(d is doc for d in docs):
            docs.append(doc)
        ran = rules.setdefault(id(doc), [])
        ran.append(rule.code)
        if len(rules) == 1 and len(ran) == 1:
            started.set()  # inside the first rule of the first run
            assert release.wait(30)
        return run(rule, doc, settings)

    monkeypatch.setattr(linter, "_run", slow_rule)
    rec.server.opened(str(path), text, 1)
    assert await asyncio.to_thread(started.wait, 30)
    rec.server.changed(str(path), text.replace(BAD_AXIS, 'xyz="1 0 0"', 1), 2)
    assert rec.server.running is not None and rec.server.running.stopped
    release.set()
    await rec.idle()
    first, second = rules.values()
    assert len(first) == 1  # the rule running when the edit came finished; no other ran
    assert len(second) > 50
    assert [p.version for p in rec.published(path)] == [2]  # nothing from version 1
    assert j008_lines(rec.sent[-1]) == [19, 32]


@pytest.mark.asyncio
async def test_a_result_from_buffers_changed_meanwhile_is_dropped(
    rec: Recorder, package: Path, monkeypatch: pytest.MonkeyPatch
):
    entry, macro = package / "urdf" / "big.urdf.xacro", package / "urdf" / "segment.xacro"
    gate = Gate()
    rec.gate = gate
    rec.server.opened(str(entry), ENTRY, 1)
    await gate.entered()
    # the macro file is opened with an edit while the entry (which reads it) is analysed:
    # nothing knew the entry reads it, so the running analysis is not stopped, but its
    # result (from the macro file on disk) is stale
    rec.server.opened(str(macro), MACRO.replace(BAD_AXIS, GOOD_AXIS), 1)
    assert rec.server.running is not None and not rec.server.running.stopped
    gate.release.set()
    await rec.idle()
    assert rec.computed().count(str(entry)) == 2  # redone with the edited macro file
    shown = rec.published(macro)
    assert shown and all(j008_lines(p) == [] for p in shown)
    assert all(p.version == 1 for p in shown)


@pytest.mark.asyncio
async def test_a_macro_file_is_published_after_each_entry_the_quickest_first(
    rec: Recorder, package: Path
):
    urdf = package / "urdf"
    macro, big, small = urdf / "segment.xacro", urdf / "big.urdf.xacro", urdf / "small.urdf.xacro"
    rec.server.opened(str(macro), MACRO, 1)
    await rec.idle()
    assert {str(big), str(small)} <= set(rec.computed())
    assert j008_lines(rec.published(macro)[-1]) == [12]

    rec.server.cost = {str(big): 10.0, str(small): 0.1}  # as if measured
    rec.events.clear()
    rec.server.changed(str(macro), MACRO.replace(BAD_AXIS, GOOD_AXIS), 2)
    await rec.idle()
    publishes = [(k, w) for k, w in rec.events if k == "compute" or w == str(macro)]
    assert publishes == [
        ("compute", str(small)),
        ("publish", str(macro)),  # small's view, before big is done...
        ("compute", str(big)),
        ("publish", str(macro)),
    ]
    first, second = rec.published(macro)[-2:]
    # ...without big's J008 there from the old text: the edit fixed it
    assert (first.version, j008_lines(first)) == (2, [])
    assert (second.version, j008_lines(second)) == (2, [])

    rec.events.clear()
    rec.server.changed(str(macro), MACRO, 3)  # the defect back: shown after the first entry
    await rec.idle()
    first, second = rec.published(macro)[-2:]
    assert (first.version, j008_lines(first)) == (3, [12])
    assert (second.version, j008_lines(second)) == (3, [12])


@pytest.mark.asyncio
async def test_a_macro_file_edited_while_an_entry_is_analysed(rec: Recorder, package: Path):
    urdf = package / "urdf"
    macro, big, small = urdf / "segment.xacro", urdf / "big.urdf.xacro", urdf / "small.urdf.xacro"
    rec.server.opened(str(macro), MACRO, 1)
    await rec.idle()
    rec.server.cost = {str(big): 10.0, str(small): 0.1}
    gate = Gate()
    rec.gate = gate
    rec.events.clear()
    rec.server.changed(str(macro), MACRO.replace(BAD_AXIS, GOOD_AXIS), 2)
    await gate.entered()  # small, version 2
    rec.server.changed(str(macro), MACRO.replace(BAD_AXIS, 'xyz="1 0 0"'), 3)
    assert list(rec.server.queue) == [str(small), str(big)]  # each once
    gate.release.set()
    await rec.idle()
    assert rec.computed() == [str(small), str(small), str(big)]
    assert [p.version for p in rec.published(macro)[-2:]] == [3, 3]
    versions = [p.version or 0 for p in rec.published(macro)]
    assert versions == sorted(versions)


@pytest.mark.asyncio
async def test_opening_a_file_an_entry_read_publishes_without_linting_the_entry(
    rec: Recorder, package: Path
):
    urdf = package / "urdf"
    entry, macro = urdf / "big.urdf.xacro", urdf / "segment.xacro"
    rec.server.opened(str(entry), ENTRY, 1)
    await rec.idle()
    rec.events.clear()
    rec.server.opened(str(macro), MACRO, 1)  # the text on disk, which the entry read
    await rec.idle()
    assert str(entry) not in rec.computed()  # (the file itself may be a robot: linted)
    assert j008_lines(rec.published(macro)[-1]) == [12]


@pytest.mark.asyncio
async def test_over_stdio_a_burst_publishes_only_the_last_version_last(tmp_path: Path):
    from pygls.lsp.client import LanguageClient

    path = tmp_path / "arm.urdf"
    shutil.copy(J008, path)
    text, uri = path.read_text(), path.as_uri()
    client = LanguageClient("test", "1")
    seen: list[T.PublishDiagnosticsParams] = []
    arrived = asyncio.Event()

    @client.feature(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def diagnostics(ls: LanguageClient, params: T.PublishDiagnosticsParams) -> None:
        if params.uri == uri:
            seen.append(params)
            arrived.set()

    async def until(test: Callable[[], bool]) -> None:
        while not test():
            arrived.clear()
            await asyncio.wait_for(arrived.wait(), 60)

    await client.start_io(sys.executable, "-m", "urdflint", "lsp")
    try:
        await client.initialize_async(
            T.InitializeParams(T.ClientCapabilities(), root_uri=tmp_path.as_uri())
        )
        client.initialized(T.InitializedParams())
        client.text_document_did_open(
            T.DidOpenTextDocumentParams(T.TextDocumentItem(uri, "xml", 1, text))
        )
        await until(lambda: bool(seen))
        axes = ['xyz="1 0 0"', 'xyz="1 1 0"'] * 5
        for version, axis in zip(itertools.count(2), axes, strict=False):  # no waiting
            client.text_document_did_change(
                T.DidChangeTextDocumentParams(
                    T.VersionedTextDocumentIdentifier(version, uri),
                    [T.TextDocumentContentChangeWholeDocument(text.replace(BAD_AXIS, axis, 1))],
                )
            )
        last = 1 + len(axes)
        await until(lambda: seen[-1].version == last)
        versions = [p.version or 0 for p in seen]
        assert versions == sorted(versions)  # never an older version after a newer one
        assert j008_lines(seen[-1]) == [6, 19, 32]  # the last text: the bad axis again
        await client.shutdown_async(None)
        client.exit(None)
    finally:
        await client.stop()


@pytest.mark.asyncio
async def test_a_value_typed_in_a_macro_file_patches_the_expansion(
    rec: Recorder, package: Path, monkeypatch: pytest.MonkeyPatch
):
    urdf = package / "urdf"
    macro, big, small = urdf / "segment.xacro", urdf / "big.urdf.xacro", urdf / "small.urdf.xacro"
    rec.server.opened(str(macro), MACRO, 1)
    await rec.idle()
    loads: list[str] = []
    load = linter.load

    def counted(path: Path, *args: Any) -> Any:
        loads.append(str(path))
        return load(path, *args)

    monkeypatch.setattr(linter, "load", counted)
    rec.events.clear()
    rec.server.changed(str(macro), MACRO.replace('<mass value="0.5"/>', '<mass value="-2"/>'), 2)
    await rec.idle()
    assert sorted(rec.computed()) == sorted([str(big), str(small)])
    assert loads == []  # both expansions patched, xacro not run again
    (shown,) = [d for d in rec.published(macro)[-1].diagnostics if d.code == "I002"]
    assert "has mass -2 kg" in shown.message and shown.range.start.line == 5
