"""The web page (``server/static``) and the headers that protect every answer.

``GET /`` serves ``static/index.html`` under a strict Content-Security-Policy (the page
loads nothing from other hosts, and this makes sure it never can); ``/static`` serves the
rest, revalidated on every load so a new release's ``app.js`` wins. Without the folder,
``/`` answers a one-line pointer to ``/docs``. :class:`SecurityHeaders` adds a few headers
to every response.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

from fastapi import APIRouter, FastAPI, Request
from fastapi.responses import FileResponse, PlainTextResponse, Response

STATIC = Path(__file__).resolve().parent / "static"
SECURITY_HEADERS = (
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
    (b"x-frame-options", b"DENY"),
)
# The page loads nothing from other hosts; this policy makes sure it never can.
PAGE_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; "
    "img-src 'self' data:; connect-src 'self'; base-uri 'none'; form-action 'self'; "
    "frame-ancestors 'none'",
    "Cache-Control": "no-cache",
}

router = APIRouter()


class SecurityHeaders:
    """A few response headers every answer carries (pure ASGI, cheap)."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def sending(message: Any) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = [*message.get("headers", ()), *SECURITY_HEADERS]
            await send(message)

        await self.app(scope, receive, sending)


@router.get("/", include_in_schema=False)
async def index() -> Response:
    """The web page, or a pointer to the API documentation when there is none."""
    page = STATIC / "index.html"
    if page.is_file():
        return FileResponse(page, media_type="text/html", headers=PAGE_HEADERS)
    return PlainTextResponse("urdflint service: see /docs for the API\n")


def mount_static(app: FastAPI) -> None:
    """Serve ``/static`` (when the folder exists), revalidated on every load."""
    if STATIC.is_dir():
        from fastapi.staticfiles import StaticFiles

        app.mount("/static", StaticFiles(directory=STATIC), name="static")
        app.middleware("http")(revalidate_static)


async def revalidate_static(
    request: Request, call_next: Callable[[Request], Awaitable[Response]]
) -> Response:
    """``Cache-Control: no-cache`` on ``/static/`` answers: a new release's app.js wins."""
    response: Response = await call_next(request)
    if request.url.path.startswith("/static/"):
        response.headers["Cache-Control"] = "no-cache"  # a new release's app.js wins
    return response
