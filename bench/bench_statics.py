#!/usr/bin/env python3
"""The cost of the statics (D family, ``info --statics``) on real robots, as ratios against
baselines measured in the same run.

    .venv/bin/python bench/bench_statics.py [--repeat 3] [--json] [ROBOT...]

Input: ../shared/corpus/robots/{ur5,panda_gazebo,kuka_iiwa,pr2,tiago,valkyrie}/model.urdf
(or the corpus robots named), those absent skipped, with the package folders of their
``package_map.json`` (``--package-path``) so the meshes load as a user's run loads them.
Each command is a whole process, as a user runs it (interpreter, imports, reading the
meshes), ``--isolated``, without the analysis cache (``URDFLINT_NO_CACHE=1``, and ``check
--no-cache``) so every run does the work; the commands take turns within each repeat (a
load that comes and goes on a shared machine spreads over all of them); one run of each
first writes the bytecode caches and is not counted. Per robot, the median of ``--repeat``
runs of:

  lxml       python -c: import lxml, parse the file with a hardened parser (the floor)
  info       urdflint info                 (mass, COM, tree: Pinocchio and the meshes)
  statics    urdflint info --statics       (+ every joint's torque, the payload, the base)
  check      urdflint check                (every rule, D001-D003 included)
  check-D    urdflint check --ignore D     (every rule but the D family)

and the ratios of statics, check and check-D to info and to lxml; ``D`` is check minus
check-D, what the D family adds to a check (within the noise of whole processes on the arms).
``D warm`` measures the same in this process, the model and its meshes loaded once (the
median of ``--repeat`` lints with every rule minus the median without the D rules): what
D001-D003 cost once the model is read. The load average before and after is printed: the
machine may be shared.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
ROBOTS = ("ur5", "panda_gazebo", "kuka_iiwa", "pr2", "tiago", "valkyrie")
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
ENV["URDFLINT_NO_CACHE"] = "1"
FLOOR = (
    "import sys\nfrom lxml import etree\n"
    "parser = etree.XMLParser(resolve_entities=False, no_network=True)\n"
    "etree.parse(sys.argv[1], parser)\n"
)
URDFLINT = [sys.executable, "-m", "urdflint"]


def packages(model: Path) -> dict[str, Path]:
    mapping = model.parent / "package_map.json"
    found = json.loads(mapping.read_text()) if mapping.is_file() else {}
    return {name: model.parent / folder for name, folder in sorted(found.items())}


def commands(model: Path) -> dict[str, list[str]]:
    """The five commands on one robot (see the module docstring)."""
    paths = [a for name, folder in packages(model).items()
             for a in ("--package-path", f"{name}={folder}")]  # fmt: skip
    info = [*URDFLINT, "info", "--isolated", *paths]
    check = [*URDFLINT, "check", "--isolated", "--no-cache", "--exit-zero", "--format", "json"]
    return {
        "lxml": [sys.executable, "-c", FLOOR, str(model)],
        "info": [*info, str(model)],
        "statics": [*info, "--statics", str(model)],
        "check": [*check, *paths, str(model)],
        "check-D": [*check, "--ignore", "D", *paths, str(model)],
    }


def timed(cmd: list[str]) -> tuple[float, str]:
    """Wall time of one run (seconds) and its standard output; a failed run stops the bench."""
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, check=False, env=ENV)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {done.returncode}:\n{done.stderr[-2000:]}")
    return elapsed, done.stdout


def measure(model: Path, repeat: int) -> dict[str, object]:
    """The medians of the five commands on ``model``, and the D findings of its check."""
    cmds = commands(model)
    outputs = {label: timed(cmd)[1] for label, cmd in cmds.items()}  # warm-up, not counted
    times: dict[str, list[float]] = {label: [] for label in cmds}
    for _ in range(repeat):
        for label, cmd in cmds.items():  # in turns
            times[label].append(timed(cmd)[0])
    median = {label: statistics.median(found) for label, found in times.items()}
    findings = json.loads(outputs["check"])["findings"]
    return {
        "robot": model.parent.name,
        "median_s": median,
        "runs_s": times,
        "d_findings": sum(1 for f in findings if f["code"].startswith("D")),
        "findings": len(findings),
    }


def warm(model: Path, repeat: int) -> float:
    """Median lint with every rule minus median lint without the D rules, in this process,
    the meshes read once (one context, no analysis cache), in turns."""
    from urdflint.engine import config, linter, registry
    from urdflint.engine.context import Context

    context = Context(package_paths=packages(model))
    every = config.Settings()
    no_d = config.Settings(ignore=tuple(c for c in registry.load_rules() if c.startswith("D")))
    times: dict[int, list[float]] = {0: [], 1: []}
    for turn in range(repeat + 1):
        for which, settings in enumerate((every, no_d)):
            start = time.perf_counter()
            linter.lint_path(model, str(model), settings, context)
            if turn:  # the first turn reads the meshes: not counted
                times[which].append(time.perf_counter() - start)
    return statistics.median(times[0]) - statistics.median(times[1])


def ratios(row: dict[str, object]) -> dict[str, float]:
    median = row["median_s"]
    assert isinstance(median, dict)
    found = {}
    for label in ("statics", "check", "check-D"):
        found[f"{label}/info"] = median[label] / median["info"]
        found[f"{label}/lxml"] = median[label] / median["lxml"]
    found["D_s"] = median["check"] - median["check-D"]
    found["D_warm_s"] = row["d_warm_s"]  # type: ignore[assignment]
    return found


def table(rows: list[dict[str, object]]) -> str:
    head = ("robot", "lxml", "info", "statics", "check", "check-D", "D", "D warm", "statics/info",
            "check/info", "check-D/info", "statics/lxml", "check/lxml", "check-D/lxml", "D found")  # fmt: skip
    lines = [" | ".join(head), " | ".join("---" for _ in head)]
    for row in rows:
        m, r = row["median_s"], row["ratios"]
        assert isinstance(m, dict) and isinstance(r, dict)
        ms = [f"{m[k] * 1e3:.0f} ms" for k in ("lxml", "info", "statics", "check", "check-D")]
        x = [f"{r[k]:.2f}x" for k in ("statics/info", "check/info", "check-D/info")]
        x += [f"{r[k]:.1f}x" for k in ("statics/lxml", "check/lxml", "check-D/lxml")]
        d = [f"{r['D_s'] * 1e3:+.0f} ms", f"{r['D_warm_s'] * 1e3:.0f} ms"]
        cells = [str(row["robot"]), *ms, *d, *x, str(row["d_findings"])]
        lines.append(" | ".join(cells))
    return "\n".join(f"| {line} |" for line in lines)


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("robots", nargs="*", help=f"corpus robots (default: {', '.join(ROBOTS)})")
    parser.add_argument("--repeat", type=int, default=3, help="runs per command (median)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    args = parser.parse_args()
    models = [CORPUS / name / "model.urdf" for name in args.robots or ROBOTS]
    present = [m for m in models if m.is_file()]
    for missing in sorted(set(models) - set(present)):
        print(f"skipped: {missing} is absent", file=sys.stderr)
    if not present:
        print("no robot to measure (is ../shared/corpus present?)", file=sys.stderr)
        return 2
    before = os.getloadavg()
    rows = []
    for model in present:
        row = measure(model, max(1, args.repeat))
        row["d_warm_s"] = warm(model, max(1, args.repeat))
        row["ratios"] = ratios(row)
        rows.append(row)
        print(f"measured {row['robot']}", file=sys.stderr, flush=True)
    after = os.getloadavg()
    print(f"median of {args.repeat} runs per command, {os.cpu_count()} CPUs; load average "
          f"{before[0]:.2f} before, {after[0]:.2f} after (1 min)")  # fmt: skip
    print(table(rows))
    if args.json:
        print(json.dumps({"load": [before, after], "repeat": args.repeat, "rows": rows}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
