#!/usr/bin/env python3
"""Cost of the xacro source map, as ratios measured in the same run.

    .venv/bin/python bench/bench_xacro.py [--repeat 5] [WORKSPACE ...]

Default input: the entry xacro files of fixtures/xacro and fixtures/packages (when
present); give workspace folders (e.g. a colcon ``src/``) to measure other packages.
Packages for ``$(find)`` are discovered below each workspace, as ``urdflint check`` does.
For every entry file that expands, three timings (best of --repeat):

  plain   urdflint's expansion with the source map switched off (minidom's own parser,
          no clone tracking): what expansion cost before the source map;
  mapped  the same expansion with the source map, plus building the map and asking the
          origin of every element of the expanded document (what a run does at most);
  xacro   bare ``xacro.process_file`` with ``$(find)`` patched, for reference.

Prints per-file and total ratios mapped/plain (issue 9's budget: <= 1.3) and plain/xacro.
"""

from __future__ import annotations

import argparse
import sys
import time
import xml.dom.minidom
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from urdflint.engine.config import Settings  # noqa: E402
from urdflint.engine.context import Context  # noqa: E402
from urdflint.sources import discovery, workspace  # noqa: E402
from urdflint.sources import xacro as xacro_input  # noqa: E402
from urdflint.sources.xacro.sourcemap import Tracker  # noqa: E402


def best(function, repeat: int) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def mapped(path: Path, context: Context) -> None:
    doc = xacro_input.document(path, str(path), Settings(), context)
    if doc.ok and doc.origin is not None:
        for el in doc.robot.iter():
            doc.origin(el)


def plain(path: Path, context: Context) -> None:
    saved = (Tracker.calling, Tracker.cloning, Tracker.parse)
    Tracker.calling = lambda self, original: original  # type: ignore[method-assign]
    Tracker.cloning = lambda self, original: original  # type: ignore[method-assign]
    Tracker.parse = lambda self, data, p, s: xml.dom.minidom.parseString(data)  # type: ignore[method-assign]
    try:
        xacro_input.document(path, str(path), Settings(), context)
    finally:
        Tracker.calling, Tracker.cloning, Tracker.parse = saved  # type: ignore[method-assign]


def bare(path: Path, packages: dict[str, Path]) -> None:
    import xacro
    from xacro import substitution_args as sa

    def find(name: str) -> str:
        return str(packages[name])

    saved = sa._eval_dict.get("find"), sa._eval_find
    sa._eval_dict["find"], sa._eval_find = find, find
    try:
        xacro.init_stacks(None)
        xacro.all_includes = []
        xacro.substitution_args_context.clear()
        xacro.process_file(str(path)).toprettyxml(indent="  ")
    finally:
        sa._eval_dict["find"], sa._eval_find = saved


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("workspaces", nargs="*", type=Path)
    args = parser.parse_args()
    spaces = args.workspaces or [
        p for p in (ROOT / "fixtures" / "xacro", ROOT / "fixtures" / "packages") if p.is_dir()
    ]
    totals = [0.0, 0.0, 0.0]
    print(f"{'file':<70} {'plain ms':>9} {'mapped ms':>10} {'mapped/plain':>13}")
    for space in spaces:
        packages = workspace.discover([space])
        context = Context(workspace=packages, environ={})
        files, _ = discovery.collect([str(space)], packages)
        for name in (f for f in files if f.endswith(".xacro")):
            path = Path(name)
            doc = xacro_input.document(path, name, Settings(), context)
            if not doc.ok:
                continue  # needs arguments, or fails upstream: nothing to time
            t_plain = best(partial(plain, path, context), args.repeat)
            t_mapped = best(partial(mapped, path, context), args.repeat)
            try:
                t_bare = best(partial(bare, path, packages), args.repeat)
            except Exception:
                t_bare = t_plain
            totals[0] += t_plain
            totals[1] += t_mapped
            totals[2] += t_bare
            shown = str(path.relative_to(space))[-70:]
            ratio = t_mapped / t_plain
            print(f"{shown:<70} {t_plain * 1e3:9.1f} {t_mapped * 1e3:10.1f} {ratio:13.2f}")
    if totals[0]:
        print(
            f"\ntotal: plain {totals[0]:.3f} s, mapped {totals[1]:.3f} s, bare xacro "
            f"{totals[2]:.3f} s; mapped/plain {totals[1] / totals[0]:.2f}, "
            f"plain/bare xacro {totals[0] / totals[2]:.2f}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
