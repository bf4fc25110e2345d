"""An element URDF allows once is repeated: MuJoCo refuses the model, the others read the first.

## What it does
Reports each later copy of an element URDF allows once in its place: a link's
`<inertial>`; an inertial's `<origin>`, `<mass>` and `<inertia>`; a joint's `<origin>`,
`<parent>`, `<child>`, `<axis>`, `<limit>`, `<dynamics>`, `<mimic>`, `<calibration>` and
`<safety_controller>`; a visual's `<origin>`, `<geometry>` and `<material>`; a collision's
`<origin>` and `<geometry>`; a material's `<color>` and `<texture>`. The finding is on the
second (or third...) copy; the message gives the line of the first (in xacro, the file,
line and macro call of each) and says whether the two copies are identical. A link may
have several `<visual>` and `<collision>` elements: those are not repeats. Two shapes in
one `<geometry>` are C003's, elements URDF does not define at that place X007's; J002, J003
and J006 speak of the first `<calibration>`, `<safety_controller>` or `<axis>` only.

## Why is this bad?
The file says two things and each consumer picks one, without a word. Observed on a
robot with each element written twice, the copies different (a mass of 1 then 5 kg, a
range of ±1 then ±2 rad, an axis z then x, a damping of 0.1 then 0.7, a parent `arm`
then `base`...):
- MuJoCo 4.0 refuses the model: `XML Error: repeated element: 'inertial'` (the tag named
  is the repeated one: `'mass'`, `'origin'`, `'limit'`, `'color'`...; the line it gives
  is the first copy's), identical copies included. It does not read a joint's
  `<calibration>` and `<safety_controller>` or a `<texture>`, and it discards visuals, so
  it loads a visual with two `<origin>` or `<geometry>`, unless `<mujoco><compiler
  discardvisual="false"/>` keeps them. A visual's `<material>` and its `<color>` it reads
  either way.
- urdfdom reads the first copy and ignores the later ones (`check_urdf` 3.0.1 builds the
  tree from the first `<parent>`), and so do sdformat 12.3 (Gazebo: the converted SDF has
  the first mass, pose, axis, limits, damping, geometry and colour), Pinocchio 4.1 (first
  mass, placement, axis, limits, damping, mimic, visual), PyBullet 3.2.7
  (`getDynamicsInfo`, `getJointInfo`, `getVisualShapeData` give the first values) and
  Drake 1.51 (first mass, pose, axis, limits, damping, geometry, colour, and the first
  mimic's gear ratio in simulation). Isaac Sim's importer reads the first too
  (`FirstChildElement`, from its source). ROS (robot_state_publisher, KDL, MoveIt) gets
  urdfdom's first copy.

So a robot that loads in ROS and Gazebo cannot be loaded in MuJoCo at all, and what ROS
and Gazebo simulate is the first copy, which is often the stale one: Trifinger's
`fingerpro.urdf` gave `finger_tip_link` a placeholder `<inertial>` (0.031 kg) and then its
CAD values (0.0092 kg); every simulator but MuJoCo used the placeholder, and the upstream
fix kept the CAD values.

## How to fix
Keep one copy: the one whose values are right. `urdflint fix --unsafe-fixes` deletes the
later copies, which keeps what urdfdom, ROS, Gazebo, Pinocchio, PyBullet and Drake use
today and lets MuJoCo load the model; it is unsafe because the later copy may be the one
the author meant (as in Trifinger): check it first, and delete the first copy instead if
so. It is safe when the copies are identical. Merging them is not offered: two
`<inertial>` are not two bodies to add up, nor two `<limit>` a range to combine; a merge
would build a model that no consumer simulates today and that the author did not write.
In xacro, the copy is deleted where it is written (the macro, when both copies come from
the same macro call); a copy written in another macro, which other links may call too, is
left to you.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document, children
from urdflint.model.edits import RemoveElement, Repair
from urdflint.model.effects import Effect, ignored, kept, refused
from urdflint.model.finding import Severity
from urdflint.model.schema import describe, visits
from urdflint.model.structure import written_at
from urdflint.model.targets import GAZEBO

# spec key of the parent -> the children URDF reads once there
ONCE: dict[str, tuple[str, ...]] = {
    "link": ("inertial",),
    "inertial": ("origin", "mass", "inertia"),
    "joint": (
        *("origin", "parent", "child", "axis", "limit", "dynamics"),
        *("calibration", "mimic", "safety_controller"),
    ),
    "visual": ("origin", "geometry", "material"),
    "collision": ("origin", "geometry"),
    "material": ("color", "texture"),
}
# what MuJoCo never looks up (a visual's origin and geometry: only with discardvisual false)
MUJOCO_UNREAD = frozenset({"calibration", "safety_controller", "texture"})
VISUAL_ONLY = frozenset({"origin", "geometry"})  # of a <visual>: discarded by MuJoCo
# consumers that ignore the element itself (J002, J003, J017 say so): a copy changes nothing
NOT_READ: dict[str, frozenset[str]] = {
    "calibration": frozenset({*GAZEBO, "mujoco", "drake", "pybullet", "isaac", "pinocchio"}),
    "safety_controller": frozenset({*GAZEBO, "mujoco", "drake", "pybullet", "isaac", "pinocchio"}),
    "mimic": frozenset({*GAZEBO, "pybullet"}),
}
ORDINALS = ("first", "second", "third", "fourth")
W, INFO = Severity.WARNING, Severity.INFO

FIRST = "reads only the first copy and silently ignores the later one"
READERS: dict[str, str] = {
    "gazebo-classic": f"sdformat's URDF parser (urdfdom) {FIRST}",
    "gz-sim": f"sdformat's URDF parser (urdfdom) {FIRST}",
    "drake": f"Drake {FIRST}",
    "pybullet": f"PyBullet {FIRST}",
    "isaac": f"the importer (FirstChildElement) {FIRST}",
    "pinocchio": f"urdfdom {FIRST}",
    "ros": f"urdfdom {FIRST}; robot_state_publisher, KDL and MoveIt use that first copy",
}
DIFFERENT: dict[str, Effect] = {t: ignored(text, W) for t, text in READERS.items()}
SAME: dict[str, Effect] = {t: kept("the copies are identical", INFO) for t in READERS}
MUJOCO = refused("\"XML Error: repeated element: '...'\" (the repeated tag)")
VISUALS_DISCARDED = ignored(
    'visuals are discarded (discardvisual defaults to true); with discardvisual="false" '
    "MuJoCo refuses the model",
    INFO,
)
EFFECTS = {
    "": {**DIFFERENT, "mujoco": MUJOCO},
    "identical": {**SAME, "mujoco": MUJOCO},
    "visual": {**DIFFERENT, "mujoco": VISUALS_DISCARDED},
    "unread": {"ros": ignored(READERS["ros"], W)},  # calibration, safety_controller
}


@rule(
    "X015",
    "repeated-element",
    Severity.WARNING,
    fix="Keep one copy, the one with the right values; delete the others.",
    effects=EFFECTS,
    by_target=True,
    fixable="unsafe",
)
def check(doc: Document) -> Iterator[Hit]:
    visuals = _mujoco_keeps_visuals(doc)
    for visit in visits(doc.robot):
        for tag in ONCE.get(visit.key or "", ()):
            copies = children(visit.element, tag)
            for n, later in enumerate(copies[1:], start=1):
                yield _hit(doc, copies[0], later, n, visuals)


def _hit(doc: Document, first: etree._Element, later: etree._Element, n: int, visuals: bool) -> Hit:
    tag = str(later.tag)
    same = _canonical(first) == _canonical(later)
    mujoco = _mujoco(later, visuals)
    ordinal = ORDINALS[n] if n < len(ORDINALS) else "another"
    copy = f"an identical {ordinal}" if same else f"a {ordinal}"
    where = written_at(doc, first)
    if mujoco is MUJOCO:
        said = "MuJoCo refuses the model, every other parser reads only the first"
    else:
        said = "URDF parsers read only the first"
    effects = _effects(tag, same, mujoco)
    selected = [t for t in doc.targets if t in effects]
    return Hit(
        later,
        f"{describe(later.getparent())} has {copy} <{tag}> (the first is on {where}): {said}",
        severity=None if selected else INFO,
        variant=_variant(tag, same, mujoco),
        effects=effects,
        repair=_repair(doc, first, later, same),
    )


def _mujoco(el: etree._Element, visuals: bool) -> Effect | None:
    """MuJoCo's effect: refused where it looks the element up, else none (or discarded)."""
    tag, parent = str(el.tag), el.getparent()
    if tag in MUJOCO_UNREAD:
        return None
    if parent is not None and parent.tag == "visual" and tag in VISUAL_ONLY and not visuals:
        return VISUALS_DISCARDED
    return MUJOCO


def _variant(tag: str, same: bool, mujoco: Effect | None) -> str:
    """The variant of the rule's page that the hit is an instance of."""
    if same:
        return "identical"
    if tag in NOT_READ and tag != "mimic":
        return "unread"
    return "visual" if mujoco is VISUALS_DISCARDED else ""


def _effects(tag: str, same: bool, mujoco: Effect | None) -> dict[str, Effect]:
    table: dict[str, Effect] = dict(SAME if same else DIFFERENT)
    for target in NOT_READ.get(tag, ()):
        table.pop(target, None)
    if mujoco is not None:
        table["mujoco"] = mujoco
    return table


def _mujoco_keeps_visuals(doc: Document) -> bool:
    """Whether ``<mujoco><compiler discardvisual="false"/>`` makes MuJoCo read visuals."""
    for compiler in doc.robot.iterfind("mujoco/compiler"):
        value = compiler.get("discardvisual")
        if value is not None:
            return value.strip().lower() in ("false", "0")
    return False


def _canonical(el: etree._Element) -> tuple[object, ...]:
    """The element's content, order of attributes and children aside, numbers as numbers."""
    attrs = frozenset((k, _value(v)) for k, v in el.attrib.items())
    kids = Counter(_canonical(child) for child in children(el))
    return (el.tag, attrs, frozenset(kids.items()))


def _value(text: str) -> object:
    tokens = text.split()
    try:
        return tuple(float(t) for t in tokens)
    except ValueError:
        return " ".join(tokens)


def _repair(doc: Document, first: etree._Element, later: etree._Element, same: bool) -> Repair:
    tag, why = str(later.tag), _elsewhere(doc, first, later)
    if same:
        description = f"delete the identical copy of <{tag}>"
    else:
        description = f"delete the later <{tag}>, keeping the first (the one urdfdom reads)"
    return Repair("safe" if same else "unsafe", description, (RemoveElement(later),), why)


def _elsewhere(doc: Document, first: etree._Element, later: etree._Element) -> str | None:
    """Why deleting the later copy where it is written could change other links or joints:
    it is written in a macro whose calls do not all write the first copy too."""
    if doc.origin is None:
        return None
    mine, theirs = doc.origin(later), doc.origin(first)
    if mine is None or not mine.trace:
        return None  # written once, outside any macro
    outer = theirs.trace[max(0, len(theirs.trace) - len(mine.trace)) :] if theirs else ()
    if outer == mine.trace:
        return None  # the first copy comes from the same macro call (or one inside it)
    return (
        f"the later <{later.tag}> is written in macro `{mine.trace[0].macro}`, which may be "
        "called for other elements too: delete it by hand"
    )
