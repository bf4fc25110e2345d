"""What ``POST /v1/check`` adds to its JSON answer when asked: ``svg`` (the kinematic tree),
``scene`` (the robot in 3D) and ``statics`` (the gravity loads, the base's stability).

Each is built in the worker from the document the check has just linted, inside the job's
fence and time limit, and never costs the findings: one that fails is left out of the
answer and logged. Strings are scrubbed like the rest of the answer (``jobs.Scrub``: the
server's folders never show).

``statics`` is what ``urdflint info --statics --format json`` puts under ``statics``
(:func:`urdflint.outputs.statics_info.collect`): per actuated joint the largest gravity
torque and where, the effort and the margin; the weakest joint; the payload it allows; and
for a mobile base (the ``base`` section) the support polygon, the centre of mass over it,
the margin, the tipping angle and the reach. The Pinocchio model the D rules built and the
loads D001 searched are reused (one build per request); the search is capped (a fixed
number of samples, no search past 200 degrees of freedom), and its time counts against the
job's ``URDFLINT_TIMEOUT`` like the rest. Numbers JSON cannot carry (``inf``, ``nan``)
become ``null``.
"""

from __future__ import annotations

import contextlib
import logging
import math
import traceback
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .jobs import CheckJob, Scrub

log = logging.getLogger("urdflint.server.worker")


def added(job: CheckJob, doc: Any, findings: list[Any], scrub: Scrub) -> dict[str, Any]:
    """The entries the job asked for (``svg``, ``scene``, ``statics``), each keyed by the
    upload's name; those that cannot be built are left out."""
    found: dict[str, Any] = {}
    if doc is None:
        return found
    root = Path(job.folder) / "files"
    builders = (
        ("svg", job.svg, lambda: svg(doc, findings)),
        ("scene", job.scene, lambda: scene(doc, findings, root, scrub)),
        ("statics", job.statics, lambda: statics(doc, root, scrub)),
    )
    for key, wanted, build in builders:
        value = build() if wanted else None
        if value is not None:
            found[key] = {job.name: value}
    return found


def svg(doc: Any, findings: list[Any]) -> str | None:
    """The kinematic tree as SVG, or ``None`` when it cannot be drawn."""
    try:
        from urdflint.outputs.svg import render_tree  # type: ignore[attr-defined,unused-ignore]
    except ImportError:
        return None
    try:
        return str(render_tree(doc, findings))
    except Exception:  # a picture must never cost the findings
        log.warning("the kinematic tree picture failed:\n%s", traceback.format_exc())
        return None


def scene(doc: Any, findings: list[Any], root: Path, scrub: Scrub) -> dict[str, Any] | None:
    """The robot as a 3D scene (meshes read inside ``root`` only; why one is missing told
    without the server's folders), or ``None``."""
    try:
        from urdflint.outputs.scene import build_scene  # type: ignore[attr-defined,unused-ignore]
    except ImportError:
        return None
    try:
        with contextlib.chdir(root):
            found = build_scene(doc, findings)
    except Exception:  # a picture must never cost the findings
        log.warning("the 3D scene failed:\n%s", traceback.format_exc())
        return None
    if found is not None:  # the meshes' base64 holds no text worth scrubbing
        found.update({key: scrub.value(found[key]) for key in ("links", "joints", "notes")})
    return found  # type: ignore[no-any-return]


def statics(doc: Any, root: Path, scrub: Scrub) -> dict[str, Any] | None:
    """``doc``'s statics as ``info --statics`` gives them, or ``None`` when the file is not
    a model (``info`` gives none either) or the computation failed."""
    if not doc.ok:
        return None
    try:
        from urdflint.outputs import statics_info
    except ImportError:  # pragma: no cover - a build without the statics
        return None
    try:
        with contextlib.chdir(root):  # a contact link's mesh is found as the lint found it
            data = statics_info.collect(doc)
    except Exception:  # the statics must never cost the findings
        log.warning("the statics failed:\n%s", traceback.format_exc())
        return None
    return finite(scrub.value(data))  # type: ignore[no-any-return]


def finite(value: Any) -> Any:
    """``value`` with every ``inf`` and ``nan`` replaced by ``None`` (JSON has neither)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {key: finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(item) for item in value]
    return value
