"""``urdflint info --statics``: every joint's largest gravity load, its effort and margin.

:func:`collect` gives plain JSON-able data, :func:`text` the table. One row per revolute,
continuous and prismatic joint that is not a mimic follower: the largest torque (N·m) or
force (N) gravity puts on it over its limits and where (the joint values that decide it,
the others at 0), the analytic bound no configuration exceeds, its effort limit, the
margin (effort / needed) and *proven* when the bound itself is within the effort. Then
the weakest joint, and the payload it allows at the tool link at full reach
(:mod:`urdflint.engine.statics_payload`).

:data:`EXTRA_SECTIONS` is where other analyses add their sections (the base's stability and
reach): each is a module with ``summary(doc)`` returning JSON-able data or ``None``, used
when the module exists; its text is ``summary_text(data)`` (a list of lines) when the
module has one, else the mapping as ``key  value`` lines.
"""

from __future__ import annotations

import importlib
import math
from typing import TYPE_CHECKING, Any

from urdflint.model.values import fmt

if TYPE_CHECKING:
    from urdflint.model.document import Document

# (section name, module with summary(doc)): shown after the joints when the module exists
EXTRA_SECTIONS: tuple[tuple[str, str], ...] = (("base", "urdflint.engine.stability"),)


WHERE_SHOWN = 4  # joint values in the text table's where column (JSON: all)


def collect(doc: Document) -> dict[str, Any]:
    """The ``statics`` entry of ``info --format json``."""
    from urdflint.engine import statics as S
    from urdflint.engine.statics_payload import allowed

    found = S.of(doc)
    settings = found.settings
    data: dict[str, Any] = {
        "computed": found.ok,
        "problem": None if found.ok else found.reason,
        "frame": found.root,
        "gravity": list(settings.gravity),
        "payload": {"mass": settings.payload, "link": found.tool} if settings.payload else None,
        "unknown_link": found.unknown_link,
        "joints": [],
        "weakest": None,
        "allowed_payload": None,
        "sections": _sections(doc),
    }
    if not found.ok:
        return data
    data["joints"] = [_row(found.load(name)) for name in found.joints]
    data["weakest"] = _weakest(data["joints"])
    extra = allowed(doc, found)
    if extra is not None:
        data["allowed_payload"] = {
            "mass": extra.mass if math.isfinite(extra.mass) else None,
            "link": extra.link,
            "joint": extra.joint,
            "already_exceeded": extra.already,
            "default_link": settings.payload_link is None,
        }
    data["samples"] = len(found.samples[0]) if found.samples is not None else 0
    data["seconds"] = round(found.seconds, 4)
    return data


def _float(value: Any) -> float | None:
    """A plain float for JSON (numpy's scalars are not serialisable), ``None`` kept."""
    return None if value is None else float(value)


def _row(load: Any) -> dict[str, Any]:
    margin = load.margin
    return {
        "name": load.name,
        "type": load.kind,
        "unit": load.unit,
        "needed": _float(load.needed),
        "at": {name: float(value) for name, value in load.at.items()},
        "bound": _float(load.bound),
        "effort": _float(load.effort),
        "margin": float(margin) if margin is not None and math.isfinite(margin) else None,
        "proven": bool(load.proven),
        "passive": bool(load.passive),
    }


def _weakest(rows: list[dict[str, Any]]) -> dict[str, Any] | None:
    judged = [r for r in rows if r["margin"] is not None and not r["passive"]]
    if not judged:
        return None
    worst = min(judged, key=lambda r: (r["margin"], r["name"]))
    return {"joint": worst["name"], "margin": worst["margin"]}


def _sections(doc: Document) -> list[dict[str, Any]]:
    """The :data:`EXTRA_SECTIONS` whose module exists and has something to say."""
    found = []
    for name, module in EXTRA_SECTIONS:
        try:
            summary = getattr(importlib.import_module(module), "summary", None)
        except ImportError:
            continue
        data = summary(doc) if summary is not None else None
        if data is not None:
            found.append({"name": name, "module": module, "data": data})
    return found


# -- text ------------------------------------------------------------------------------------


def text(data: dict[str, Any]) -> list[str]:
    """The lines of the statics section."""
    lines = ["", _head(data)]
    if not data["computed"]:
        lines.append(f"not computed: {data['problem']}")
        return lines + _section_lines(data)
    if data["unknown_link"]:
        lines.append(f"error: the payload link '{data['unknown_link']}' is not a link of the model")
    rows = [_cells(r) for r in data["joints"]]
    heads = ("joint", "type", "needs", "bound", "effort", "margin", "where")
    widths = [max([len(h), *(len(r[i]) for r in rows)]) for i, h in enumerate(heads[:-1])]
    for cells in [heads, *rows]:
        padded = [c.ljust(w) for c, w in zip(cells[:-1], widths, strict=True)]
        lines.append("  ".join([*padded, cells[-1]]).rstrip())
    lines.append(_weakest_line(data))
    lines.append(_payload_line(data))
    return lines + _section_lines(data)


def _head(data: dict[str, Any]) -> str:
    gravity = " ".join(fmt(g + 0.0) for g in data["gravity"])
    payload = data["payload"]
    load = f"{fmt(payload['mass'])} kg at '{payload['link']}'" if payload else "no payload"
    return (
        f"statics (Pinocchio; root link '{data['frame']}' fixed, gravity {gravity} m/s² "
        f"in its frame, {load})"
    )


def _cells(row: dict[str, Any]) -> tuple[str, ...]:
    unit = row["unit"]
    effort = f"{fmt(row['effort'])} {unit}" if row["effort"] else "-"
    if row["passive"]:
        margin = "passive"
    elif row["margin"] is None:
        margin = "-" if not row["effort"] else "inf"
    else:
        margin = f"{row['margin']:.3g}"
    if row["proven"] and not row["passive"]:
        margin += " proven"
    at = list(row["at"].items())
    where = ", ".join(f"{k}={fmt(v)}" for k, v in at[:WHERE_SHOWN])
    if len(at) > WHERE_SHOWN:  # a hand's fingers: --format json lists every one
        where += f", … {len(at) - WHERE_SHOWN} more"
    return (
        row["name"],
        row["type"],
        f"{row['needed']:.3g} {unit}",
        f"{row['bound']:.3g} {unit}",
        effort,
        margin,
        where or ("-" if not row["needed"] else "any configuration"),
    )


def _weakest_line(data: dict[str, Any]) -> str:
    weakest = data["weakest"]
    if weakest is None:
        return "weakest  none: no actuated joint has an effort limit and a load"
    row = next(r for r in data["joints"] if r["name"] == weakest["joint"])
    verdict = "cannot hold (D001)" if weakest["margin"] < 1 else "holds"
    return (
        f"weakest  {weakest['joint']}: margin {weakest['margin']:.3g}, "
        f"{fmt(row['effort'])} {row['unit']} for {row['needed']:.3g} {row['unit']}: {verdict}"
    )


def _payload_line(data: dict[str, Any]) -> str:
    found = data["allowed_payload"]
    if found is None:
        return "payload  not computed: no actuated joint with an effort limit carries a tool link"
    where = f"'{found['link']}'" + (" (end of the longest chain)" if found["default_link"] else "")
    more = " more" if data["payload"] else ""
    if found["already_exceeded"]:
        return f"payload  none at {where}: {found['joint']} cannot hold the robot itself"
    if found["mass"] is None:
        return f"payload  gravity sets no limit at {where}: no joint that carries it lifts it"
    return (
        f"payload  the weakest joint allows {found['mass']:.3g} kg{more} at {where} at full "
        f"reach ({found['joint']} reaches its effort limit)"
    )


def _section_lines(data: dict[str, Any]) -> list[str]:
    lines = []
    for section in data["sections"]:
        lines += ["", section["name"]]
        body = section["data"]
        own = getattr(importlib.import_module(section["module"]), "summary_text", None)
        if own is not None:
            lines += list(own(body))
        elif isinstance(body, dict):
            lines += [f"  {key}  {_value(value)}" for key, value in body.items()]
        else:
            lines.append(f"  {_value(body)}")
    return lines


def _value(value: Any) -> str:
    if isinstance(value, float):
        return fmt(value)
    if isinstance(value, list | tuple):
        return " ".join(_value(v) for v in value)
    return str(value)
