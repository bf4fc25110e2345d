"""``urdflint lsp``: start the language server on stdin/stdout."""

from __future__ import annotations

import argparse
from typing import Any

from urdflint.cli.common import UsageError, cache_options, open_cache, settings_here


def add_parser(sub: Any) -> None:
    parser = sub.add_parser(
        "lsp",
        help="run the language server over stdio (diagnostics, fixes, hover in your editor)",
        description="Speak the Language Server Protocol on stdin/stdout: diagnostics for "
        ".urdf and .xacro files as you type, quick fixes, suppression comments, hover, outline. "
        "Editors start it; see README (VS Code, Neovim, Helix).",
    )
    cache_options(parser)


def run(args: argparse.Namespace) -> int:
    try:
        import pygls  # noqa: F401
    except ImportError:
        raise UsageError("urdflint lsp needs pygls: pip install 'urdflint[lsp]'") from None
    from urdflint.lsp.server import main

    return main(open_cache(args, settings_here()))
