"""The "base" section of ``urdflint info --statics``: :func:`summary` gives the support
polygon, the centre of mass over it (margin, tipping angle), the sampled configuration
nearest to tipping and the reach as plain data, :func:`text` its lines
(``stability.summary`` and ``stability.summary_text``, which the statics section calls)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from urdflint.model.values import fmt

if TYPE_CHECKING:
    from urdflint.engine.stability import Stability, Stance
    from urdflint.engine.stability_sampling import Reach
    from urdflint.model.document import Document


def _p(values: list[float]) -> str:
    return "(" + ", ".join(fmt(round(v, 4) + 0.0) for v in values) + ")"


def _q(values: dict[str, float]) -> str:
    shown = [f"{n}={fmt(round(v, 3))}" for n, v in values.items() if round(v, 3) != 0.0]
    return ", ".join(shown) if shown else "every joint at 0"


def _n(count: int, word: str) -> str:
    return f"{count} {word}" + ("" if count == 1 else "s")


def _line(label: str, stance: dict[str, Any]) -> str:
    margin = stance["margin_mm"]
    where = "inside, nearest edge" if margin >= 0 else "OUTSIDE, towards"
    tilt = stance["tipping_angle_deg"]
    angle = f", tipping angle {fmt(tilt)}°" if tilt is not None else ""
    return (
        f"  {label:<9} com {_p(stance['com'])} m, margin {fmt(margin)} mm ({where} "
        f"{stance['direction']}){angle}"
    )


def text(data: dict[str, Any]) -> list[str]:
    """The lines of the base section (after its title)."""
    lines = []
    support = data["support"]
    if not data["mobile"]:
        lines.append(f"  not mobile: {data['reason']}")
    elif support is None or support["kind"] == "none":
        lines.append(f"  not judged: {data['reason']}")
    else:
        source = "configured" if data["contacts_from"] == "configuration" else "found"
        lines.append(f"  contacts  {', '.join(support['contact_links'])} ({source})")
        lines.append(
            f"  support   {support['kind']} {', '.join(_p(p) for p in support['polygon'])} m, "
            f"ground at z = {fmt(support['ground'])} m (root link '{data['root']}' frame)"
        )
        if data["reason"]:
            lines.append(f"  not judged: {data['reason']}")
    for key, label in (("zero", "zero pose"), ("given", "--q")):
        if data[key] is not None:
            lines.append(_line(label, data[key]))
    worst = data["worst"]
    if worst is not None:
        lines.append(_line("worst", worst))
        lines.append(
            f"            at {_q(worst['q'])} ({_n(worst['configurations'], 'configuration')} "
            f"of {_n(worst['joints'], 'joint')}, seed {data['seed']})"
        )
    reach = data["reach"]
    if reach is not None:
        lines.append(
            f"  reach     {fmt(reach['max_distance'])} m from the root link's origin "
            f"('{reach['link']}' at {_q(reach['q'])}); {_n(len(reach['links']), 'end link')}, "
            f"{_n(reach['configurations'], 'configuration')}"
        )
        bounds = reach["bounds"]
        lines.append(f"  workspace {_p(bounds['lower'])} to {_p(bounds['upper'])} m")
    return lines


# -- the data -------------------------------------------------------------------------------


def _r(value: float, digits: int = 6) -> float:
    return round(value, digits) + 0.0


def _stance(stance: Stance | None) -> dict[str, Any] | None:
    if stance is None:
        return None
    tilt = stance.tilt
    return {
        "q": {n: _r(v) for n, v in stance.values.items() if v != 0.0},
        "com": [_r(c) for c in stance.com],
        "margin_mm": _r(stance.margin * 1000, 1),
        "tipping_angle_deg": None if tilt is None else _r(tilt, 2),
        "direction": stance.direction,
        "com_height": _r(stance.height),
    }


def summary(doc: Document, found: Stability, reached: Reach | None) -> dict[str, Any]:
    """The base's stability (``found``, sampled) and the arms' reach as plain data. Lengths
    in metres in the root link's frame, margins in mm (positive: inside), angles in degrees."""
    from urdflint.engine.stability_sampling import SEED

    support = None
    if found.support is not None:
        s = found.support
        support = {
            "kind": s.kind,
            "polygon": [[_r(x), _r(y)] for x, y in s.polygon],
            "ground": _r(s.ground),
            "contact_links": list(s.links),
            "lifted_mm": {n: _r(h * 1000, 1) for n, h in s.lifted.items()},
            "below_mm": {n: _r(h * 1000, 1) for n, h in s.below.items()},
        }
    candidates = found.candidates
    worst = _stance(found.worst)
    if worst is not None:
        worst.update(configurations=found.evaluated, joints=len(found.joints))
    return {
        "root": doc.physics.root,
        "mobile": found.mobile,
        "reason": found.reason,
        "contacts_from": None
        if candidates is None
        else ("configuration" if candidates.configured else "heuristic"),
        "candidates": dict(candidates.links) if candidates else {},
        "support": support,
        "zero": _stance(found.zero),
        "given": _stance(found.given),
        "worst": worst,
        "seed": SEED,
        "reach": _reach(reached),
    }


def _reach(found: Reach | None) -> dict[str, Any] | None:
    if found is None:
        return None
    return {
        "configurations": found.samples,
        "links": found.links,
        "max_distance": _r(found.distance),
        "link": found.link,
        "q": {n: _r(v) for n, v in found.values.items() if v != 0.0},
        "bounds": {"lower": [_r(v) for v in found.lower], "upper": [_r(v) for v in found.upper]},
    }
