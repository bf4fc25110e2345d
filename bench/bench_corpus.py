#!/usr/bin/env python3
"""Speed of the static rules, as ratios against baselines measured in the same run.

    .venv/bin/python bench/bench_corpus.py [--repeat 5] [FILES or folders...]

Default input: every ../shared/corpus/robots/*/model.urdf. Prints:
  1. linting every file in one process vs a bare (hardened) lxml parse of the same bytes,
  2. vs Debian's check_urdf (liburdfdom-tools) run once per file, when installed,
  3. cold start of `urdflint check` on one small file vs `python -c "import lxml.etree"`,
  4. which heavy modules a static lint imported (must be none).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
SMALL = ROOT / "fixtures" / "models" / "example_arm.urdf"
# Subprocesses run as a user's would: with bytecode caches (PYTHONDONTWRITEBYTECODE unset).
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
FLOOR = (
    "import sys\nfrom lxml import etree\n"
    "parser = etree.XMLParser(resolve_entities=False, no_network=True)\n"
    "for name in sys.argv[1:]:\n    etree.parse(name, parser)\n"
)
HEAVY = ("numpy", "scipy", "trimesh", "yourdfpy", "pinocchio", "fastapi")


def files_from(args: list[str]) -> list[Path]:
    if not args:
        return sorted(CORPUS.glob("*/model.urdf"))
    found: list[Path] = []
    for arg in map(Path, args):
        found.extend(sorted(arg.rglob("*.urdf")) if arg.is_dir() else [arg])
    return found


def best_of(repeat: int, fn) -> tuple[float, float]:
    """(minimum, median) wall time of ``fn()`` over ``repeat`` runs, in seconds."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times)


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("paths", nargs="*")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    args = parser.parse_args()

    from lxml import etree

    from urdflint.engine import linter, registry
    from urdflint.model.document import make_parser

    files = files_from(args.paths)
    if not files:
        print("no input files (is ../shared/corpus present?)", file=sys.stderr)
        return 2
    blobs = [(str(p), p.read_bytes()) for p in files]
    size = sum(len(b) for _, b in blobs)
    registry.load_rules()

    def parse_only() -> None:
        for _, data in blobs:
            etree.fromstring(data, make_parser())

    findings = 0

    def lint_all() -> None:
        nonlocal findings
        findings = sum(len(linter.lint_bytes(data, name).findings) for name, data in blobs)

    from urdflint.engine import config

    # the static rules: every rule that needs no optional module (no Pinocchio, no mesh
    # loading through trimesh, no numpy self-collision)
    heavy = tuple(sorted(code for code, r in registry.RULES.items() if r.needs))
    no_physics = config.Settings(ignore=heavy)

    def lint_static() -> None:
        for name, data in blobs:
            linter.lint_bytes(data, name, no_physics)

    lint_all()  # warm caches shared by both sides (rule import, lxml, Pinocchio, trimesh)
    parse_min, parse_med = best_of(args.repeat, parse_only)
    lint_min, lint_med = best_of(args.repeat, lint_all)
    static_min, _ = best_of(args.repeat, lint_static)

    results: dict[str, object] = {
        "files": len(files),
        "bytes": size,
        "rules": len(registry.RULES),
        "findings": findings,
        "lxml_parse_s": parse_min,
        "urdflint_s": lint_min,
        "ratio_vs_lxml": lint_min / parse_min,
    }
    print(
        f"{len(files)} files, {size / 1e6:.2f} MB, {len(registry.RULES)} rules, {findings} findings"
    )
    print(
        f"bare lxml parse (hardened parser)  min {parse_min * 1e3:8.1f} ms   median {parse_med * 1e3:8.1f} ms"
    )
    print(
        f"urdflint, all rules, one process  min {lint_min * 1e3:8.1f} ms   median {lint_med * 1e3:8.1f} ms"
    )
    print(f"  ratio urdflint / lxml parse: {lint_min / parse_min:.1f}x")
    results.update(
        urdflint_no_physics_s=static_min, ratio_no_physics_vs_lxml=static_min / parse_min
    )
    print(
        f"urdflint, static rules (all but {','.join(heavy)})  min {static_min * 1e3:8.1f} ms  "
        f"({static_min / parse_min:.1f}x the parse)"
    )

    check_urdf = shutil.which("check_urdf")
    if check_urdf:

        def run_check_urdf() -> None:
            for name, _ in blobs:
                subprocess.run([check_urdf, name], capture_output=True, check=False)

        cu_min, cu_med = best_of(max(1, args.repeat // 2), run_check_urdf)
        results.update(check_urdf_s=cu_min, ratio_vs_check_urdf=lint_min / cu_min)
        print(
            f"check_urdf, one process per file   min {cu_min * 1e3:8.1f} ms   median {cu_med * 1e3:8.1f} ms"
        )
        print(f"  ratio urdflint (in-process) / check_urdf: {lint_min / cu_min:.2f}x")
        names = [name for name, _ in blobs]
        cli = [sys.executable, "-m", "urdflint", "check", "--format", "json", "--exit-zero", *names]
        subprocess.run(cli, capture_output=True, check=False, env=ENV)  # write bytecode caches
        cli_min, _ = best_of(
            args.repeat, lambda: subprocess.run(cli, capture_output=True, check=False, env=ENV)
        )
        results.update(urdflint_cli_all_s=cli_min, ratio_cli_vs_check_urdf=cli_min / cu_min)
        print(
            f"urdflint check <all files>, one CLI process: min {cli_min * 1e3:.0f} ms "
            f"({cli_min / cu_min:.2f}x the check_urdf loop, which checks far less)"
        )
    else:
        print("check_urdf not installed (apt-get install liburdfdom-tools): skipped")

    def cold(cmd: list[str]) -> float:
        return best_of(args.repeat, lambda: subprocess.run(cmd, capture_output=True, check=False))[
            0
        ]

    names = [name for name, _ in blobs]
    floor_cmd = [sys.executable, "-c", FLOOR, *names]
    static_cmd = [sys.executable, "-m", "urdflint", "check", "--isolated", "--exit-zero"]
    static_cmd += ["--ignore", ",".join(heavy), "--format", "json", *names]
    subprocess.run(static_cmd, capture_output=True, check=False, env=ENV)  # bytecode caches
    floor_s, static_s = cold(floor_cmd), cold(static_cmd)
    results.update(cmd_floor_s=floor_s, cmd_static_s=static_s, ratio_cmd_static=static_s / floor_s)
    print(
        f"whole command on every file: python -c (import lxml, parse each) {floor_s * 1e3:.0f} ms; "
        f"urdflint check, static rules {static_s * 1e3:.0f} ms ({static_s / floor_s:.1f}x)"
    )

    cold_lxml = cold([sys.executable, "-c", "import lxml.etree"])
    cold_static = cold(
        [sys.executable, "-m", "urdflint", "check", "--exit-zero", "--select", "X,S,J", str(SMALL)]
    )
    cold_full = cold([sys.executable, "-m", "urdflint", "check", "--exit-zero", str(SMALL)])
    results.update(
        cold_import_lxml_s=cold_lxml,
        cold_static_s=cold_static,
        cold_full_s=cold_full,
        cold_static_ratio=cold_static / cold_lxml,
    )
    print(
        f"cold start on {SMALL.name}: python -c 'import lxml.etree' {cold_lxml * 1e3:.0f} ms; "
        f"urdflint check --select X,S,J {cold_static * 1e3:.0f} ms ({cold_static / cold_lxml:.2f}x); "
        f"urdflint check, every rule (Pinocchio) {cold_full * 1e3:.0f} ms ({cold_full / cold_lxml:.2f}x)"
    )

    for label, select in (("--select X,S,J", ("X", "S", "J")), ("every rule", None)):
        probe = (
            "import sys; from urdflint.engine import config, linter; "
            f"s = config.Settings(select={select!r}); "
            f"linter.lint_bytes(open({str(SMALL)!r}, 'rb').read(), 'x', s); "
            f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
        )
        heavy = subprocess.run(
            [sys.executable, "-c", probe], capture_output=True, text=True, check=True, env=ENV
        ).stdout.strip()
        results[f"heavy_modules {label}"] = heavy.split(",") if heavy else []
        print(f"heavy modules imported by urdflint check {label}: {heavy or 'none'}")
    if args.json:
        print(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
