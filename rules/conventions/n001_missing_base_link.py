"""The robot has no `base_link` on its root body.

## What it does
Runs with `profile = "mobile"`, `"humanoid"` or `"industrial"` (and never without a
profile). Reports the root link when no link named `base_link` (or `base_link` behind
a prefix such as `robot_` or `${prefix}`) is the root link, is welded to it by fixed
joints, or hangs directly below that rigid root body (a `world` anchor's child).

## Why is this bad?
REP 105 (section "base_link") names the frame rigidly attached to a mobile base
`base_link`; REP 120 (section "base_link") keeps that name for the root body of a
humanoid (the waist is recommended), and the REP 199 draft (section "base_link") for
the base of an industrial arm, where it starts the kinematic chain. Navigation,
localization, MoveIt and robot_localization configurations default to `base_link`;
a model whose base is called `pelvis` or `link_0` needs every one of them
reconfigured, and a `base_link` deep in the tree (an arm's base on a differently
named mobile base) is not the frame those tools expect.

On industrial arms the finding is informational: REP 199 is still a draft.

## How to fix
Rename the root body `base_link`, or add a massless `base_link` frame welded to it by
a fixed joint (`<joint type="fixed">` with the root as parent).
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.rules.conventions.common import BASE_LINK_REP, EVERY, INDUSTRIAL, active, root_body

from urdflint.engine.registry import Hit, rule
from urdflint.model.conventions import named
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q


@rule(
    "N001",
    "missing-base-link",
    Severity.WARNING,
    fix="Name the root body 'base_link', or weld a 'base_link' frame to it with a fixed joint.",
)
def check(doc: Document) -> Iterator[Hit]:
    profile = active(doc, *EVERY)
    root = doc.graph.root
    if profile is None or root is None:
        return
    body = root_body(doc)
    near = set(body) | {child for name in body for child in doc.graph.children(name)}
    if any(named(name, "base_link") for name in near):
        return
    rep = BASE_LINK_REP[profile]
    if "base_link" in doc.link_map:
        message = (
            f"{rep} expects 'base_link' on the robot's root body; here 'base_link' is not "
            f"rigidly attached to the root link {q(root)}"
        )
    else:
        message = (
            f"{rep} expects the robot's root body to be 'base_link' or to carry it on a "
            f"fixed joint; the root link {q(root)} has none"
        )
    severity = Severity.INFO if profile == INDUSTRIAL else None
    yield Hit(doc.link_map[root].element, message, severity=severity)
