#!/usr/bin/env python3
"""``urdflint lsp`` on a real package workspace: a macro file included by several robots.

    .venv/bin/python bench/lsp_packages.py [--workspace DIR] [--file FILE] [--edits 10]
        [--bursts 3] [--xacro-arg NAME:=VALUE ...]

Starts ``python -m urdflint lsp`` over stdio as an editor does (pygls client), with the
workspace folder as the LSP root, opens FILE (default: PR2's
``pr2_description/urdf/forearm_v0/forearm.urdf.xacro``, a macro file that the three robots in
``pr2_description/robots/`` include) and measures, in that file:

* **cold**: from ``didOpen`` to the first ``publishDiagnostics`` for the file, and to the
  last one (the server quiet for ``--quiet`` seconds: every entry analysed);
* **edit**: the first ``<mass value="..."/>`` in the file is changed to ``-1.5`` (a planted
  defect), then back: from each change to the first publish for the file that reflects it
  (an I002 "has mass -1.5 kg" on that line, then none), median and worst over ``--edits``
  changes, and to the last publish (every entry redone). The server is left idle between
  changes;
* **burst**: five changes 150 ms apart, typing ``-1.5`` into that mass value (``""``, ``-``,
  ``-1``, ``-1.``, ``-1.5``): from the last change to the first publish that reflects the
  last text (its I002, and nothing on that line that the last text does not give: the
  settled publish tells what it gives), the number of publishes, and whether a *stale* set
  was published after a newer one (after that first publish, one with a diagnostic on that
  line from an older text, or a ``version`` lower than an earlier one's).

Files are read from a temporary copy of the workspace when ``--xacro-arg`` is given (it
writes an ``urdflint.toml`` with them), e.g. UR's macro file, whose entries need arguments::

    .venv/bin/python bench/lsp_packages.py \\
        --workspace /work/realpkgs/UniversalRobots+Universal_Robots_ROS2_Description \\
        --file urdf/ur_macro.xacro --xacro-arg name:=ur --xacro-arg ur_type:=ur5e

No figure is asserted: it prints a table.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import itertools
import re
import shutil
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

PR2 = Path("/work/realpkgs/PR2+pr2_common")
FOREARM = "pr2_description/urdf/forearm_v0/forearm.urdf.xacro"
MASS = re.compile(r'(<mass\s+value=")([^"]*)(")')
PLANTED = "-1.5"
BURST = ("", "-", "-1", "-1.", "-1.5")


@dataclass
class Publish:
    at: float
    version: int | None
    mass_messages: list[str]  # messages of the diagnostics on the mass line


@dataclass
class Watch:
    uri: str
    line: int  # 0-based line of the planted mass
    seen: list[Publish] = field(default_factory=list)
    event: asyncio.Event = field(default_factory=asyncio.Event)


def planted(p: Publish) -> bool:
    return any(f"mass {PLANTED} kg" in m for m in p.mass_messages)


async def wait_for(watch: Watch, since: int, test, timeout: float = 120) -> Publish:
    """The first publish at index >= ``since`` that passes ``test``."""
    deadline = time.perf_counter() + timeout
    index = since
    while True:
        while index < len(watch.seen):
            if test(watch.seen[index]):
                return watch.seen[index]
            index += 1
        watch.event.clear()
        left = deadline - time.perf_counter()
        if left <= 0:
            raise TimeoutError("no such publish")
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(watch.event.wait(), left)


async def quiet(last: list[float], seconds: float) -> float:
    """Wait until no publish (any file) arrived for ``seconds``; the time of the last one."""
    while True:
        since = time.perf_counter() - last[0]
        if since >= seconds:
            return last[0]
        await asyncio.sleep(seconds - since)


async def run(args: argparse.Namespace, workspace: Path, path: Path) -> dict[str, object]:
    from lsprotocol import types as T
    from pygls.lsp.client import LanguageClient

    text = path.read_text()
    found = MASS.search(text)
    if found is None:
        raise SystemExit(f"{path}: no <mass value=...> to plant a defect in")
    line = text.count("\n", 0, found.start())
    uri = path.as_uri()
    watch = Watch(uri, line)
    last = [time.perf_counter()]

    client = LanguageClient("bench", "1")

    @client.feature(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def diagnostics(ls: LanguageClient, params: T.PublishDiagnosticsParams) -> None:
        now = time.perf_counter()
        last[0] = now
        if params.uri == uri:
            messages = [d.message for d in params.diagnostics if d.range.start.line == line]
            watch.seen.append(Publish(now, params.version, messages))
            watch.event.set()

    def with_value(value: str) -> str:
        return text[: found.start(2)] + value + text[found.end(2) :]

    version = [1]

    def change(new: str) -> float:
        version[0] += 1
        start = time.perf_counter()
        client.text_document_did_change(
            T.DidChangeTextDocumentParams(
                T.VersionedTextDocumentIdentifier(version[0], uri),
                [T.TextDocumentContentChangeWholeDocument(new)],
            )
        )
        return start

    await client.start_io(sys.executable, "-m", "urdflint", "lsp", *_cache_args(args))
    await client.initialize_async(
        T.InitializeParams(
            T.ClientCapabilities(),
            root_uri=workspace.as_uri(),
            workspace_folders=[T.WorkspaceFolder(workspace.as_uri(), workspace.name)],
        )
    )
    client.initialized(T.InitializedParams())
    out: dict[str, object] = {}

    # (c) cold
    start = time.perf_counter()
    client.text_document_did_open(
        T.DidOpenTextDocumentParams(T.TextDocumentItem(uri, "xml", 1, text))
    )
    first = await wait_for(watch, 0, lambda p: True)
    out["cold_first"] = first.at - start
    out["cold_all"] = await quiet(last, args.quiet) - start

    # (a) edits: plant, revert, ...
    firsts: list[float] = []
    alls: list[float] = []
    for i in range(args.edits):
        plant = i % 2 == 0
        since = len(watch.seen)
        start = change(with_value(PLANTED) if plant else text)
        got = await wait_for(watch, since, planted if plant else (lambda p: not planted(p)))
        firsts.append(got.at - start)
        alls.append(await quiet(last, args.quiet) - start)
    if args.edits % 2:
        change(text)
        await quiet(last, args.quiet)
    out["edit_first"] = firsts
    out["edit_all"] = alls

    # (b) bursts
    bursts = []
    for _ in range(args.bursts):
        since = len(watch.seen)
        for value in BURST:
            start = change(with_value(value))
            if value != BURST[-1]:
                await asyncio.sleep(args.gap)
        final = version[0]
        await wait_for(watch, since, planted)
        done = await quiet(last, args.quiet)
        seen = watch.seen[since:]
        # the last publish, every entry redone from the last text, is the truth for it: a
        # publish reflects the last text when it shows the planted I002 and nothing on that
        # line that the last text does not give (what "", "-", "-1", "-1." gave)
        truth = set(seen[-1].mass_messages)

        def current(p: Publish, truth: set[str] = truth) -> bool:
            return planted(p) and set(p.mass_messages) <= truth

        first = next(i for i, p in enumerate(seen) if current(p))
        stale = any(not set(p.mass_messages) <= truth for p in seen[first:])
        versions = [p.version for p in seen if p.version is not None]
        if any(b < a for a, b in itertools.pairwise(versions)):
            stale = True
        if versions and versions[-1] != final:
            stale = True
        got = seen[first]
        bursts.append(
            {"last": got.at - start, "busy": done - start, "publishes": len(seen), "stale": stale}
        )
        change(text)
        await quiet(last, args.quiet)
    out["bursts"] = bursts

    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return out


def _cache_args(args: argparse.Namespace) -> list[str]:
    return ["--no-cache"] if args.no_cache else ["--cache-dir", str(args.cache_dir)]


async def warm_open(args: argparse.Namespace, workspace: Path, path: Path) -> tuple[float, float]:
    """A new server (an editor started again) opens the file with the cache the first
    session left: open -> first diagnostics, and -> the server quiet."""
    from lsprotocol import types as T
    from pygls.lsp.client import LanguageClient

    client = LanguageClient("bench", "1")
    uri = path.as_uri()
    got: list[float] = []
    last = [time.perf_counter()]

    @client.feature(T.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def diagnostics(ls: LanguageClient, params: T.PublishDiagnosticsParams) -> None:
        last[0] = time.perf_counter()
        if params.uri == uri:
            got.append(last[0])

    await client.start_io(sys.executable, "-m", "urdflint", "lsp", *_cache_args(args))
    await client.initialize_async(
        T.InitializeParams(
            T.ClientCapabilities(),
            root_uri=workspace.as_uri(),
            workspace_folders=[T.WorkspaceFolder(workspace.as_uri(), workspace.name)],
        )
    )
    client.initialized(T.InitializedParams())
    start = time.perf_counter()
    client.text_document_did_open(
        T.DidOpenTextDocumentParams(T.TextDocumentItem(uri, "xml", 1, path.read_text()))
    )
    while not got and time.perf_counter() - start < 120:
        await asyncio.sleep(0.005)
    done = await quiet(last, args.quiet)
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return got[0] - start, done - start


def ms(seconds: float) -> str:
    return f"{seconds * 1e3:.0f} ms"


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--workspace", type=Path, default=PR2)
    parser.add_argument("--file", default=FOREARM, help="relative to the workspace, or absolute")
    parser.add_argument("--edits", type=int, default=10)
    parser.add_argument("--bursts", type=int, default=3)
    parser.add_argument("--gap", type=float, default=0.15, help="s between a burst's changes")
    parser.add_argument("--quiet", type=float, default=2.0, help="s without a publish: idle")
    parser.add_argument("--xacro-arg", action="append", default=[], metavar="NAME:=VALUE")
    parser.add_argument(
        "--cache-dir", type=Path, help="the server's analysis cache (default: a new empty one)"
    )
    parser.add_argument("--no-cache", action="store_true", help="run the server without one")
    args = parser.parse_args()

    workspace = args.workspace.resolve()
    path = Path(args.file)
    path = (path if path.is_absolute() else workspace / path).resolve()
    with tempfile.TemporaryDirectory() as tmp:
        if args.cache_dir is None:
            args.cache_dir = Path(tmp) / "cache"
        if args.xacro_arg:
            copy = Path(tmp) / workspace.name
            shutil.copytree(workspace, copy, symlinks=True)
            lines = ["[xacro-args]"]
            for arg in args.xacro_arg:
                name, _, value = arg.partition(":=")
                lines.append(f'{name} = "{value}"')
            (copy / "urdflint.toml").write_text("\n".join(lines) + "\n")
            path = copy / path.relative_to(workspace)
            workspace = copy
        out = asyncio.run(run(args, workspace, path))
        out["warm"] = asyncio.run(warm_open(args, workspace, path))

    firsts, alls = out["edit_first"], out["edit_all"]
    bursts = out["bursts"]
    assert isinstance(firsts, list) and isinstance(alls, list) and isinstance(bursts, list)
    print(f"{path.relative_to(workspace)} in {workspace.name}")
    print("| measure | median | worst |")
    print("|---|---|---|")
    print(f"| cold: open -> first diagnostics | {ms(out['cold_first'])} | |")  # type: ignore[arg-type]
    print(f"| cold: open -> every entry done | {ms(out['cold_all'])} | |")  # type: ignore[arg-type]
    warm_first, warm_all = out["warm"]  # type: ignore[misc]
    print(f"| warm cache, new server: open -> first diagnostics | {ms(warm_first)} | |")
    print(f"| warm cache, new server: open -> server quiet | {ms(warm_all)} | |")
    print(
        f"| edit -> first diagnostics reflecting it ({len(firsts)} edits) "
        f"| {ms(statistics.median(firsts))} | {ms(max(firsts))} |"
    )
    print(
        f"| edit -> every entry done (server quiet) "
        f"| {ms(statistics.median(alls))} | {ms(max(alls))} |"
    )
    lasts = [b["last"] for b in bursts]
    busy = [b["busy"] for b in bursts]
    print(
        f"| burst of 5 ({len(bursts)}x): last change -> its diagnostics "
        f"| {ms(statistics.median(lasts))} | {ms(max(lasts))} |"
    )
    print(
        f"| burst: last change -> every entry done "
        f"| {ms(statistics.median(busy))} | {ms(max(busy))} |"
    )
    print("edit -> first diagnostics, each (ms):", " ".join(f"{t * 1e3:.0f}" for t in firsts))
    publishes = [b["publishes"] for b in bursts]
    stale = sum(1 for b in bursts if b["stale"])
    print(f"publishes per burst for the file: {publishes}; bursts with a stale publish: {stale}")
    print(f"(quiet window {args.quiet:g} s: 'every entry done' includes no part of it)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
