"""The compatibility matrix: what each target will do with one model, and why.

One row per target, every target (:func:`every_target`), the selected ones marked: the
matrix is a display, so asking for it never changes which targets the findings and the
exit code are for. The prediction is the worst effect the model's findings have
on that target (:mod:`urdflint.model.effects`): it loads, loads with changes, is refused or
crashes the consumer. With ``--confirm``, the row also says what the target's engine did
when it loaded the model (the E findings): the two side by side are the check on the
prediction.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace
from typing import Any

from urdflint.model import targets as T
from urdflint.model.effects import MEASURABLE, Consequence, Effect, Outcome
from urdflint.model.finding import Finding, Severity

# E rule -> what it shows the engine did
CONFIRMS: dict[str, Outcome] = {
    "E001": Outcome.REFUSED,
    "E002": Outcome.CHANGES,
    "E003": Outcome.CHANGES,
    "E004": Outcome.CHANGES,
    "E005": Outcome.CRASHES,
}
NOT_INSTALLED = "not-installed"  # E007: the engine is not installed here


def every_target(
    findings: Sequence[Finding], settings: Any, relint: Callable[[Any], Sequence[Finding]]
) -> list[dict[str, Any]]:
    """Every target's row for one model linted with ``settings`` (its ``findings``).

    A selected target's row comes from those findings, the ones reported. The others come
    from ``relint(wider)``: the same model linted again with every target and without the
    engines (``--confirm``'s findings are the first run's); those findings are only used
    here, never reported. Each row says whether its target is ``selected``.
    """
    selected = set(settings.targets)
    others = [t for t in T.TARGETS if t not in selected]
    found = rows(findings, tuple(selected), settings.confirm)
    if others:
        wider = replace(settings, targets=tuple(T.TARGETS), confirm=())
        more = [*relint(wider), *(f for f in findings if f.engine)]
        found += rows(more, tuple(others), settings.confirm)
    order = {t: n for n, t in enumerate(T.ordered(tuple(T.TARGETS)))}
    found.sort(key=lambda row: order[row["target"]])
    for row in found:
        row["selected"] = row["target"] in selected
    return found


def rows(
    findings: Iterable[Finding], targets: Sequence[str], engines: Sequence[str]
) -> list[dict[str, Any]]:
    """The matrix of one model: ``targets`` selected, ``engines`` named by ``--confirm``."""
    findings = list(findings)
    return [_row(findings, target, engines) for target in T.ordered(tuple(targets))]


def _row(findings: list[Finding], target: str, engines: Sequence[str]) -> dict[str, Any]:
    outcome, deciding = predict(findings, target)
    engine = T.ENGINE[target]
    row: dict[str, Any] = {
        "target": target,
        "label": T.LABELS[target],
        "basis": "engine" if engine else "source and documentation",
        "predicted": {"outcome": outcome.key, "findings": deciding},
        "confirmed": None,
    }
    if engine is not None and engine in engines:
        row["confirmed"] = confirm(findings, engine)
    return row


def predict(findings: list[Finding], target: str) -> tuple[Outcome, list[dict[str, Any]]]:
    """The worst outcome the findings' effects have on ``target``, and the findings that
    decide it (those with an effect of that outcome; for a model that loads, those that
    load only with a warning or silently wrong)."""
    effects = [(f, e) for f in findings for t, e in f.effects if t == target]
    worst = max((outcome(e) for _, e in effects), default=Outcome.LOADS)
    deciding = [
        {
            "code": f.code,
            "path": f.path,
            "line": f.line,
            "element": f.element,
            "consequence": e.consequence.key,
            "detail": e.detail,
        }
        for f, e in effects
        if outcome(e) is worst
    ]
    return worst, deciding


def outcome(effect: Effect) -> Outcome:
    """The effect's outcome; one of info severity (a tag ignored that changes nothing that
    matters, like KDL dropping the root's inertia) leaves the model loading."""
    if effect.level is Severity.INFO:
        return min(effect.consequence.outcome, Outcome.LOADS)
    return effect.consequence.outcome


def confirm(findings: list[Finding], engine: str) -> dict[str, Any]:
    """What ``engine`` did: the worst of its E findings (none: it loaded the model)."""
    mine = [f for f in findings if f.engine == engine]
    if any(f.code == "E007" for f in mine):  # the engine is not installed here
        return {"engine": engine, "outcome": NOT_INSTALLED, "findings": []}
    worst = max((CONFIRMS[f.code] for f in mine if f.code in CONFIRMS), default=Outcome.LOADS)
    shown = [
        {"code": f.code, "path": f.path, "line": f.line, "message": f.message}
        for f in mine
        if CONFIRMS.get(f.code) is worst
    ]
    return {"engine": engine, "outcome": worst.key, "findings": shown}


def measurable(row: dict[str, Any]) -> str:
    """The predicted outcome counting only the effects an engine's load can show (refusals,
    crashes, dropped links, unlimited joints, substituted inertias): what ``--confirm`` is
    compared with."""
    keys = {c.key: c for c in Consequence}
    found = [
        keys[d["consequence"]].outcome
        for d in row["predicted"]["findings"]
        if keys[d["consequence"]] in MEASURABLE
    ]
    return max(found, default=Outcome.LOADS).key
