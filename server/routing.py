"""What the route modules share: the error answer and the app's limits and worker pool.

``create_app`` (``app.py``) keeps the limits and the pool in ``app.state``; the routes,
defined once at module level, reach them through the request.
"""

from __future__ import annotations

from typing import cast

from fastapi import Request
from fastapi.responses import JSONResponse

from . import options as opts
from .limits import Limits
from .pool import Pool


def error(status: int, detail: str, headers: dict[str, str] | None = None) -> JSONResponse:
    """An error answer: ``{"detail": ...}`` with ``status`` (and ``headers``)."""
    return JSONResponse({"detail": detail}, status_code=status, headers=headers)


async def option_error(request: Request, exc: opts.OptionError) -> JSONResponse:
    """A bad option is a 422 with the reason (the app's ``OptionError`` handler)."""
    return error(422, str(exc))


def limits_of(request: Request) -> Limits:
    """The limits of the app that received ``request``."""
    return cast(Limits, request.app.state.limits)


def pool_of(request: Request) -> Pool:
    """The worker pool of the app that received ``request``."""
    return cast(Pool, request.app.state.pool)
