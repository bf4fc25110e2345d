#!/usr/bin/env python3
"""``urdflint fix --unsafe-fixes`` on copies of the shared corpus: findings per code before
and after, and whether Pinocchio and MuJoCo load each robot before and after.

    .venv/bin/python bench/fix_corpus.py [CORPUS_DIR] [--write-meshes] [--target=NAMES]

Each robot is copied with its meshes folder into a temporary folder (its package map is
passed as --package-path), linted, fixed, and linted again; nothing in the corpus changes.
"""

from __future__ import annotations

import contextlib
import io
import json
import shutil
import sys
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from urdflint.cli import main as cli  # noqa: E402
from urdflint.engines import runner  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "robots"


def report(path: Path, args: list[str]) -> list[dict]:
    out = path.with_suffix(".json")
    with contextlib.redirect_stderr(io.StringIO()):
        cli(["check", "--isolated", "--format", "json", "--exit-zero", "--output", str(out),
             *args, str(path)])  # fmt: skip
    return list(json.loads(out.read_text())["findings"])


def loads(path: Path, engine: str, packages: dict[str, Path]) -> bool | None:
    """Whether the engine builds the model (None: not installed)."""
    from urdflint.engine import config, linter

    if not runner.installed(engine):
        return None
    settings = config.Settings(confirm=(engine,), select=("E001", "E005"), package_paths=packages)
    found = linter.lint_path(path, str(path), settings).findings
    return not any(f.code in ("E001", "E005") for f in found)


def one(
    robot: Path, folder: Path, extra: list[str]
) -> tuple[Counter[str], Counter[str], dict[str, tuple]]:
    shutil.copytree(robot, folder, dirs_exist_ok=True)
    path = folder / "model.urdf"
    mapping = folder / "package_map.json"
    found = json.loads(mapping.read_text()) if mapping.is_file() else {}
    packages = {name: folder / sub for name, sub in found.items()}
    args = [f"--package-path={name}={where}" for name, where in packages.items()]
    args += [a for a in extra if a.startswith("--target")]
    before = Counter(f["code"] for f in report(path, args))
    engines = {e: (loads(path, e, packages),) for e in ("pinocchio", "mujoco")}
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        writes = [a for a in extra if a == "--write-meshes"]
        cli(["fix", "--isolated", "--unsafe-fixes", "--exit-zero", *writes, *args, str(path)])
    after = Counter(f["code"] for f in report(path, args))
    engines = {e: (*v, loads(path, e, packages)) for e, v in engines.items()}
    return before, after, engines


def main() -> int:
    extra = [a for a in sys.argv[1:] if a.startswith("--")]
    given = [a for a in sys.argv[1:] if a not in extra]
    corpus = Path(given[0]) if given else CORPUS
    total_before: Counter[str] = Counter()
    total_after: Counter[str] = Counter()
    rows = []
    for robot in sorted(p.parent for p in corpus.glob("*/model.urdf")):
        with tempfile.TemporaryDirectory() as tmp:
            before, after, engines = one(robot, Path(tmp) / robot.name, extra)
        total_before.update(before)
        total_after.update(after)
        rows.append((robot.name, sum(before.values()), sum(after.values()), engines))
    print("| code | before | after |\n|---|---|---|")
    for code in sorted(set(total_before) | set(total_after)):
        if total_before[code] != total_after[code]:
            print(f"| {code} | {total_before[code]} | {total_after[code]} |")
    print(f"| all | {sum(total_before.values())} | {sum(total_after.values())} |")
    print("\n| robot | findings before | after | Pinocchio before/after | MuJoCo before/after |")
    print("|---|---|---|---|---|")
    for name, before_n, after_n, engines in rows:
        pin, mj = engines["pinocchio"], engines["mujoco"]
        print(f"| {name} | {before_n} | {after_n} | {pin[0]}/{pin[1]} | {mj[0]}/{mj[1]} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
