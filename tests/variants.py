"""Generated datasets: variants of the corpus robots, each with one planted defect.

:func:`make` writes ``count`` URDF files below a folder: the robots of
``../shared/corpus/robots`` taken in turn (the smallest files first unless told), each
variant a copy of a robot with one defect of :mod:`tests.planted` planted (the defects
taken in turn too, skipping those that do not apply to that robot), some left as they are.
Each robot's variants share a folder with links to its meshes and a ``urdflint.toml``
naming its packages (its ``package_map.json``), so meshes resolve as in the corpus.
``bench/bench_ray.py`` and the Ray tests use it. This module holds no tests.
"""

from __future__ import annotations

import json
from pathlib import Path

from tests import planted

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus" / "robots"
DEFECTS = (
    None,
    "negative_mass",
    "zero_axis",
    "missing_inertial_moving_link",
    "inverted_limits",
    "not_positive_definite",
    "zero_mass_moving_link",
    "non_unit_axis",
    "tiny_mass",
)


def robots(largest: int | None = None) -> list[Path]:
    """The corpus robots' model files, smallest first (at most ``largest`` bytes each)."""
    found = sorted(CORPUS.glob("*/model.urdf"), key=lambda p: (p.stat().st_size, str(p)))
    return [p for p in found if largest is None or p.stat().st_size <= largest]


def _folder(model: Path, dest: Path) -> Path:
    folder = dest / model.parent.name
    if folder.is_dir():
        return folder
    folder.mkdir(parents=True)
    for entry in model.parent.iterdir():
        if entry.name not in ("model.urdf", "package_map.json"):
            (folder / entry.name).symlink_to(entry)
    packages = model.parent / "package_map.json"
    if packages.is_file():
        table = json.loads(packages.read_text())
        lines = ["[package-paths]"] + [f'"{k}" = "{v}"' for k, v in sorted(table.items())]
        (folder / "urdflint.toml").write_text("\n".join(lines) + "\n")
    return folder


def make(dest: Path, count: int, largest: int | None = None) -> list[Path]:
    """``count`` variant files below ``dest`` (see the module docstring), in a stable order."""
    models = robots(largest)
    if not models:
        raise FileNotFoundError(f"no corpus robots in {CORPUS}")
    made: list[Path] = []
    turn = 0
    while len(made) < count:
        model = models[turn % len(models)]
        defect = DEFECTS[(turn // len(models) + turn) % len(DEFECTS)]
        turn += 1
        tree, element = planted.plant(model, defect) if defect else (planted.load(model), True)
        if element is None:
            continue
        folder = _folder(model, dest)
        path = folder / f"v{len(made):05d}-{defect or 'as-is'}.urdf"
        tree.write(str(path), xml_declaration=True, encoding="utf-8")
        made.append(path)
        if turn > count * 20:  # nothing applies any more: fewer than asked
            break
    return made
