"""Dataset records: one JSON object per line and per checked file (``--format jsonl``).

A record says everything the run found about one file, and enough to trust it later:

- ``path`` (as shown), ``hash`` (the BLAKE2b-128 digest of the file's bytes) and
  ``settings`` (a digest of the file's settings, the run's context and urdflint's code
  version): ``--resume`` reuses a record only when all three still match, and every
  ``inputs`` entry (each file, folder and variable the check read: xacro includes,
  meshes, ``package.xml``) is as recorded;
- ``summary`` (counts by severity), ``links``, ``joints``, ``mass``, ``model``;
- ``matrix``: what each target does with the model (the ``--matrix`` rows, predicted, and
  confirmed by the engine with ``--confirm``), and ``engines``: each ``--confirm`` engine's
  outcome (``loads``, ``loads with changes``, ``refused``, ``crashes``, ``not-installed``);
- ``findings``: the v1 JSON finding objects (lossless: :func:`finding` reads them back);
- ``ran``, ``skipped``, ``targets``, ``crashed``, ``error``: the rest of what the report of
  the run needs (an ``error`` is a file that could not be read: no findings).

Lines are written as files finish; a run that is stopped leaves at most its last line cut,
which :func:`read` ignores. ``urdflint report`` and ``--resume`` read them back.
"""

from __future__ import annotations

import json
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import IO, Any

from urdflint.model.finding import Call, Finding, Severity

FORMAT = 1  # the "record" key: the version of this layout


def record(outcome: Any, *, hash: str | None, settings: str, tool: str) -> dict[str, Any]:
    """The record of one file's :class:`urdflint.cli.parallel.Outcome`."""
    findings = [f.to_dict() for f in outcome.findings]
    summary = {"error": 0, "warning": 0, "info": 0}
    for f in outcome.findings:
        summary[str(f.severity)] += 1
    model = outcome.model if isinstance(outcome.model, dict) else None
    return {
        "record": FORMAT,
        "path": outcome.shown,
        "hash": hash,
        "settings": settings,
        "tool": tool,
        "error": outcome.error,
        "crashed": outcome.crashed,
        "summary": summary,
        "links": outcome.links,
        "joints": outcome.joints,
        "mass": model.get("mass") if model else None,
        "engines": engines(outcome.findings, outcome.engines),
        "matrix": outcome.matrix,
        "targets": outcome.targets,
        "model": model,
        "ran": list(outcome.ran),
        "skipped": {code: list(m) for code, m in outcome.skipped.items()},
        "findings": findings,
        "inputs": outcome.inputs,
    }


def engines(findings: Sequence[Finding], names: Sequence[str]) -> dict[str, str]:
    """What each ``--confirm`` engine did with the model (the E findings)."""
    if not names:
        return {}
    from urdflint.engine import matrix

    found = list(findings)
    return {name: matrix.confirm(found, name)["outcome"] for name in names}


def dumps(data: dict[str, Any]) -> str:
    """One record as one line (compact; numbers from numpy written as plain numbers)."""
    return json.dumps(data, separators=(",", ":"), ensure_ascii=False, default=_plain) + "\n"


def _plain(value: Any) -> Any:
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return value.tolist()
    if isinstance(value, (set, frozenset, tuple)):
        return list(value)
    raise TypeError(f"not JSON: {type(value).__name__}")


class Unreadable(Exception):
    """A results file that is not urdflint records (the message says why, one line)."""


def read(path: Path) -> tuple[list[dict[str, Any]], int]:
    """The records of a results file, and the length in bytes of its complete lines (a run
    that was stopped may have cut its last line: it is left out, and a resumed run
    writes from there). Raises :class:`Unreadable` for a file that is not records."""
    found: list[dict[str, Any]] = []
    good = 0
    for item, end in scan(path):
        if item is not None:
            found.append(item)
        good = end
    return found, good


def each(path: Path) -> Iterator[dict[str, Any]]:
    """The records of a results file one at a time (memory stays flat over a large one)."""
    for item, _ in scan(path):
        if item is not None:
            yield item


def scan(path: Path) -> Iterator[tuple[dict[str, Any] | None, int]]:
    """Each record (``None`` for a blank line) with the byte offset where its line ends; a
    cut last line (no newline, not JSON) ends the scan."""
    try:
        handle = path.open("rb")
    except OSError as exc:
        raise Unreadable(f"{path}: cannot read: {exc.strerror or exc}") from None
    with handle:
        end = 0
        for number, raw in enumerate(handle, 1):
            end += len(raw)
            if not raw.strip():
                yield None, end
                continue
            try:
                item = json.loads(raw)
            except ValueError:
                if not raw.endswith(b"\n"):  # cut by a stop: the lines before it are whole
                    return
                raise Unreadable(f"{path}:{number}: not a JSON line") from None
            if not isinstance(item, dict) or item.get("record") != FORMAT or "path" not in item:
                raise Unreadable(
                    f"{path}:{number}: not an urdflint record (write one with --format jsonl)"
                )
            yield item, end


def iterate(paths: Sequence[Path]) -> Iterator[dict[str, Any]]:
    """The records of several files in turn, the last record of a path winning."""
    latest: dict[str, dict[str, Any]] = {}
    for path in paths:
        for item in each(path):
            latest.pop(item["path"], None)
            latest[item["path"]] = item
    yield from latest.values()


def append_to(path: Path) -> IO[str]:
    """``path`` opened for more records: after its last complete line (a cut line is
    dropped), created when missing."""
    length = 0
    if path.exists():
        _, length = read(path)
    handle = open(path, "a+", encoding="utf-8")  # noqa: SIM115 (the caller closes it)
    handle.truncate(length)
    handle.seek(length)
    if length and not path.read_bytes()[:length].endswith(b"\n"):
        handle.write("\n")
    return handle


# -- reading findings and outcomes back ----------------------------------------------------


def finding(data: dict[str, Any]) -> Finding:
    """The :class:`Finding` of a v1 JSON finding object (``to_dict``'s inverse)."""
    from urdflint.model.effects import Consequence, Effect

    effects = tuple(
        (
            target,
            Effect(
                Consequence.parse(e["consequence"]),
                e.get("detail", ""),
                Severity.parse(e["severity"]) if e.get("severity") else None,
            ),
        )
        for target, e in (data.get("effects") or {}).items()
    )
    trace = tuple(Call(c["macro"], c["path"], c["line"], c["column"]) for c in data["trace"])
    return Finding(
        data["path"],
        data["line"],
        data["column"],
        data["code"],
        data["name"],
        Severity.parse(data["severity"]),
        data["message"],
        data["element"],
        data.get("fix"),
        trace,
        effects,
        data.get("engine"),
        _autofix(data.get("autofix")),
    )


def _autofix(data: dict[str, Any] | None) -> Any:
    if data is None:
        return None
    from urdflint.model.edits import Autofix, Edit

    edits = tuple(
        Edit(
            e["path"],
            e["offsets"][0],
            e["offsets"][1],
            e["content"],
            e["start"]["line"],
            e["start"]["column"],
            e["end"]["line"],
            e["end"]["column"],
            bool(e.get("create", False)),
        )
        for e in data["edits"]
    )
    return Autofix(data["applicability"], data["description"], edits, data.get("unavailable"))
