#!/usr/bin/env python3
"""Mesh loading: urdflint's mesh rules next to trimesh alone on the same files.

    .venv/bin/python bench/bench_meshes.py [--repeat 3] [--json]

Input: every ../shared/corpus/robots/* whose meshes resolve (package_map.json gives the
package folders; bullet3's robots use paths relative to model.urdf). Prints:
  1. linting those robots in one process with the mesh rules (C004-C009, I007, I008) and a
     cold mesh cache per repeat, i.e. every file read again;
  2. the same trimesh.load calls on the same files, without urdflint (same arguments: no
     textures or materials read, see urdflint.meshes.assets_resolver);
  3. plain trimesh.load(path, force="mesh") on the same files, as most tools call it
     (textures decoded);
  4. the ratios, and the number of robots, files, loads and bytes.
Imports (trimesh, numpy, pycollada) are warmed up first and timed by neither side.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
MESH_RULES = ("C004", "C005", "C006", "C007", "C008", "C009", "I007", "I008")


def robots() -> list[tuple[Path, dict[str, Path]]]:
    """``(model.urdf, package paths)`` of every corpus robot with at least one mesh on disk."""
    from urdflint.engine import config, linter
    from urdflint.engine.context import Context
    from urdflint.sources.meshes import references, resolved

    found = []
    for model in sorted(CORPUS.glob("*/model.urdf")):
        mapping = model.parent / "package_map.json"
        paths = (
            {k: model.parent / v for k, v in json.loads(mapping.read_text()).items()}
            if mapping.is_file()
            else {}
        )
        doc = linter.load(model, str(model), config.Settings(), Context(package_paths=paths))
        if doc.ok and any(resolved(doc, r.uri).found for r in references(doc)):
            found.append((model, paths))
    return found


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    args = parser.parse_args()
    if not CORPUS.is_dir():
        print("../shared/corpus is not present", file=sys.stderr)
        return 2

    import trimesh  # warm imports: timed by neither side

    from urdflint.engine import config, linter, registry
    from urdflint.engine.context import Context
    from urdflint.sources.mesh_cache import assets_resolver
    from urdflint.sources.mesh_formats import TRIMESH_TYPES

    registry.load_rules()
    settings = config.Settings(select=MESH_RULES)
    models = robots()

    def urdflint_run() -> Context:
        context = Context()
        for model, paths in models:
            context.package_paths = paths
            linter.lint_path(model, str(model), settings, context)
        return context

    context = urdflint_run()  # warm-up; also tells which files and scales were loaded
    cache = context.meshes
    loaded = [key for key, info in cache._cache.items() if info.format in TRIMESH_TYPES]
    files = sorted({path for path, _ in loaded})
    size = sum(p.stat().st_size for p in files)

    def trimesh_run() -> None:
        for path, _ in loaded:  # the same calls urdflint makes, one per (file, scale)
            trimesh.load(
                str(path),
                file_type=TRIMESH_TYPES[path.suffix.lower().lstrip(".")],
                force="mesh",
                resolver=assets_resolver(path),
                skip_materials=True,
            )

    def plain_run() -> None:

        for path, _ in loaded:
            trimesh.load(str(path), force="mesh")

    ours, same, plain = [], [], []
    for _ in range(args.repeat):  # interleaved, so drift hits every side alike
        for fn, times in ((urdflint_run, ours), (trimesh_run, same), (plain_run, plain)):
            start = time.perf_counter()
            fn()
            times.append(time.perf_counter() - start)

    figures = {
        "robots": len(models),
        "files": len(files),
        "loads": len(loaded),
        "megabytes": round(size / 2**20, 2),
        "urdflint_s": round(min(ours), 3),
        "urdflint_median_s": round(statistics.median(ours), 3),
        "trimesh_same_calls_s": round(min(same), 3),
        "trimesh_same_calls_median_s": round(statistics.median(same), 3),
        "trimesh_plain_s": round(min(plain), 3),
        "trimesh_plain_median_s": round(statistics.median(plain), 3),
        "ratio_same_calls": round(min(ours) / min(same), 2),
        "ratio_plain": round(min(ours) / min(plain), 2),
    }
    f = figures
    print(
        f"{f['robots']} robots, {f['files']} mesh files ({f['megabytes']} MB), "
        f"{f['loads']} loads (file, scale); best of {args.repeat}, median in brackets"
    )
    print(
        f"urdflint mesh rules, cold cache   : {f['urdflint_s']:.3f} s "
        f"({f['urdflint_median_s']:.3f})"
    )
    print(
        f"trimesh.load, the same calls      : {f['trimesh_same_calls_s']:.3f} s "
        f"({f['trimesh_same_calls_median_s']:.3f})  ratio {f['ratio_same_calls']:.2f}x"
    )
    print(
        f"trimesh.load(path, force='mesh')  : {f['trimesh_plain_s']:.3f} s "
        f"({f['trimesh_plain_median_s']:.3f})  ratio {f['ratio_plain']:.2f}x"
    )
    if args.json:
        print(json.dumps(figures))
    return 0


if __name__ == "__main__":
    sys.exit(main())
