#!/usr/bin/env python3
"""``urdflint mcp``: an agent-style exchange on a real corpus robot, as a Markdown transcript.

    .venv/bin/python bench/mcp_transcript.py [--robot robotiq_2f_85] [--out FILE]

Copies the corpus robot (``../shared/corpus/robots/ROBOT``, read-only) to a temporary folder,
starts ``python -m urdflint mcp`` there with the SDK's stdio client, the copy as the client's
only root, and records every JSON-RPC message on the wire while the "agent" calls check, fix
(write=false: the edits and the diff), fix (write=true), check again, and explain for what
is left. The messages are pasted trimmed (long lists cut, with what was cut said), then what
remained and why. Writes FILE (default: /work/notes/mcp-transcript.md).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
import tempfile
from collections import Counter
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
KEEP = {"findings": 3, "fixes": 2, "edits": 2}  # list items shown of a long list
TEXT_LINES = 4  # lines shown of a longer text in the JSON (the text follows in full)


async def exchange(folder: Path, arguments: dict[str, Any]) -> tuple[list[Any], dict[str, Any]]:
    """The agent's calls; every message on the wire ``(direction, JSON)``, and the results."""
    import anyio
    from mcp import ClientSession, StdioServerParameters, types
    from mcp.client.stdio import stdio_client

    wire: list[Any] = []

    async def roots(context: Any) -> Any:
        root = types.Root.model_validate({"uri": folder.as_uri(), "name": folder.name})
        return types.ListRootsResult(roots=[root])

    server = StdioServerParameters(
        command=sys.executable, args=["-m", "urdflint", "mcp"], cwd=str(folder)
    )
    results: dict[str, Any] = {}
    async with stdio_client(server) as (read, write), anyio.create_task_group() as tasks:
        to_server, from_client = anyio.create_memory_object_stream[Any](100)
        to_client, from_server = anyio.create_memory_object_stream[Any](100)

        async def up() -> None:
            async for message in from_client:
                wire.append(("client", _json(message)))
                await write.send(message)

        async def down() -> None:
            async for message in read:
                wire.append(("server", _json(message)))
                await to_client.send(message)

        tasks.start_soon(up)
        tasks.start_soon(down)
        async with ClientSession(from_server, to_server, list_roots_callback=roots) as session:
            await session.initialize()
            call = session.call_tool
            results["check"] = await call("check", arguments)
            results["preview"] = await call("fix", arguments)
            results["write"] = await call("fix", {**arguments, "write": True})
            # the agent accepts the estimates for links with no mass at all (a dropped link
            # is worse than a guessed inertia): the unsafe fixes, written
            results["unsafe"] = await call("fix", {**arguments, "write": True, "unsafe": True})
            results["again"] = await call("check", arguments)
            left = results["again"].structured_content["findings"]
            unfixable = [f for f in left if f["autofix"] is None and f["severity"] != "info"]
            if unfixable:  # why the worst finding without a fix is one
                results["explain"] = await call("explain", {"rule": unfixable[0]["code"]})
        tasks.cancel_scope.cancel()
    return wire, results


def _json(message: Any) -> Any:
    if isinstance(message, Exception):
        return {"exception": repr(message)}
    return message.message.model_dump(by_alias=True, mode="json", exclude_none=True)


def trimmed(value: Any, key: str = "") -> Any:
    """``value`` with long lists cut to :data:`KEEP` items, and texts of more than a few lines
    (the text content, a diff) to their first lines: they are shown in full as text."""
    if isinstance(value, dict):
        return {k: trimmed(v, k) for k, v in value.items()}
    if isinstance(value, list):
        keep = KEEP.get(key)
        items = [trimmed(v) for v in value]
        if keep is not None and len(items) > keep:
            rest = value[keep:]
            codes = Counter(v.get("code") for v in rest if isinstance(v, dict) and "code" in v)
            what = ", ".join(f"{c} ×{n}" for c, n in codes.most_common()) if codes else ""
            items = [
                *items[:keep],
                f"… {len(rest)} more {key} cut here{': ' + what if what else ''}",
            ]
        return items
    if key in ("text", "diff") and isinstance(value, str) and value.count("\n") > TEXT_LINES:
        lines = value.splitlines()
        cut = len(lines) - TEXT_LINES
        return "\n".join([*lines[:TEXT_LINES], f"… {cut} more lines cut here (in full below)"])
    return value


def exchanges(wire: list[Any]) -> list[tuple[str, list[Any]]]:
    """Each tool call on the wire: its request, what the server asked the client meanwhile
    (roots/list) and the answers, then the call's result."""
    found: list[tuple[str, list[Any]]] = []
    for index, (side, message) in enumerate(wire):
        if side != "client" or message.get("method") != "tools/call":
            continue
        messages = [(side, message)]
        for later in wire[index + 1 :]:
            asked = later[1].get("method") == "roots/list"
            told = "roots" in later[1].get("result", {})
            if (later[0] == "server" and asked) or (later[0] == "client" and told):
                messages.append(later)
            elif later[0] == "server" and later[1].get("id") == message["id"]:
                messages.append(later)
                break
        found.append((f"tools/call {message['params']['name']}", messages))
    return found


def rendered(title: str, messages: list[Any], seen: set[str]) -> list[str]:
    """One exchange as Markdown: each message as JSON (trimmed), the text content in full."""
    lines = [f"## {title}", ""]
    for side, message in messages:
        arrow = "client → server" if side == "client" else "server → client"
        if message.get("method") == "roots/list" or "roots" in message.get("result", {}):
            if "roots" in seen:  # the same question and answer on every call: shown once
                lines += [f"{arrow}: {'roots/list' if 'method' in message else 'the same roots'}", ""]  # fmt: skip
                continue
            if "result" in message:
                seen.add("roots")
        text = json.dumps(trimmed(message), indent=2, ensure_ascii=False)
        lines += [f"{arrow}:", "", "```json", text, "```", ""]
        for block in message.get("result", {}).get("content", []):
            if block.get("type") == "text" and block["text"].count("\n") > TEXT_LINES:
                lines += ["The text content in full, as the agent reads it:", "", "````text"]
                lines += [block["text"].rstrip("\n"), "````", ""]
    return lines


def markdown(robot: str, wire: list[Any], results: dict[str, Any]) -> str:
    before = results["check"].structured_content
    after = results["again"].structured_content
    preview = results["preview"].structured_content
    fixed = Counter(fix["code"] for fix in preview["fixes"])
    lines = [
        f"# `urdflint mcp` transcript: {robot} from the corpus",
        "",
        "Produced by `bench/mcp_transcript.py` (re-run it to regenerate this file): the SDK's",
        "stdio client (`mcp` " + _sdk() + ") starts `python -m urdflint mcp` in a temporary copy",
        f"of `shared/corpus/robots/{robot}` and lists that copy as its only root. The agent calls",
        "check, fix (write=false), fix (write=true), fix (write=true, unsafe=true), check again,",
        "and explain for what no fix covers. Below, each JSON-RPC",
        "request and its answer as they crossed the wire, trimmed where a list or a text is long",
        "(each cut says what it left out). The copy's path is shown as `$ROOT`.",
        "",
        "## In short",
        "",
        f"- check: {_summary(before)}.",
        f"- fix, write=false: {len(preview['fixes'])} safe fixes ({_counts(fixed)}), "
        f"{preview['unsafe_left']} more with unsafe=true; nothing written.",
        f"- fix, write=true: {results['write'].structured_content['applied']} fixes applied in "
        f"{len(results['write'].structured_content['written'])} file.",
        f"- fix, write=true, unsafe=true: {results['unsafe'].structured_content['applied']} "
        "more fixes applied (the estimated inertias).",
        f"- check again: {_summary(after)}; none of the fixed findings is left "
        f"({', '.join(c for c in fixed if c not in _codes(after)) or 'none'} gone).",
        "",
    ]
    seen: set[str] = set()
    for title, messages in exchanges(wire):
        lines += rendered(title, messages, seen)
    lines += _remaining(after)
    return "\n".join(lines).replace(str(results["folder"]), "$ROOT") + "\n"


def _remaining(after: dict[str, Any]) -> list[str]:
    """What the last check still reports, and why the fix tool left it."""
    lines = [
        "## What remained, and why",
        "",
        "| rule | findings | automatic fix |",
        "|---|---|---|",
    ]
    by_code: dict[str, list[Any]] = {}
    for finding in after["findings"]:
        by_code.setdefault(finding["code"], []).append(finding)
    for code, found in sorted(by_code.items()):
        levels = Counter(f["severity"] for f in found)
        count = ", ".join(f"{level} ×{n}" for level, n in sorted(levels.items()))
        fixes = [f["autofix"] for f in found if f["autofix"] and not f["autofix"].get("unavailable")]  # fmt: skip
        how = "none offered"
        if fixes:
            what = re.sub(r"(<[^>]+>)", r"`\1`", fixes[0]["description"].split(":")[0])
            how = f"{fixes[0]['applicability']} for {len(fixes)} of {len(found)}: {what}"
        lines.append(f"| {code} {found[0]['name']} | {count} | {how} |")
    lines += [
        "",
        "Safe fixes keep the model's meaning: all of them were applied. An unsafe fix changes the",
        "physics (here an `<inertial>` computed from the collision mesh's convex hull at a guessed",
        "density of 1000 kg/m³), so an agent should leave it to a person, or apply it with",
        "unsafe=true only when no real masses exist and an estimate beats a dropped link. A",
        "finding no fix is offered for is a design decision (a mimic range outside the",
        "follower's limits, a missing control plugin): explain gives the reasoning. The infos",
        "are notes on what a simulator does with the model, not defects.",
    ]
    return lines


def _summary(envelope: dict[str, Any]) -> str:
    counts = envelope["summary"]
    return f"{counts['error']} errors, {counts['warning']} warnings, {counts['info']} infos"


def _codes(envelope: dict[str, Any]) -> set[str]:
    return {f["code"] for f in envelope["findings"]}


def _counts(counter: Counter[str]) -> str:
    return ", ".join(f"{code} ×{count}" for code, count in sorted(counter.items()))


def _sdk() -> str:
    from importlib.metadata import version

    return version("mcp")


def main() -> int:
    import anyio

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", default="robotiq_2f_85")
    parser.add_argument("--out", type=Path, default=Path("/work/notes/mcp-transcript.md"))
    args = parser.parse_args()
    source = CORPUS / args.robot
    with tempfile.TemporaryDirectory(prefix="urdflint-mcp-") as temp:
        folder = Path(temp).resolve() / args.robot
        shutil.copytree(source, folder)
        arguments: dict[str, Any] = {"paths": ["model.urdf"]}
        mapping = folder / "package_map.json"
        if mapping.is_file():  # the corpus's package:// folders, relative to the robot
            arguments["package_paths"] = json.loads(mapping.read_text())
        wire, results = anyio.run(exchange, folder, arguments)
        results["folder"] = folder
        text = markdown(args.robot, wire, results)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text, encoding="utf-8")
    print(f"wrote {args.out} ({len(text.splitlines())} lines)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
