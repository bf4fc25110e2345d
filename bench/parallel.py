#!/usr/bin/env python3
"""Many files: ``urdflint check --jobs N`` against ``--jobs 1`` and two baselines.

    .venv/bin/python bench/parallel.py [--files 200] [--jobs 2] [--repeat 3]

The folder: ``--files`` copies of the 36 corpus robots' ``model.urdf`` (../shared/corpus, each
robot copied in turn, with its meshes reachable as in the corpus), in a temporary directory.
Every figure is a whole command measured in this run (best of ``--repeat``):

  1. ``urdflint check --jobs 1`` and ``--jobs N`` (default text output): the speed-up (goal:
     ≥ 1.7× with 2 on 2 CPUs), and the two outputs, text and JSON, compared byte for byte;
  2. the floor: one ``python -c`` that imports lxml and parses every file (hardened parser);
  3. Debian's ``check_urdf`` (liburdfdom-tools) once per file, when installed.
"""

from __future__ import annotations

import argparse
import os
import shutil
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
    "parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)\n"
    "for name in sys.argv[1:]:\n    etree.parse(name, parser)\n"
)


def best(repeat: int, argv: list[str]) -> tuple[float, bytes]:
    """Best wall time of ``argv`` over ``repeat`` runs, and its stdout."""
    times, out = [], b""
    for _ in range(repeat):
        start = time.perf_counter()
        out = subprocess.run(argv, capture_output=True, check=False, env=ENV, cwd=ROOT).stdout
        times.append(time.perf_counter() - start)
    return min(times), out


def folder(tmp: Path, count: int) -> list[Path]:
    """``count`` robot files: corpus robots in turn, each copy in its own folder beside a link
    to the robot's meshes and package map (so meshes resolve as in the corpus)."""
    robots = sorted(p for p in CORPUS.iterdir() if (p / "model.urdf").is_file())
    files = []
    for i in range(count):
        robot = robots[i % len(robots)]
        where = tmp / f"{robot.name}_{i // len(robots)}"
        where.mkdir()
        for extra in robot.iterdir():
            if extra.name != "model.urdf":
                (where / extra.name).symlink_to(extra)
        shutil.copy(robot / "model.urdf", where / "model.urdf")
        files.append(where / "model.urdf")
    return files


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--files", type=int, default=200)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    if not CORPUS.is_dir():
        print("../shared/corpus is not present", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        files = folder(Path(tmp), args.files)
        names = [str(f) for f in files]
        check = [sys.executable, "-m", "urdflint", "check", "--isolated", "--exit-zero", tmp]
        _, json1 = best(1, [*check, "--format", "json", "--jobs", "1"])  # also warms caches
        _, jsonn = best(1, [*check, "--format", "json", "--jobs", str(args.jobs)])
        serial, out1 = best(args.repeat, [*check, "--jobs", "1"])
        pooled, outn = best(args.repeat, [*check, "--jobs", str(args.jobs)])
        floor, _ = best(args.repeat, [sys.executable, "-c", FLOOR, *names])
        print(f"{len(files)} robot files ({len(os.sched_getaffinity(0))} CPUs)")
        print(f"| command | s | × floor |\n|---|---|---|\n| lxml parse floor | {floor:.2f} | 1 |")
        print(f"| urdflint check --jobs 1 | {serial:.2f} | {serial / floor:.0f} |")
        print(f"| urdflint check --jobs {args.jobs} | {pooled:.2f} | {pooled / floor:.0f} |")
        tool = shutil.which("check_urdf")
        if tool:
            start = time.perf_counter()
            for name in names:
                subprocess.run([tool, name], capture_output=True, check=False)
            loop = time.perf_counter() - start
            print(f"| check_urdf, once per file | {loop:.2f} | {loop / floor:.0f} |")
        print(f"\n--jobs {args.jobs} vs --jobs 1: {serial / pooled:.2f}x faster")
        print(f"text outputs identical: {out1 == outn} ({len(out1)} bytes)")
        print(f"JSON outputs identical: {json1 == jsonn} ({len(json1)} bytes)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
