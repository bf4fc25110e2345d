"""``urdflint cache info|clean``: what the analysis cache holds, and emptying it."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from urdflint.cli.common import EXIT_ERROR, EXIT_OK, cache_options, settings_here


def add_parser(sub: Any) -> None:
    parser = sub.add_parser("cache", help="show or empty the analysis cache")
    parser.add_argument("action", choices=("info", "clean"), help="info: where and how big; "
                        "clean: remove every entry")  # fmt: skip
    parser.add_argument("--format", choices=("text", "json"), default="text")
    parser.add_argument("--config", type=Path, metavar="FILE", help="the configuration file")
    parser.add_argument("--isolated", action="store_true", help="ignore configuration files")
    cache_options(parser)


def run(args: argparse.Namespace) -> int:
    from urdflint.cache import DEFAULT_MAX_BYTES, default_dir
    from urdflint.cache.store import FORMAT, Store

    settings = settings_here(args)
    folder = args.cache_dir or getattr(settings, "cache_dir", None) or default_dir()
    limit = getattr(settings, "cache_max_size", None) or DEFAULT_MAX_BYTES
    exists = Path(folder).is_dir()
    if args.action == "clean":
        if not exists:
            print(f"urdflint: the cache folder {folder} does not exist; nothing to clean")
            return EXIT_OK
        removed = Store(Path(folder), limit).clean()
        print(f"urdflint: removed {removed} cache files from {folder}")
        return EXIT_OK
    store = Store(Path(folder), limit) if exists else None
    kinds: dict[str, dict[str, int]] = {}
    if store is not None:
        for _, size, path in store.entries():
            kind = path.relative_to(store.base).parts[0]
            entry = kinds.setdefault(kind, {"entries": 0, "bytes": 0})
            entry["entries"] += 1
            entry["bytes"] += size
    total = sum(k["bytes"] for k in kinds.values())
    info = {
        "folder": str(folder),
        "format": FORMAT,
        "exists": exists,
        "usable": bool(store and store.usable),
        "writable": bool(store and store.writable),
        "problem": store.problem if store is not None else None,
        "max_bytes": limit,
        "bytes": total,
        "entries": sum(k["entries"] for k in kinds.values()),
        "kinds": kinds,
    }
    if args.format == "json":
        json.dump(info, sys.stdout, indent=2)
        print()
        return EXIT_OK
    state = "read-only" if info["usable"] and not info["writable"] else "usable"
    if not exists:
        state = "not created yet"
    elif not info["usable"]:
        state = f"not usable: {info['problem']}"
    print(f"folder:  {folder} ({state})")
    print(f"size:    {_size(total)} of {_size(limit)} in {info['entries']} entries")
    for kind, entry in sorted(kinds.items()):
        print(f"  {kind:<9}{entry['entries']:>7} entries {_size(entry['bytes']):>10}")
    return EXIT_OK if info["usable"] or not exists else EXIT_ERROR


def _size(count: int) -> str:
    value = float(count)
    for unit in ("B", "KiB", "MiB", "GiB"):
        if value < 1024 or unit == "GiB":
            return f"{value:.0f} {unit}" if unit == "B" else f"{value:.1f} {unit}"
        value /= 1024
    return f"{count} B"
