"""The web pages (``server/static``) and the headers that protect every answer.

Each page is a static HTML file served under a strict Content-Security-Policy (it loads
nothing from other hosts, runs no inline script, and this makes sure it never can), so
every page works offline:

``GET /``               the check page (``index.html``, ``app.js``)
``GET /rules``          the rule catalogue as a table (``rules.html``, ``rules.js``, which
                        reads ``/v1/rules``)
``GET /rules/{code}``   one rule and its documentation (the same page, reading
                        ``/v1/rules/{code}``; 404 for an unknown rule)
``GET /docs``           Swagger UI on ``/openapi.json``, from the copy in
                        ``static/swagger-ui`` (``docs.html``, ``docs.js``); FastAPI's own
                        ``/docs`` and ``/redoc`` load theirs from a CDN, so they are off

``/static`` serves the rest, revalidated on every load so a new release's ``app.js`` wins.
Without the folder, each page answers a one-line pointer to ``/openapi.json``.
:class:`SecurityHeaders` adds a few headers to every response.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

from fastapi import APIRouter, FastAPI, Request
from fastapi.responses import FileResponse, PlainTextResponse, Response

from urdflint.engine import registry

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


def _page(name: str, status: int = 200) -> Response:
    """``static/<name>`` under :data:`PAGE_HEADERS`, or a pointer to the API description."""
    page = STATIC / name
    if page.is_file():
        return FileResponse(page, status, media_type="text/html", headers=PAGE_HEADERS)
    return PlainTextResponse("urdflint service: the API is described at /openapi.json\n", status)


@router.get("/", include_in_schema=False)
async def index() -> Response:
    """The check page."""
    return _page("index.html")


@router.get("/rules", include_in_schema=False)
async def rules_page() -> Response:
    """The rule catalogue, as a table."""
    return _page("rules.html")


@router.get("/rules/{code}", include_in_schema=False)
async def rule_page(code: str) -> Response:
    """One rule and its documentation (404 when there is no such rule)."""
    return _page("rules.html", 200 if registry.lookup(code) is not None else 404)


@router.get("/docs", include_in_schema=False)
async def docs_page() -> Response:
    """Swagger UI on ``/openapi.json``, from the copy this server ships."""
    return _page("docs.html")


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
