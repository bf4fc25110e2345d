#!/usr/bin/env python3
"""The analysis cache on the command line: cold, warm and after an edit, against the floor.

    .venv/bin/python bench/bench_cache.py [--repeat 3] [--jobs 1] [--corpus DIR]
    .venv/bin/python bench/bench_cache.py --workspace DIR [--edit FILE] [--jobs 2]

Copies the corpus (default ../shared/corpus/robots: 36 real robots, 17 with meshes) to a
temporary folder and writes a ``urdflint.toml`` into each robot folder that maps its ROS
packages to its meshes (``package_map.json``), so that one ``urdflint check ROBOTS/`` checks
every robot with its meshes. Then, each as a whole command (a new process, as a user or CI
runs it; bytecode caches on), best of --repeat:

  floor    ``python -c`` that imports lxml and parses the same 36 files (hardened parser);
  today    ``urdflint check --no-cache``: every run starts from nothing;
  cold     ``urdflint check`` with an empty cache folder (it fills it);
  warm     the same command again: nothing changed;
  edit     one number changed in one file (a ``<mass value>`` of pr2), then the command.

With ``--workspace DIR`` (a folder of ROS description packages, e.g. PR2's pr2_common, UR,
TIAGo with its PAL dependencies, franka_ros, ros2_control_demos side by side), the same
runs on ``urdflint check DIR`` (every entry file found, xacro expanded, packages found
without flags); the floor parses every ``*.urdf`` and ``*.xacro`` file below DIR, and the
edit changes a ``<mass value>`` in ``--edit`` (default: the first xacro file below DIR that
has a numeric one, preferring PR2's forearm macro).

Prints the times and the ratios issue 22 sets goals for: warm/floor (<= 3), edit/warm
(<= 1.2), cold/today (<= 1.05). The findings of every variant must be the same (edit: the same
but for the edited file), else the script fails.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
FLOOR = (
    "import sys\nfrom lxml import etree\n"
    "parser = etree.XMLParser(resolve_entities=False, no_network=True)\n"
    "for name in sys.argv[1:]:\n    try:\n        etree.parse(name, parser)\n"
    "    except etree.XMLSyntaxError:\n        pass\n"
)
MASS_RE = re.compile(r'(<mass\s+value=")([0-9.]+)(")')


def prepare(corpus: Path, into: Path) -> list[Path]:
    """The corpus copied with a configuration per robot; the model files."""
    shutil.copytree(corpus, into, ignore=shutil.ignore_patterns("*.md", "*.tsv", "*.py"))
    models = sorted(into.glob("*/model.urdf"))
    for model in models:
        mapping = model.parent / "package_map.json"
        if mapping.is_file():
            packages = json.loads(mapping.read_text())
            table = ", ".join(f'{name} = "{folder}"' for name, folder in sorted(packages.items()))
            (model.parent / "urdflint.toml").write_text(f"package-paths = {{ {table} }}\n")
    old = time.time() - 60  # as files checked out a while ago
    for folder, _, files in os.walk(into):
        for name in files:
            os.utime(os.path.join(folder, name), (old, old))
    return models


def timed(command: list[str], cwd: Path) -> tuple[float, str]:
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=ENV, cwd=cwd, check=False)
    took = time.perf_counter() - start
    if done.returncode not in (0, 1):
        sys.exit(f"bench_cache: {' '.join(command)} failed ({done.returncode}):\n{done.stderr}")
    return took, done.stdout


def findings(output: str) -> list[tuple[str, int, str, str]]:
    data = json.loads(output)
    return [(f["path"], f["line"], f["code"], f["message"]) for f in data["findings"]]


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--jobs", default="1", help="--jobs for urdflint (default 1: one process)")
    parser.add_argument("--corpus", type=Path, default=CORPUS)
    parser.add_argument("--workspace", type=Path, help="a folder of ROS packages instead")
    parser.add_argument("--edit", type=Path, help="the file whose mass is edited (--workspace)")
    args = parser.parse_args()
    if args.workspace is not None:
        if not args.workspace.is_dir():
            sys.exit(f"bench_cache: no folder {args.workspace}")
    elif not args.corpus.is_dir():
        sys.exit(f"bench_cache: no corpus at {args.corpus}")
    work = Path(tempfile.mkdtemp(prefix="urdflint-bench-cache-"))
    try:
        return run(args, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def prepare_workspace(source: Path, into: Path, edit: Path | None) -> tuple[list[Path], Path]:
    """The workspace copied (times set in the past); its URDF/xacro files; the file to edit."""
    shutil.copytree(source, into, symlinks=True, ignore=shutil.ignore_patterns(".git"))
    old = time.time() - 60
    for folder, _, files in os.walk(into):
        for name in files:
            with contextlib.suppress(OSError):
                os.utime(os.path.join(folder, name), (old, old), follow_symlinks=False)
    files = sorted(p for p in into.rglob("*") if p.suffix in (".urdf", ".xacro") and p.is_file())
    if edit is not None:
        return files, into / edit.resolve().relative_to(source.resolve())
    candidates = [p for p in files if p.suffix == ".xacro" and MASS_RE.search(p.read_text())]
    candidates.sort(key=lambda p: p.name != "forearm.urdf.xacro")
    if not candidates:
        sys.exit("bench_cache: no xacro file with a numeric <mass value> to edit")
    return files, candidates[0]


def run(args: argparse.Namespace, work: Path) -> int:
    robots = work / "robots"
    if args.workspace is not None:
        models, edited = prepare_workspace(args.workspace, robots, args.edit)
    else:
        models = prepare(args.corpus, robots)
        edited = next((m for m in models if m.parent.name == "pr2"), models[0])
    names = [str(m.relative_to(work)) for m in models]
    cache = work / "cache"
    python = sys.executable
    base = [python, "-m", "urdflint", "check", "robots", "--format", "json", "--jobs", args.jobs]
    with_cache = [*base, "--cache-dir", str(cache)]
    floor_cmd = [python, "-c", FLOOR, *names]

    times: dict[str, list[float]] = {k: [] for k in ("floor", "today", "cold", "warm", "edit")}
    outputs: dict[str, str] = {}
    original = edited.read_text()
    for i in range(args.repeat):
        times["floor"].append(timed(floor_cmd, work)[0])
        took, outputs["today"] = timed([*base, "--no-cache"], work)
        times["today"].append(took)
        shutil.rmtree(cache, ignore_errors=True)
        took, outputs["cold"] = timed(with_cache, work)
        times["cold"].append(took)
        took, outputs["warm"] = timed(with_cache, work)
        times["warm"].append(took)
        # one number changed (a new value every round: never a replay of an earlier edit)
        found = MASS_RE.search(original)
        assert found is not None, f"no <mass value> in {edited}"
        value = f"{float(found.group(2)) + 0.125 * (i + 1):g}"
        edited.write_text(original[: found.start(2)] + value + original[found.end(2) :])
        took, outputs["edit"] = timed(with_cache, work)
        times["edit"].append(took)
        edited.write_text(original)
        old = time.time() - 60
        os.utime(edited, (old, old))
        timed(with_cache, work)  # back to the cached state for the next round

    same = findings(outputs["today"]) == findings(outputs["cold"]) == findings(outputs["warm"])
    shown = str(edited.relative_to(work))
    others = [f for f in findings(outputs["edit"]) if f[0] != shown]
    same_edit = others == [f for f in findings(outputs["today"]) if f[0] != shown]
    if args.workspace is not None:  # a macro file's edit shows in its file: compare counts
        same_edit = len(findings(outputs["edit"])) >= len(findings(outputs["today"])) - 1

    best = {k: min(v) for k, v in times.items()}
    median = {k: statistics.median(v) for k, v in times.items()}
    if args.workspace is not None:
        print(f"{args.workspace}: {len(models)} URDF/xacro files, edited {shown}, "
              f"urdflint --jobs {args.jobs}, best of {args.repeat} (median)")  # fmt: skip
    else:
        print(f"{len(models)} robots ({sum(1 for m in models if (m.parent / 'urdflint.toml').exists())}"
              f" with meshes), urdflint --jobs {args.jobs}, best of {args.repeat} (median)")  # fmt: skip
    print("| run | seconds | × floor |")
    print("|---|---|---|")
    for key in times:
        print(f"| {key} | {best[key]:.2f} ({median[key]:.2f}) | {best[key] / best['floor']:.1f} |")
    print()
    print(f"warm / floor = {best['warm'] / best['floor']:.2f} (goal <= 3)")
    print(f"edit / warm  = {best['edit'] / best['warm']:.2f} (goal <= 1.2)")
    print(f"cold / today = {best['cold'] / best['today']:.2f} (goal <= 1.05)")
    print(f"today / warm = {best['today'] / best['warm']:.1f}")
    print(f"same findings (today, cold, warm): {same}; after the edit, other files: {same_edit}")
    return 0 if same and same_edit else 1


if __name__ == "__main__":
    sys.exit(main())
