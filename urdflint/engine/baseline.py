"""Baselines: record today's findings, then report only new ones (``--baseline FILE``).

An entry is keyed on ``(path, code, element, fingerprint)``; ``path`` is relative to the
baseline file's folder (POSIX), so the file works from any working directory, and the
fingerprint is :meth:`Finding.fingerprint` of the finding with that relative path, so
neither the line nor the message matters: reformatting and moved lines keep matching.
Several findings with one key (two ``X004`` on one element) are one entry with a count.
"""

from __future__ import annotations

import json
import os
from collections import Counter
from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, NamedTuple

from urdflint.engine import registry
from urdflint.model.finding import Finding

VERSION = 1
# Run-level notes, never recorded: they describe the installation, not the model
# (E007 an engine not installed, U001 a crash, U004 a missing extra, U005 the baseline
# itself).
UNRECORDED = frozenset({"E007", "U001", "U004", "U005"})
FIX = "Rewrite the baseline with --write-baseline FILE so it only keeps what still occurs."


class BaselineError(Exception):
    """A baseline file that cannot be read or is not a urdflint baseline."""


class Key(NamedTuple):
    path: str
    code: str
    element: str
    fingerprint: str


def relative(path: str, folder: Path) -> str:
    """``path`` (as shown, relative to the working directory) relative to ``folder``, POSIX."""
    target = Path(path).resolve()
    try:
        return Path(os.path.relpath(target, folder.resolve())).as_posix()
    except ValueError:  # another drive on Windows
        return target.as_posix()


def key(finding: Finding, folder: Path) -> Key:
    rel = relative(finding.path, folder)
    return Key(rel, finding.code, finding.element, replace(finding, path=rel).fingerprint())


def render(findings: Iterable[Finding], folder: Path) -> str:
    """The baseline file's text: sorted entries, so an unchanged run gives identical bytes."""
    counts: Counter[Key] = Counter()
    messages: dict[Key, str] = {}
    for finding in sorted(findings, key=Finding.sort_key):
        if finding.code in UNRECORDED:
            continue
        k = key(finding, folder)
        counts[k] += 1
        messages.setdefault(k, finding.message)
    entries = [{**k._asdict(), "count": counts[k], "message": messages[k]} for k in sorted(counts)]
    data = {"version": VERSION, "tool": "urdflint", "findings": entries}
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def write(path: Path, findings: Iterable[Finding]) -> int:
    """Write the baseline for ``findings``; returns the number of findings recorded."""
    text = render(findings, path.parent)
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise BaselineError(f"baseline {path}: cannot write: {exc.strerror or exc}") from None
    return sum(entry["count"] for entry in json.loads(text)["findings"])


@dataclass
class Baseline:
    """A loaded baseline: how many findings of each key are accepted."""

    path: Path
    counts: dict[Key, int]
    messages: dict[Key, str]

    @property
    def folder(self) -> Path:
        return self.path.parent


def load(path: Path) -> Baseline:
    """Read and validate a baseline file; :class:`BaselineError` with one line otherwise."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise BaselineError(f"baseline {path}: cannot read: {exc.strerror or exc}") from None
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise BaselineError(f"baseline {path}: not valid JSON: {exc}") from None
    if not isinstance(data, dict) or data.get("tool") != "urdflint" or "findings" not in data:
        raise BaselineError(f"baseline {path}: not a urdflint baseline (no tool/findings)")
    if data.get("version") != VERSION:
        raise BaselineError(
            f"baseline {path}: unsupported version {data.get('version')!r} (expected {VERSION})"
        )
    if not isinstance(data["findings"], list):
        raise BaselineError(f"baseline {path}: 'findings' must be a list")
    counts: dict[Key, int] = {}
    messages: dict[Key, str] = {}
    for index, entry in enumerate(data["findings"]):
        k, count, message = _entry(entry, f"baseline {path}: findings[{index}]")
        counts[k] = counts.get(k, 0) + count
        messages.setdefault(k, message)
    return Baseline(path, counts, messages)


def _entry(entry: Any, where: str) -> tuple[Key, int, str]:
    if not isinstance(entry, dict):
        raise BaselineError(f"{where} must be an object")
    fields = []
    for name in Key._fields:
        value = entry.get(name)
        if not isinstance(value, str) or not value:
            raise BaselineError(f"{where}: '{name}' must be a non-empty string")
        fields.append(value)
    count = entry.get("count", 1)
    if not isinstance(count, int) or isinstance(count, bool) or count < 1:
        raise BaselineError(f"{where}: 'count' must be a positive integer")
    message = entry.get("message", "")
    return Key(*fields), count, message if isinstance(message, str) else ""


def apply(
    baseline: Baseline,
    findings: Sequence[Finding],
    ran: Mapping[str, Collection[str]],
) -> tuple[list[Finding], list[Finding]]:
    """``(new findings, U005 stale-entry findings)``.

    A finding whose key still has a count left in the baseline is dropped. An entry is
    stale when its file was checked in this run (``ran``: shown path -> codes that ran
    on it) and its rule ran there, yet fewer findings than recorded occurred.
    """
    left = dict(baseline.counts)
    new: list[Finding] = []
    for finding in findings:
        if finding.code in UNRECORDED:
            new.append(finding)
            continue
        k = key(finding, baseline.folder)
        if left.get(k, 0) > 0:
            left[k] -= 1
        else:
            new.append(finding)
    shown = {relative(path, baseline.folder): path for path in ran}
    rule = registry.RULES["U005"]
    stale: list[Finding] = []
    for k, missing in sorted(left.items()):
        path = shown.get(k.path)
        if missing <= 0 or path is None or k.code not in ran[path] or "U005" not in ran[path]:
            continue
        recorded = baseline.counts[k]
        times = f" ({missing} of {recorded})" if recorded > 1 else ""
        stale.append(
            Finding(
                path,
                1,
                1,
                rule.code,
                rule.name,
                rule.severity,
                f"baseline entry {k.code} at {k.element} no longer occurs{times}",
                k.element,
                FIX,
            )
        )
    return new, stale
