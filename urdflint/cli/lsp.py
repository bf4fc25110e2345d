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
        from urdflint.model.optional import install_command

        raise UsageError(f"urdflint lsp needs pygls: {install_command('lsp')}") from None
    from urdflint.lsp.server import main

    return main(open_cache(args, settings_here()))
