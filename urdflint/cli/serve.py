"""``urdflint serve``: the HTTP validation service under uvicorn."""

from __future__ import annotations

import argparse
import os
from typing import Any

from urdflint.cli.common import EXIT_OK, UsageError, cache_options


def add_parser(sub: Any) -> None:
    serve = sub.add_parser(
        "serve",
        help="run the HTTP validation service (needs urdflint[server])",
        description="Run the HTTP service (urdflint.server.app:app) with uvicorn. Limits come "
        "from URDFLINT_* environment variables: MAX_URDF_BYTES, MAX_ZIP_BYTES, TIMEOUT, "
        "JOBS, QUEUE (see the README).",
    )
    serve.add_argument(
        "--allow-confirm",
        action="store_true",
        help="accept the confirm option of /v1/check: load uploads in the installed "
        "simulation engines (off by default: heavy native code on untrusted input; each "
        "engine runs in its own process with a memory limit and a timeout); the same as "
        "URDFLINT_ALLOW_CONFIRM=1",
    )
    serve.add_argument("--host", default="127.0.0.1", help="address to listen on")
    serve.add_argument("--port", type=int, default=8000, help="port to listen on")
    serve.add_argument(
        "--workers",
        type=int,
        default=1,
        help="server processes (each with its own URDFLINT_JOBS lint workers)",
    )
    serve.add_argument("--log-level", default="info", choices=("debug", "info", "warning", "error"))
    cache_options(serve)


def run(args: argparse.Namespace) -> int:
    """Run uvicorn with the service; its imports happen here, never at CLI start."""
    try:
        import uvicorn
    except ImportError:
        from urdflint.model.optional import install_command

        raise UsageError(f"serve needs the server extra: {install_command('server')}") from None
    if args.workers < 1 or not 0 <= args.port < 65536:
        raise UsageError("--workers must be at least 1 and --port between 0 and 65535")
    from urdflint.server.limits import LimitError, Limits

    if args.allow_confirm:  # the app reads its settings from the environment (Limits.from_env)
        os.environ["URDFLINT_ALLOW_CONFIRM"] = "1"
    if args.no_cache:  # the lint workers read these (server/jobs.py: worker_cache)
        os.environ["URDFLINT_NO_CACHE"] = "1"
    if args.cache_dir is not None:
        os.environ["URDFLINT_CACHE_DIR"] = str(args.cache_dir.resolve())
    try:
        Limits.from_env()
    except LimitError as exc:
        raise UsageError(str(exc)) from None
    uvicorn.run(
        "urdflint.server.app:app",
        host=args.host,
        port=args.port,
        workers=args.workers,
        log_level=args.log_level,
        timeout_keep_alive=5,
        timeout_graceful_shutdown=10,
    )
    return EXIT_OK
