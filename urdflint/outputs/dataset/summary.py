"""The summary of a dataset run: the ``--format jsonl`` records aggregated as plain dicts.

:func:`load` reads one or more results files (the shards of one run: the last record of a
path wins), :func:`summarize` counts them: the files by status, the findings by severity
and by rule, the load matrix per target (predicted, and confirmed per engine with
``--confirm``, with their agreement), the worst assets and the distributions of mass, link
count and findings per file. Every value read from a record is checked before it is used:
a field that is missing or of the wrong type counts as absent, never as a crash.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from urdflint.model import targets as T
from urdflint.outputs import records
from urdflint.outputs.dataset.histogram import describe

OUTCOMES = ("loads", "changes", "refused", "crashes")  # urdflint.model.effects.Outcome.key
NOT_INSTALLED = "not-installed"  # urdflint.engine.matrix.NOT_INSTALLED
BLOCKING = ("refused", "crashes")
SEVERITIES = ("error", "warning", "info")
ALIASES = {"loads with changes": "changes", "crash": "crashes", "refuses": "refused"}
TOP_CODES = 5
SUMMARY = 1  # the "report" key: the version of this layout


@dataclass
class File:
    """What the summary needs of one record (typed: a bad field is absent)."""

    path: str
    hash: str | None = None
    error: str | None = None
    crashed: bool = False
    counts: dict[str, int] = field(default_factory=dict)
    links: int | None = None
    joints: int | None = None
    mass: float | None = None
    predicted: dict[str, str] = field(default_factory=dict)  # target -> outcome key
    labels: dict[str, str] = field(default_factory=dict)  # target -> label
    confirmed: dict[str, str] = field(default_factory=dict)  # engine -> outcome key
    rows: list[dict[str, Any]] = field(default_factory=list)
    findings: list[dict[str, Any]] = field(default_factory=list)

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    @property
    def blocked(self) -> list[str]:
        """The targets that refuse the model or crash on it (predicted)."""
        return [t for t, o in self.predicted.items() if o in BLOCKING]


def load(paths: Sequence[Path]) -> list[dict[str, Any]]:
    """The records of ``paths``, the last record of a path winning (``records.iterate``).
    Raises :class:`records.Unreadable` for a file that is not records (one that has text
    but not one whole record is not)."""
    latest: dict[str, dict[str, Any]] = {}
    for path in paths:
        count = 0
        for item in records.each(path):  # one at a time, slimmed as read
            if not isinstance(item["path"], str):
                raise records.Unreadable(f"{path}: a record whose path is not a string")
            latest.pop(item["path"], None)
            latest[item["path"]] = slim(item)
            count += 1
        if not count and _has_text(path):
            raise records.Unreadable(
                f"{path}: not an urdflint record (write one with --format jsonl)"
            )
    return list(latest.values())


KEPT = ("path", "line", "column", "code", "name", "severity", "message", "element", "engine")


def slim(item: dict[str, Any]) -> dict[str, Any]:
    """A record without what no report reads (inputs, rules run, traces, fixes, effects,
    the deciding findings' details): a large run's records stay small in memory."""
    kept = {k: v for k, v in item.items() if k not in ("inputs", "ran", "skipped", "targets")}
    found = item.get("findings")
    if isinstance(found, list):
        kept["findings"] = [
            {k: f.get(k) for k in KEPT} if isinstance(f, dict) else f for f in found
        ]
    rows = item.get("matrix")
    if isinstance(rows, list):
        kept["matrix"] = [_slim_row(r) for r in rows]
    return kept


def _slim_row(row: Any) -> Any:
    predicted = row.get("predicted") if isinstance(row, dict) else None
    if not isinstance(predicted, dict) or not isinstance(predicted.get("findings"), list):
        return row
    deciding = [
        {"consequence": d.get("consequence")} if isinstance(d, dict) else d
        for d in predicted["findings"]
    ]
    return {**row, "predicted": {**predicted, "findings": deciding}}


def _has_text(path: Path) -> bool:
    try:
        return bool(path.read_bytes().strip())
    except OSError:
        return False


def outcome_key(value: Any) -> str | None:
    """An outcome as one of :data:`OUTCOMES` or ``not-installed`` (None: not one)."""
    if not isinstance(value, str):
        return None
    value = ALIASES.get(value, value)
    return value if value in OUTCOMES or value == NOT_INSTALLED else None


def _int(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _number(value: Any) -> float | None:
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    return None


def _list(value: Any) -> list[Any]:
    return value if isinstance(value, list) else []


def _text(value: Any) -> str | None:
    return value if isinstance(value, str) else None


def normalize(record: dict[str, Any]) -> File:
    """The :class:`File` of one record."""
    found = File(str(record.get("path")), _text(record.get("hash")), _text(record.get("error")))
    found.crashed = record.get("crashed") is True
    found.findings = [f for f in _list(record.get("findings")) if isinstance(f, dict)]
    found.counts = _counts(record.get("summary"), found.findings)
    found.links, found.joints = _int(record.get("links")), _int(record.get("joints"))
    found.mass = _number(record.get("mass"))
    for row in _list(record.get("matrix")):
        if not isinstance(row, dict) or not isinstance(row.get("target"), str):
            continue
        predicted = row.get("predicted")
        key = outcome_key(predicted.get("outcome") if isinstance(predicted, dict) else None)
        if key in OUTCOMES:
            found.predicted[row["target"]] = key
            found.labels[row["target"]] = _text(row.get("label")) or row["target"]
            found.rows.append(row)
        confirmed = row.get("confirmed")
        if isinstance(confirmed, dict) and isinstance(confirmed.get("engine"), str):
            done = outcome_key(confirmed.get("outcome"))
            if done is not None:
                found.confirmed[confirmed["engine"]] = done
    engines = record.get("engines")
    for engine, value in engines.items() if isinstance(engines, dict) else ():
        done = outcome_key(value)
        if done is not None:
            found.confirmed[str(engine)] = done
    return found


def _counts(summary: Any, findings: list[dict[str, Any]]) -> dict[str, int]:
    if isinstance(summary, dict) and all(_int(summary.get(s)) is not None for s in SEVERITIES):
        return {s: int(summary[s]) for s in SEVERITIES}
    counted = Counter(f.get("severity") for f in findings)
    return {s: counted.get(s, 0) for s in SEVERITIES}


def summarize(items: Iterable[dict[str, Any]], *, top: int = 20) -> dict[str, Any]:
    """The summary of a run's records (see the module's docstring)."""
    items = list(items)
    files = [normalize(r) for r in items]
    readable = [f for f in files if f.error is None]
    return {
        "report": SUMMARY,
        "files": len(files),
        "status": status(files),
        "unreadable": [{"path": f.path, "error": f.error} for f in files if f.error is not None],
        "crashed": [f.path for f in files if f.crashed],
        "severities": severities(readable),
        "rules": rules(readable),
        "matrix": matrix(readable),
        "worst": worst(readable, top),
        "distributions": {
            "mass": describe((f.mass for f in readable), unit="kg"),
            "links": describe((f.links for f in readable), integer=True),
            "findings": describe((f.total for f in readable), integer=True),
        },
        "tools": sorted({str(r["tool"]) for r in items if r.get("tool")}),
    }


def status(files: list[File]) -> dict[str, int]:
    """Files by their worst finding (each file once), the unreadable apart; ``crashed``
    counts the files a rule crashed on (they are counted by their findings too)."""
    found = {"errors": 0, "warnings": 0, "infos": 0, "clean": 0, "unreadable": 0, "crashed": 0}
    for f in files:
        found["crashed"] += f.crashed
        if f.error is not None:
            found["unreadable"] += 1
        elif f.counts.get("error"):
            found["errors"] += 1
        elif f.counts.get("warning"):
            found["warnings"] += 1
        elif f.counts.get("info"):
            found["infos"] += 1
        else:
            found["clean"] += 1
    return found


def severities(files: list[File]) -> list[dict[str, Any]]:
    """Findings and files per severity, most frequent first."""
    found = [
        {
            "severity": s,
            "findings": sum(f.counts.get(s, 0) for f in files),
            "files": sum(1 for f in files if f.counts.get(s, 0)),
        }
        for s in SEVERITIES
    ]
    return sorted(found, key=lambda x: (-x["findings"], SEVERITIES.index(x["severity"])))


def rules(files: list[File]) -> list[dict[str, Any]]:
    """Per rule code: its name, worst severity, findings and files, most frequent first."""
    table: dict[str, dict[str, Any]] = {}
    for f in files:
        for code in {str(x.get("code")) for x in f.findings}:
            table.setdefault(code, _rule(code))["files"] += 1
        for x in f.findings:
            entry = table[str(x.get("code"))]
            entry["findings"] += 1
            entry["name"] = entry["name"] or _text(x.get("name")) or ""
            entry["severity"] = _worse(entry["severity"], x.get("severity"))
    return sorted(table.values(), key=lambda r: (-r["findings"], -r["files"], r["code"]))


def _rule(code: str) -> dict[str, Any]:
    return {"code": code, "name": "", "severity": "info", "findings": 0, "files": 0}


def _worse(a: str, b: Any) -> str:
    if b not in SEVERITIES:
        return a
    return a if SEVERITIES.index(a) <= SEVERITIES.index(b) else str(b)


def target_order(names: Iterable[str]) -> list[str]:
    """Targets in the canonical order (:data:`urdflint.model.targets.TARGETS`), unknown
    ones after them by name."""
    names = set(names)
    return [*T.ordered(tuple(names)), *sorted(names - set(T.TARGETS))]


def matrix(files: list[File]) -> dict[str, Any]:
    """Per target, how many files load, load with changes, are refused or crash
    (predicted); per engine, what ``--confirm`` saw; and where both exist, whether they
    agree."""
    labels: dict[str, str] = {}
    for f in files:
        labels.update(f.labels)
    rows = []
    for target in target_order(labels):
        counted = Counter(f.predicted[target] for f in files if target in f.predicted)
        rows.append(
            {
                "target": target,
                "label": T.LABELS.get(target, labels[target]),
                "files": sum(counted.values()),
                **{o: counted[o] for o in OUTCOMES},
            }
        )
    modelled = [f for f in files if f.predicted]
    return {
        "targets": rows,
        "modelled": len(modelled),
        "everywhere": sum(all(o == "loads" for o in f.predicted.values()) for f in modelled),
        "engines": engines(files),
        "agreement": agreement(files),
    }


def engines(files: list[File]) -> list[dict[str, Any]]:
    """Per ``--confirm`` engine: the files it loaded, changed, refused, crashed on, or
    could not run (not installed)."""
    known = [e for e in dict.fromkeys(T.ENGINE.values()) if e]
    names = {e for f in files for e in f.confirmed}
    found = []
    for engine in [*(e for e in known if e in names), *sorted(names - set(known))]:
        counted = Counter(f.confirmed[engine] for f in files if engine in f.confirmed)
        found.append(
            {
                "engine": engine,
                "files": sum(counted.values()),
                **{o: counted[o] for o in (*OUTCOMES, NOT_INSTALLED)},
            }
        )
    return found


def agreement(files: list[File]) -> list[dict[str, Any]]:
    """Per target with confirmed rows: how often the prediction (the effects an engine
    can show, :func:`urdflint.engine.matrix.measurable`) matches what the engine did."""
    table: dict[str, dict[str, Any]] = {}
    for f in files:
        for row in f.rows:
            confirmed = row.get("confirmed")
            done = outcome_key(confirmed.get("outcome")) if isinstance(confirmed, dict) else None
            if done not in OUTCOMES:
                continue
            target = row["target"]
            entry = table.setdefault(
                target,
                {
                    "target": target,
                    "label": f.labels[target],
                    "engine": str(confirmed.get("engine")),
                    "compared": 0,
                    "agree": 0,
                    "pairs": Counter(),
                },
            )
            said = _measurable(row, f.predicted[target])
            entry["compared"] += 1
            entry["agree"] += said == done
            if said != done:
                entry["pairs"][(said, done)] += 1
    found = []
    for target in target_order(table):
        entry = table[target]
        pairs = sorted(entry.pop("pairs").items(), key=lambda p: (-p[1], p[0]))
        entry["disagreements"] = [
            {"predicted": p, "confirmed": c, "files": n} for (p, c), n in pairs
        ]
        found.append(entry)
    return found


def _measurable(row: dict[str, Any], predicted: str) -> str:
    from urdflint.engine import matrix as M

    try:
        return str(M.measurable(row))
    except (KeyError, TypeError, AttributeError):  # a row not written by this urdflint
        return predicted


def worst(files: list[File], top: int) -> list[dict[str, Any]]:
    """The ``top`` files with the most refusing or crashing targets, then errors, then
    warnings (files with none of them are not listed)."""
    bad = [f for f in files if f.blocked or f.counts.get("error") or f.counts.get("warning")]
    bad.sort(
        key=lambda f: (
            -len(f.blocked),
            -f.counts.get("error", 0),
            -f.counts.get("warning", 0),
            f.path,
        )
    )
    return [_asset(f) for f in bad[: max(top, 0)]]


def _asset(f: File) -> dict[str, Any]:
    codes = Counter(str(x.get("code")) for x in f.findings)
    severity: dict[str, str] = {}
    for x in f.findings:
        code = str(x.get("code"))
        severity[code] = _worse(severity.get(code, "info"), x.get("severity"))
    ranked = sorted(codes.items(), key=lambda c: (SEVERITIES.index(severity[c[0]]), -c[1], c[0]))
    return {
        "path": f.path,
        "blocked": len(f.blocked),
        "refused": [t for t in target_order(f.predicted) if f.predicted[t] == "refused"],
        "crashes": [t for t in target_order(f.predicted) if f.predicted[t] == "crashes"],
        "errors": f.counts.get("error", 0),
        "warnings": f.counts.get("warning", 0),
        "infos": f.counts.get("info", 0),
        "crashed": f.crashed,
        "codes": [{"code": c, "severity": severity[c], "count": n} for c, n in ranked[:TOP_CODES]],
        "outcomes": {t: f.predicted[t] for t in target_order(f.predicted)},
    }
