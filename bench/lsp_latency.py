#!/usr/bin/env python3
"""``urdflint lsp``: time from an edit in the editor to the new diagnostics.

    .venv/bin/python bench/lsp_latency.py [--links 100] [--edits 20] [FILE]

Starts the server over stdio as an editor does (pygls client), opens FILE (default: a
synthetic robot of ``--links`` links, as bench/scale.py builds them, every rule enabled), then
``--edits`` times changes one value in the buffer and waits for the diagnostics of that
version. Prints the median and worst time beside the same file linted in this process (the
floor the server adds its debounce and the protocol to) and the server's debounce.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))


async def measure(path: Path, edits: int) -> list[float]:
    from lsprotocol import types as T
    from pygls.lsp.client import LanguageClient

    client = LanguageClient("bench", "1")
    arrived: asyncio.Queue[float] = asyncio.Queue()

    @client.feature(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def diagnostics(ls: LanguageClient, params: T.PublishDiagnosticsParams) -> None:
        if params.uri == path.as_uri():
            arrived.put_nowait(time.perf_counter())

    await client.start_io(sys.executable, "-m", "urdflint", "lsp")
    await client.initialize_async(
        T.InitializeParams(T.ClientCapabilities(), root_uri=path.parent.as_uri())
    )
    client.initialized(T.InitializedParams())
    text = path.read_text()
    uri = path.as_uri()
    client.text_document_did_open(
        T.DidOpenTextDocumentParams(T.TextDocumentItem(uri, "xml", 1, text))
    )
    await asyncio.wait_for(arrived.get(), 120)
    times = []
    for version in range(2, edits + 2):
        # one value changes, as when someone types a digit: the mass of the first link
        edited = text.replace('<mass value="1"/>', f'<mass value="{version}"/>', 1)
        if edited == text:
            edited = text + f"<!-- {version} -->"
        start = time.perf_counter()
        client.text_document_did_change(
            T.DidChangeTextDocumentParams(
                T.VersionedTextDocumentIdentifier(version, uri),
                [T.TextDocumentContentChangeWholeDocument(edited)],
            )
        )
        times.append(await asyncio.wait_for(arrived.get(), 120) - start)
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return times


def in_process(path: Path, repeat: int) -> float:
    from urdflint.engine import config, linter, registry
    from urdflint.engine.context import Context

    registry.load_rules()
    data, settings = path.read_bytes(), config.Settings()
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        linter.lint_bytes(data, str(path), settings, Context(), path.parent)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("file", nargs="?", type=Path)
    parser.add_argument("--links", type=int, default=100)
    parser.add_argument("--edits", type=int, default=20)
    args = parser.parse_args()
    from urdflint.lsp.server import DEBOUNCE

    with tempfile.TemporaryDirectory() as tmp:
        path = args.file
        if path is None:
            from scale import model

            path = Path(tmp) / f"chain{args.links}.urdf"
            path.write_text(model(args.links, tree=False))
        times = asyncio.run(measure(path.resolve(), args.edits))
        floor = in_process(path, 5)
    median, worst = statistics.median(times), max(times)
    print(f"{path.name}: {args.edits} edits, change -> diagnostics over LSP")
    print(f"  median {median * 1e3:.0f} ms, worst {worst * 1e3:.0f} ms")
    print(f"  (debounce {DEBOUNCE * 1e3:.0f} ms; the same lint in-process {floor * 1e3:.0f} ms)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
