#!/usr/bin/env python3
"""A sample dataset and its report: the corpus robots plus planted-defect variants, checked
before and after a change set, summarised by ``urdflint report``.

    .venv/bin/python bench/dataset_sample.py [--out DIR] [--screenshot PNG] [--height PX]
                                             [--jobs N]

Into ``DIR/dataset`` (default: a temporary folder, kept) go the robots of
``../shared/corpus/robots`` (each in its own folder, beside links to its meshes, with a
``urdflint.toml`` holding its ``package_map.json`` as ``package-paths``) and variants of
them with one defect of ``tests/planted.py`` planted: a negative mass, a zero joint axis, a
moving link without ``<inertial>``, inverted joint limits, a second root.
``urdflint check --format jsonl --matrix`` writes ``DIR/before.jsonl``; then a change set
is applied in place (the negative-mass and zero-axis variants repaired, defects planted in
three of the original robots, two variants removed, three added) and the check writes
``DIR/after.jsonl``. Last, ``urdflint report DIR/after.jsonl --against DIR/before.jsonl``
prints the summary and writes ``DIR/report.html`` (and ``DIR/parquet/`` with pyarrow).

``--screenshot PNG`` saves the page as headless Chromium shows it at 1400 px wide, its top
``--height`` pixels (needs Selenium, Debian's ``chromium`` and ``chromium-driver``, and
Pillow to shrink the PNG to 256 colours): the README's ``docs/images/dataset-report.png``
is made this way.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests import planted  # noqa: E402

SHARED = Path(os.environ.get("URDFLINT_SHARED", ROOT.parent / "shared"))
CORPUS = SHARED / "corpus" / "robots"
PLANTED = {  # defect -> how many variants the dataset has
    "negative_mass": 4,
    "zero_axis": 4,
    "missing_inertial_moving_link": 4,
    "inverted_limits": 4,
    "second_root": 3,
}
REPAIRED = ("negative_mass", "zero_axis")  # the change set fixes these variants
REGRESSIONS = ("inverted_limits", "second_root", "negative_mass")  # planted in originals
ADDED = "zero_axis"  # the change set adds variants with this defect


def robots() -> list[Path]:
    """The corpus robots' model files, by name."""
    return sorted(CORPUS.glob("*/model.urdf"))


def write(model: Path, folder: Path, defect: str | None) -> bool:
    """The robot of ``model`` (with ``defect`` planted) in ``folder``, beside links to its
    meshes and a configuration naming its packages; False when the defect does not apply."""
    tree, element = planted.plant(model, defect) if defect else (planted.load(model), True)
    if element is None:
        return False
    folder.mkdir(parents=True, exist_ok=True)
    for entry in model.parent.iterdir():
        if entry.name not in ("model.urdf", "package_map.json"):
            target = folder / entry.name
            if not target.exists():
                target.symlink_to(entry)
    tree.write(str(folder / "model.urdf"), xml_declaration=True, encoding="utf-8")
    packages = model.parent / "package_map.json"
    if packages.is_file():
        table = json.loads(packages.read_text())
        lines = ["[package-paths]"] + [f'"{k}" = "{v}"' for k, v in sorted(table.items())]
        (folder / "urdflint.toml").write_text("\n".join(lines) + "\n")
    return True


def variants(
    models: list[Path], dataset: Path, defect: str, count: int, skip: int = 0
) -> list[str]:
    """``count`` variants with ``defect`` (robots taken in turn from ``skip`` on, those the
    defect does not apply to passed over); their folder names."""
    made: list[str] = []
    order = models[skip:] + models[:skip]
    for model in order:
        if len(made) == count:
            break
        name = f"{model.parent.name}-{defect.replace('_', '-')}"
        if (dataset / name).exists():
            continue
        if write(model, dataset / name, defect):
            made.append(name)
    return made


def check(out: Path, dataset: Path, jobs: int | None) -> float:
    """``urdflint check --format jsonl --matrix`` of every model of the dataset into ``out``
    (run from the dataset's parent: the records' paths are ``dataset/<robot>/model.urdf``)."""
    files = sorted(str(p.relative_to(dataset.parent)) for p in dataset.glob("*/model.urdf"))
    command = [
        sys.executable,
        "-m",
        "urdflint",
        "check",
        "--format",
        "jsonl",
        "--matrix",
        "--exit-zero",
        "--output",
        str(out),
        *files,
    ]
    if jobs:
        command[4:4] = ["--jobs", str(jobs)]
    started = time.perf_counter()
    done = subprocess.run(command, cwd=dataset.parent, capture_output=True, text=True)
    # exit 2 with every record written: a rule crashed on a file (U001), which the records
    # say and the report shows
    if done.returncode != 0 and not (done.returncode == 2 and "records in" in done.stderr):
        sys.exit(f"urdflint check failed ({done.returncode}):\n{done.stderr}")
    return time.perf_counter() - started


def change(models: list[Path], dataset: Path, made: dict[str, list[str]]) -> dict[str, list[str]]:
    """The change set, applied in place: what it repaired, broke, removed and added."""
    done: dict[str, list[str]] = {"repaired": [], "regressed": [], "removed": [], "added": []}
    for defect in REPAIRED:
        for name in made[defect]:
            robot = name.removesuffix("-" + defect.replace("_", "-"))
            write(CORPUS / robot / "model.urdf", dataset / name, None)
            done["repaired"].append(name)
    untouched = [
        m for m in models if not any(m.parent.name + "-" in n for v in made.values() for n in v)
    ]
    for defect, model in zip(REGRESSIONS, untouched or models, strict=False):
        if write(model, dataset / model.parent.name, defect):
            done["regressed"].append(f"{model.parent.name} ({defect})")
    for name in made["missing_inertial_moving_link"][:2]:
        shutil.rmtree(dataset / name)
        done["removed"].append(name)
    done["added"] = variants(models, dataset, ADDED, 3, skip=len(models) // 2)
    return done


def screenshot(page: Path, target: Path, tallest: int) -> None:
    """The page at 1400 px wide, its top ``tallest`` px (or all of it), as a palette PNG."""
    from PIL import Image

    from tests.server.browsing import new_driver

    with tempfile.TemporaryDirectory(prefix="urdflint-chromium-") as profile:
        driver = new_driver(Path(profile))
        try:
            driver.get(page.resolve().as_uri())
            height = int(driver.execute_script("return document.documentElement.scrollHeight"))
            driver.set_window_size(1400, height + 140)  # all of it; 140: the window's frame
            driver.execute_script("document.documentElement.style.overflow = 'hidden'")
            time.sleep(0.5)
            raw = target.with_suffix(".raw.png")
            driver.save_screenshot(str(raw))
        finally:
            driver.quit()
    with Image.open(raw) as image:
        shown = image.convert("RGB").crop((0, 0, 1400, min(height, tallest, image.height)))
        shown.quantize(colors=256, method=Image.Quantize.FASTOCTREE).save(target, optimize=True)
    raw.unlink()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, help="the folder (default: a new temporary one)")
    parser.add_argument("--screenshot", type=Path, metavar="PNG", help="save the page as PNG")
    parser.add_argument("--height", type=int, default=3700, help="the screenshot's height (px)")
    parser.add_argument("--jobs", type=int, help="urdflint check --jobs")
    args = parser.parse_args()
    models = robots()
    if not models:
        sys.exit(f"no corpus robots in {CORPUS}")
    out = (args.out or Path(tempfile.mkdtemp(prefix="urdflint-dataset-"))).resolve()
    dataset = out / "dataset"
    if dataset.exists():
        shutil.rmtree(dataset)
    for model in models:
        write(model, dataset / model.parent.name, None)
    made = {
        d: variants(models, dataset, d, n, skip=5 * i) for i, (d, n) in enumerate(PLANTED.items())
    }
    took = check(out / "before.jsonl", dataset, args.jobs)
    print(
        f"before: {len(list(dataset.glob('*/model.urdf')))} files in {took:.1f} s", file=sys.stderr
    )
    done = change(models, dataset, made)
    took = check(out / "after.jsonl", dataset, args.jobs)
    print(
        f"after: {len(list(dataset.glob('*/model.urdf')))} files in {took:.1f} s", file=sys.stderr
    )
    for key, names in done.items():
        print(f"  {key}: {', '.join(names)}", file=sys.stderr)
    report = [
        sys.executable,
        "-m",
        "urdflint",
        "report",
        "after.jsonl",
        "--against",
        "before.jsonl",
        "--html",
        "report.html",
        "--top",
        "12",
    ]
    try:
        import pyarrow  # noqa: F401

        report += ["--parquet", "parquet"]
    except ImportError:
        pass
    subprocess.run(report, cwd=out, check=True)
    print(f"report: {out / 'report.html'}", file=sys.stderr)
    if args.screenshot:
        screenshot(out / "report.html", args.screenshot.resolve(), args.height)
        print(
            f"screenshot: {args.screenshot} ({args.screenshot.stat().st_size // 1024} KB)",
            file=sys.stderr,
        )


if __name__ == "__main__":
    main()
