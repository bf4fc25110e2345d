"""``urdflint rules`` and ``urdflint explain``: the rule catalogue and each rule's page."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from urdflint.cli.common import EXIT_OK, UsageError
from urdflint.engine import registry


def add_parsers(sub: Any) -> None:
    rules = sub.add_parser("rules", help="list the rules")
    rules.add_argument("--format", choices=("text", "json"), default="text")

    explain = sub.add_parser(
        "explain", help="show a rule's page: what, why, how to fix, a bad and a good example"
    )
    explain.add_argument("rule", metavar="CODE|NAME")
    explain.add_argument(
        "--long",
        action="store_true",
        help="the full page: every section in full, what each target does, every example",
    )


def run_rules(args: argparse.Namespace) -> int:
    rules = registry.load_rules()
    if args.format == "json":
        data = registry.catalogue()
        import json

        print(json.dumps({"version": 1, "rules": data}, indent=2))
        return EXIT_OK
    for r in sorted(rules.values(), key=lambda r: r.code):
        print(f"{r.code}  {r.name:<36} {r.severity!s:<8} {r.summary}")
    return EXIT_OK


def run_explain(args: argparse.Namespace) -> int:
    from urdflint.engine import docs

    found = registry.lookup(args.rule)
    if found is None:
        raise UsageError(f"unknown rule {args.rule!r} (see 'urdflint rules')")
    sys.stdout.write(docs.page(found) if args.long else docs.short_page(found))
    return EXIT_OK
