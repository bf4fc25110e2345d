"""A humanoid's wrist, gripper, ankle, sole or toe frame is not named as REP 120 names it.

## What it does
Runs with `profile = "humanoid"` (and never without a profile). For each frame REP 120
defines on both sides (`l_wrist`/`r_wrist`, `l_gripper`/`r_gripper`,
`l_ankle`/`r_ankle`, `l_sole`/`r_sole`, `l_toe`/`r_toe`), reports a link spelt
otherwise (`left_sole`, `leftSole`, `L_sole_link`, `sole_l`, ...) when no link carries
the REP 120 name. A robot without a left arm is not reported for lacking `l_wrist`:
only a differently spelt frame is.

## Why is this bad?
REP 120 (sections "l_wrist and r_wrist" to "l_toe and r_toe") fixes these names so
that walking controllers, whole-body planners and teleoperation tools find the feet and
hands of any humanoid without configuration. `l_sole` in particular is the frame
whose (X,Y) plane is the foot's contact surface, used for support polygons and
footstep planning. A model that calls it `left_sole_link` needs every such tool
remapped, and a model that mixes `l_` and `left_` on its two sides is a common source
of one-sided bugs.

## How to fix
Rename the link to the REP 120 name, or add a massless frame with that name on a fixed
joint at the same place (`<link name="l_sole"/>` welded to `left_sole_link`).
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from urdflint.rules.conventions.common import HUMANOID, active

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q

FRAMES = ("wrist", "gripper", "ankle", "sole", "toe")
SIDES = {"l": ("l", "left"), "r": ("r", "right")}
SIDE_WORD = {"l": "left", "r": "right"}


def _pattern(side: str, frame: str) -> re.Pattern[str]:
    words = "|".join(SIDES[side])
    tail = r"(?:_?link|_?frame)?"
    return re.compile(rf"^(?:(?:{words})_?{frame}{tail}|{frame}_(?:{words}){tail})$", re.I)


PATTERNS = {(side, frame): _pattern(side, frame) for side in SIDES for frame in FRAMES}


@rule(
    "N008",
    "humanoid-frame-name",
    Severity.INFO,
    fix="Rename the link to its REP 120 name, or weld a frame of that name to it.",
)
def check(doc: Document) -> Iterator[Hit]:
    if active(doc, HUMANOID) is None:
        return
    for (side, frame), pattern in PATTERNS.items():
        expected = f"{side}_{frame}"
        if expected in doc.link_map:
            continue
        found = next((link for link in doc.links if link.name and pattern.match(link.name)), None)
        if found is None:
            continue
        yield Hit(
            found.element,
            f"REP 120 names the {SIDE_WORD[side]} {frame} frame {q(expected)}; "
            f"this robot calls it {q(found.name)}",
        )
