"""The MCP server over stdio (the official ``mcp`` SDK, 2.x, its low-level ``Server``).

Only this module imports the SDK, and only in its functions: the package imports without
the ``mcp`` extra. Each tool call that reads files asks the client for its roots first
(``roots/list``; a client without any gets ``--root``, else the working directory), then runs
the tool (:mod:`urdflint.mcp.tools`) in a worker thread, so the connection keeps answering.
A tool that cannot answer returns an error result (``isError``) with one line.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from urdflint import __version__
from urdflint.mcp import catalogue, schemas, tools
from urdflint.mcp.roots import Refused, Roots


def serve(folders: Sequence[Path] = ()) -> int:
    """Serve MCP on stdin/stdout until the client closes the connection; ``folders``: the
    roots for a client that lists none (default: the working directory)."""
    import anyio

    anyio.run(_serve, Roots.of(folders) if folders else Roots.here())
    return 0


async def _serve(fallback: Roots) -> None:
    from mcp.server.stdio import stdio_server

    server = build(fallback)
    async with stdio_server() as (read, write):
        await server.run(read, write, server.create_initialization_options())


def build(fallback: Roots | None = None) -> Any:
    """The server with its handlers (``mcp.server.lowlevel.Server``)."""
    from mcp.server.lowlevel import Server

    return Server(
        "urdflint",
        version=__version__,
        title="urdflint: robot description linter",
        instructions=schemas.INSTRUCTIONS,
        on_list_tools=_list_tools,
        on_call_tool=functools.partial(_call_tool, fallback=fallback or Roots.here()),
        on_list_resources=_list_resources,
        on_list_resource_templates=_list_templates,
        on_read_resource=_read_resource,
    )


async def _list_tools(ctx: Any, params: Any) -> Any:
    from mcp import types

    return types.ListToolsResult(tools=[types.Tool.model_validate(t) for t in schemas.TOOLS])


async def _call_tool(ctx: Any, params: Any, fallback: Roots) -> Any:
    import anyio
    from mcp import types

    try:
        roots = await client_roots(ctx, fallback) if tools.needs_roots(params.name) else None
        work = functools.partial(tools.call, params.name, params.arguments or {}, roots)
        reply = await anyio.to_thread.run_sync(work)
    except Refused as exc:
        text = " ".join(str(exc).split()) or "refused"
        return types.CallToolResult(content=[types.TextContent(text=text)], is_error=True)
    return types.CallToolResult(
        content=[types.TextContent(text=reply.text)], structured_content=reply.data
    )


async def client_roots(ctx: Any, fallback: Roots) -> Roots:
    """The client's roots (``roots/list``), or ``fallback`` when it has none."""
    from mcp.shared.exceptions import MCPDeprecationWarning

    capabilities = ctx.session.client_capabilities
    if capabilities is None or capabilities.roots is None:
        return fallback
    try:
        with warnings.catch_warnings():  # roots are deprecated in MCP 2026-07-28, not gone
            warnings.simplefilter("ignore", MCPDeprecationWarning)
            listed = await ctx.session.list_roots()
    except Exception as exc:
        raise Refused(f"the client did not list its roots: {exc}") from None
    uris = [str(root.uri) for root in listed.roots]
    return Roots.from_uris(uris) if uris else fallback


async def _list_resources(ctx: Any, params: Any) -> Any:
    from mcp import types

    found = [types.Resource.model_validate(r) for r in catalogue.RESOURCES]
    return types.ListResourcesResult(resources=found)


async def _list_templates(ctx: Any, params: Any) -> Any:
    from mcp import types

    found = [types.ResourceTemplate.model_validate(t) for t in catalogue.TEMPLATES]
    return types.ListResourceTemplatesResult(resource_templates=found)


async def _read_resource(ctx: Any, params: Any) -> Any:
    from mcp import types
    from mcp.shared.exceptions import MCPError

    uri = str(params.uri)
    try:
        text, mime = catalogue.read(uri)
    except Refused as exc:
        raise MCPError(types.INVALID_PARAMS, str(exc)) from None
    found = types.TextResourceContents(uri=uri, mime_type=mime, text=text)
    return types.ReadResourceResult(contents=[found])
