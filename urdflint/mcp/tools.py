"""What each tool answers: a short text for the agent and, for the model tools, structured
content (the JSON ``urdflint`` prints with ``--format json``).

Plain Python (no MCP types), called by :mod:`urdflint.mcp.server` in a worker thread, one
call at a time: the linter keeps per-process state (xacro's globals, the fixes' file cache).
A call either answers or raises :class:`Refused` with one line, the tool's error; anything
else that escapes the linter becomes one line too, never a traceback.
"""

from __future__ import annotations

import json
import logging
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from urdflint.mcp import runs
from urdflint.mcp.roots import Refused, Roots

log = logging.getLogger("urdflint.mcp")
MAX_TEXT_LINES = 60  # of the findings in the text of check: the structured content has all
_LOCK = threading.Lock()
SPOKEN = (  # the CLI's options in its notes, as this server's
    ("urdflint fix --unsafe-fixes", "the fix tool with unsafe=true"),
    ("urdflint fix", "the fix tool"),
    ("--unsafe-fixes", "unsafe=true"),
    ("--show-info lists them", "every finding is in findings"),
    ("--target chooses", "the targets option chooses"),
)


@dataclass(frozen=True)
class Reply:
    """A tool's answer: text for the agent, and the structured content (or ``None``)."""

    text: str
    data: dict[str, Any] | None = None


def needs_roots(name: str) -> bool:
    """Whether the tool reads files (the server asks the client for its roots first)."""
    return name in ("check", "fix", "info", "matrix")


def call(name: str, arguments: Mapping[str, Any], roots: Roots | None) -> Reply:
    """Run tool ``name``; :class:`Refused` (one line) when it cannot answer."""
    from urdflint.engine import fixes

    chosen = TOOLS.get(name)
    if chosen is None:
        raise Refused(f"unknown tool {name!r} (tools: {', '.join(TOOLS)})")
    with _LOCK:
        try:
            return chosen(arguments, roots or Roots.here())
        except Refused:
            raise
        except Exception as exc:  # the linter reports bad input as findings; this is a bug
            log.exception("urdflint mcp: %s failed", name)
            first = (str(exc).strip().splitlines() or [""])[0]
            raise Refused(f"internal error in {name}: {type(exc).__name__}: {first}") from None
        finally:
            fixes.forget_files()  # the next call reads the files as they are then


# -- check, matrix ---------------------------------------------------------------------------


def check(arguments: Mapping[str, Any], roots: Roots) -> Reply:
    """The findings of ``urdflint check --format json``, and the CLI's text, shortened."""
    run = _checked(runs.request(arguments, roots))
    data = runs.envelope(run)
    if run.errors:
        data["errors"] = run.errors
    return Reply("\n".join([*summary(run), *_errors(run)]), data)


def matrix(arguments: Mapping[str, Any], roots: Roots) -> Reply:
    """What each target does with the model: ``urdflint check --matrix``'s rows."""
    from urdflint.outputs import matrix_text

    run = _checked(runs.request(arguments, roots), matrix=True)
    data: dict[str, Any] = {"matrix": run.matrix, "targets": run.targets}
    if run.errors:
        data["errors"] = run.errors
    lines = [line.replace(" (--matrix)", "") for line in matrix_text.table(run.matrix)]
    return Reply("\n".join([*lines, *_errors(run)]), data)


def _checked(req: runs.Request, matrix: bool = False) -> runs.Run:
    run = runs.check(req, matrix)
    if not run.checked:
        raise Refused("; ".join(run.errors) or "no *.urdf or *.xacro files found")
    return run


def summary(run: runs.Run) -> list[str]:
    """The CLI's text output: the findings (at most :data:`MAX_TEXT_LINES`), then the notes
    and the summary line, its options named as this server's."""
    from urdflint.outputs.formatters import text

    shown = runs.info(run)
    lines = text.render(run.findings, shown).splitlines()
    count = len(text.listed(run.findings, shown)[0])
    body, tail = lines[:count], lines[count:]
    if len(body) > MAX_TEXT_LINES:
        left = len(body) - MAX_TEXT_LINES
        body = [*body[:MAX_TEXT_LINES], f"… {left} more: every finding is in findings"]
    for cli, here in SPOKEN:
        tail = [line.replace(cli, here) for line in tail]
    return [*body, *tail]


def _errors(run: runs.Run) -> list[str]:
    return [f"error: {message}" for message in run.errors]


# -- explain ---------------------------------------------------------------------------------


def explain(arguments: Mapping[str, Any], roots: Roots) -> Reply:
    """``urdflint explain CODE [--long]``."""
    from urdflint.engine import docs, registry

    key = arguments.get("rule")
    if not isinstance(key, str) or not key.strip():
        raise Refused("rule: give a rule code or name, e.g. J009 or inverted-limits")
    found = registry.lookup(key.strip())
    if found is None:
        raise Refused(f"unknown rule {key!r} (the urdflint://rules resource lists them)")
    return Reply(docs.page(found) if arguments.get("long") else docs.short_page(found))


# -- info ------------------------------------------------------------------------------------


def info(arguments: Mapping[str, Any], roots: Roots) -> Reply:
    """``urdflint info --format json [--statics]``: the tree, masses, COM; the text too."""
    from urdflint.engine import linter
    from urdflint.outputs import info as shown

    if isinstance(arguments.get("paths"), list):
        raise Refused("info takes one model: path (or text and name)")
    req = runs.request(arguments, roots, command="info")
    place = req.places[0]
    if not req.is_text and not place.path.is_file():
        raise Refused(f"{place.shown}: not a file")
    settings = req.finder.for_folder(place.path.parent)
    try:
        doc = linter.load(Path(place.shown), place.shown, settings, req.context(place.root))
    except OSError as exc:
        raise Refused(f"{place.shown}: cannot read: {exc.strerror or exc}") from None
    rendered, _built = shown.render(doc, "json", statics=bool(arguments.get("statics")))
    data = json.loads(rendered)
    return Reply(shown.text(data).rstrip("\n"), data)


# -- fix -------------------------------------------------------------------------------------


def fix(arguments: Mapping[str, Any], roots: Roots) -> Reply:
    from urdflint.mcp import fixing

    return Reply(*fixing.fix(arguments, roots))


TOOLS: dict[str, Callable[[Mapping[str, Any], Roots], Reply]] = {
    "check": check,
    "fix": fix,
    "explain": explain,
    "info": info,
    "matrix": matrix,
}
