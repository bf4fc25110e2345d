#!/usr/bin/env python3
"""A value typed into a macro file: the xacro patch against a full expansion of the entry.

    .venv/bin/python bench/bench_xacro_patch.py [--repeat 5] [ENTRY MACRO [WORKSPACE]]

Default: PR2 (/work/realpkgs/PR2+pr2_common, entry robots/pr2.urdf.xacro, macro
urdf/forearm_v0/forearm.urdf.xacro). Packages for ``$(find)`` are those found below the
workspace (``urdflint.sources.workspace.Packages``). The edit negates the first literal
``<mass value>`` of the macro file, as the language server receives it (the edited buffer in
the context's overlay). Best of --repeat, each:

  full     the entry expanded by xacro with the edited buffer, as a Document
  patch    ``patch.apply`` on the previous document (its source map already built, as after
           a lint) -> the new Document
  +map     the same, then one origin asked (pairs the carried marks with the new tree, as
           the first finding of a lint does)
  +all     the same, then the origin of every element (the most a lint can ask)
  lint     ``lint_document`` of the patched document, for scale
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from urdflint.engine import linter  # noqa: E402
from urdflint.engine.config import Settings  # noqa: E402
from urdflint.engine.context import Context  # noqa: E402
from urdflint.sources import xacro as xacro_input  # noqa: E402
from urdflint.sources.workspace import Packages  # noqa: E402
from urdflint.sources.xacro import patch  # noqa: E402

PR2 = Path("/work/realpkgs/PR2+pr2_common")


def best(function: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = function()
        times.append(time.perf_counter() - start)
    return min(times), out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("files", nargs="*", help="ENTRY MACRO [WORKSPACE]")
    args = parser.parse_args()
    if args.files:
        entry, macro = Path(args.files[0]).resolve(), Path(args.files[1]).resolve()
        workspace = Path(args.files[2]) if len(args.files) > 2 else entry.parent
    else:
        package = PR2 / "pr2_description"
        entry = package / "robots/pr2.urdf.xacro"
        macro = package / "urdf/forearm_v0/forearm.urdf.xacro"
        workspace = PR2
    settings = Settings()
    context = Context(workspace=Packages([workspace]))
    old = macro.read_bytes()
    at = old.index(b'<mass value="') + len(b'<mass value="')
    new = old[:at] + (old[at + 1 :] if old[at : at + 1] == b"-" else b"-" + old[at:])
    edited = dataclasses.replace(context, overlay={str(macro): new})

    previous = xacro_input.document(entry, str(entry), settings, context)
    assert previous.ok and previous.origin is not None
    previous.origin(previous.robot)  # the map is built, as after the lint of the previous text

    full, expanded = best(
        lambda: xacro_input.document(entry, str(entry), settings, edited), args.repeat
    )
    patched_time, patched = best(
        lambda: patch.apply(previous, str(macro), old, new, edited), args.repeat
    )
    assert patched is not None, "the edit was not patched"
    assert patched.source == expanded.source

    def mapped(every: bool) -> None:
        doc = patch.apply(previous, str(macro), old, new, edited)
        assert doc is not None and doc.origin is not None
        for el in doc.robot.iter() if every else [doc.robot]:
            doc.origin(el)

    mapped_time, _ = best(lambda: mapped(False), args.repeat)
    every_time, _ = best(lambda: mapped(True), args.repeat)
    lint_time, _ = best(lambda: linter.lint_document(patched, settings), args.repeat)
    copies = sum(
        a.get("value") != b.get("value")
        for a, b in zip(previous.robot.iter("mass"), patched.robot.iter("mass"), strict=True)
    )
    print(f"entry {entry}\nedit  {macro}: <mass value> negated ({len(new) - len(old):+d} byte)")
    print(f"expanded {len(expanded.source)} bytes; {copies} copies patched, same text as full")
    print(f"full     {full * 1000:8.1f} ms")
    print(f"patch    {patched_time * 1000:8.1f} ms  ({full / patched_time:.0f}x faster)")
    print(f"+map     {mapped_time * 1000:8.1f} ms  (patch, then the first origin: marks paired)")
    print(f"+all     {every_time * 1000:8.1f} ms  (patch, then the origin of every element)")
    print(f"lint     {lint_time * 1000:8.1f} ms")


if __name__ == "__main__":
    main()
