"""What sdformat's URDF converter makes of ``<gazebo>`` blocks (the G rules' tables).

Sources: the "Using a URDF in Gazebo" tutorial (classic.gazebosim.org, tut=ros_urdf),
sdformat.org "SDFormat extensions to URDF" (sdf_tutorials urdf/sdf_extensions.md) and
``ParseSDFExtension`` / ``Insert SDFExtension*`` in gazebosim/sdformat ``src/parser_urdf.cc``.

A ``<gazebo>`` block without ``reference`` extends the SDF ``<model>`` ("robot" scope), one
with ``reference`` extends the link or joint of that name. The converter reads the keys in
:data:`KEYS`; every other child is copied verbatim ("blob") into the SDF element, where
only the SDF elements in :data:`SDF_ELEMENTS` mean anything.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from importlib import resources

from lxml import etree

from urdflint.model.document import Document, Joint, children
from urdflint.model.memo import once, table
from urdflint.model.spelling import distance, near_miss, suggest
from urdflint.model.values import fmt, has_xacro, parse_number, parse_numbers

ROBOT, LINK, JOINT = "robot", "link", "joint"
SCOPE_SDF = {ROBOT: "<model>", LINK: "<link>", JOINT: "<joint>"}


@dataclass(frozen=True, slots=True)
class Key:
    """One key the converter understands: where it belongs, its type and valid range.

    ``kind`` is ``bool`` (converter rule: true/yes/1, anything else is false), ``sdfbool``
    (copied into SDF, which takes true/false/1/0), ``double``, ``int``, ``vector3``,
    ``string`` or ``element`` (a block of SDF, not a value).
    """

    name: str
    scope: str
    kind: str
    minimum: float | None = None
    maximum: float | None = None
    sdf: str = ""  # what it becomes in SDF


def _keys(*keys: Key) -> dict[str, Key]:
    return {k.name: k for k in keys}


KEYS: dict[str, Key] = _keys(
    Key("static", ROBOT, "bool", sdf="model/static"),
    Key("material", LINK, "string", sdf="visual/material/script/name"),
    Key("visual", LINK, "element", sdf="every visual of the link"),
    Key("collision", LINK, "element", sdf="every collision of the link"),
    Key("gravity", LINK, "sdfbool", sdf="link/gravity"),
    Key("turnGravityOff", LINK, "bool", sdf="link/gravity (inverted)"),
    Key("dampingFactor", LINK, "double", 0.0, 1.0, sdf="link/velocity_decay"),
    Key("maxVel", LINK, "double", 0.0, sdf="collision/surface/contact/ode/max_vel"),
    Key("minDepth", LINK, "double", 0.0, sdf="collision/surface/contact/ode/min_depth"),
    Key("mu1", LINK, "double", 0.0, sdf="collision/surface/friction/ode/mu"),
    Key("mu2", LINK, "double", 0.0, sdf="collision/surface/friction/ode/mu2"),
    Key("fdir1", LINK, "vector3", sdf="collision/surface/friction/ode/fdir1"),
    Key("kp", LINK, "double", 0.0, sdf="collision/surface/contact/ode/kp"),
    Key("kd", LINK, "double", 0.0, sdf="collision/surface/contact/ode/kd"),
    Key("selfCollide", LINK, "bool", sdf="link/self_collide"),
    Key("maxContacts", LINK, "int", 0.0, sdf="collision/max_contacts"),
    Key("laserRetro", LINK, "double", 0.0, sdf="collision/laser_retro"),
    Key("stopCfm", JOINT, "double", 0.0, sdf="physics/ode/limit/cfm"),
    Key("stopErp", JOINT, "double", 0.0, 1.0, sdf="physics/ode/limit/erp"),
    Key("provideFeedback", JOINT, "bool", sdf="physics/provide_feedback"),
    Key("implicitSpringDamper", JOINT, "bool", sdf="physics/ode/implicit_spring_damper"),
    Key("cfmDamping", JOINT, "bool", sdf="physics/ode/implicit_spring_damper"),
    Key("fudgeFactor", JOINT, "double", 0.0, 1.0, sdf="physics/ode/fudge_factor"),
    Key("springReference", JOINT, "double", sdf="axis/dynamics/spring_reference"),
    Key("springStiffness", JOINT, "double", 0.0, sdf="axis/dynamics/spring_stiffness"),
    Key("disableFixedJointLumping", JOINT, "bool", sdf="fixed joint kept (as revolute 0..0)"),
    Key("preserveFixedJoint", JOINT, "bool", sdf="fixed joint kept"),
)

# Deprecated or dropped keys: name -> (what sdformat does with it, what to do instead).
LEGACY: dict[str, tuple[str, str]] = {
    "cfmDamping": ("deprecated in favour of <implicitSpringDamper>", "Rename it."),
    "stopKp": ("no longer read by sdformat", "Set the joint stops with <stopErp> and <stopCfm>."),
    "stopKd": ("no longer read by sdformat", "Set the joint stops with <stopErp> and <stopCfm>."),
    "initialJointPosition": ("no longer read by sdformat", "Remove it."),
    "canonicalBody": ("read and ignored by sdformat", "Remove it."),
}


def _names(text: str) -> frozenset[str]:
    return frozenset(text.split())


# SDF elements that are meaningful when copied verbatim into each scope (sdformat sdf/1.6-1.11
# model.sdf, link.sdf, joint.sdf).
SDF_ELEMENTS: dict[str, frozenset[str]] = {
    ROBOT: _names(
        "static self_collide allow_auto_disable enable_wind frame pose link joint plugin "
        "gripper include model"
    ),
    LINK: _names(
        "gravity enable_wind self_collide kinematic must_be_base_link velocity_decay frame pose "
        "inertial collision visual sensor projector audio_sink audio_source battery light "
        "particle_emitter"
    ),
    JOINT: _names(
        "parent child gearbox_ratio gearbox_reference_body thread_pitch screw_thread_pitch axis "
        "axis2 physics frame pose sensor"
    ),
}

# Link keys and link-level SDF blobs that set a property of the whole SDF <link>: on a link
# removed by fixed-joint lumping they land on the surviving parent link. Canonical name and
# default value ("gravity" covers turnGravityOff, "self_collide" covers selfCollide).
LINK_LEVEL: dict[str, tuple[str, str]] = {
    "turnGravityOff": ("gravity", "true"),
    "gravity": ("gravity", "true"),
    "selfCollide": ("self_collide", "false"),
    "self_collide": ("self_collide", "false"),
    "dampingFactor": ("dampingFactor", "0"),
    "kinematic": ("kinematic", "false"),
    "enable_wind": ("enable_wind", "false"),
    "must_be_base_link": ("must_be_base_link", "false"),
    "velocity_decay": ("velocity_decay", ""),
}

CONVERTER_TRUE = frozenset({"true", "yes", "1"})
CONVERTER_FALSE = frozenset({"false", "no", "0"})
SDF_BOOLS = frozenset({"true", "false", "1", "0"})


# -- the blocks ---------------------------------------------------------------------------


def scopes_of(doc: Document, gazebo: etree._Element) -> frozenset[str] | None:
    """``{"robot"}``, ``{"link"}``, ``{"joint"}`` (both when a link and a joint share the
    name), or ``None`` when ``reference`` names nothing."""
    ref = gazebo.get("reference")
    if ref is None or ref == "":  # sdformat files an empty reference under the model
        return frozenset({ROBOT})
    found = set()
    if ref in doc.link_map:
        found.add(LINK)
    if ref in doc.joint_map:
        found.add(JOINT)
    return frozenset(found) or None


def keys_of(gazebo: etree._Element) -> list[etree._Element]:
    """Plain (non-namespaced) element children of a ``<gazebo>`` block (read once; the list
    is shared: do not change it)."""
    found = table(gazebo, "gazebo.keys")
    keys = found.get(gazebo)
    if keys is None:
        keys = found[gazebo] = [c for c in children(gazebo) if not c.tag.startswith("{")]
    return keys  # type: ignore[no-any-return]


UNRESOLVED = frozenset({LINK, JOINT})  # a dangling reference was meant for a link or a joint


def checked_scopes(doc: Document, gazebo: etree._Element) -> frozenset[str]:
    """The scopes a block's contents are checked against: its reference's, or, when the
    reference names nothing (G001), a link and a joint alike, so that the contents are
    still checked in the same run and fixing the reference reveals no second round."""
    return scopes_of(doc, gazebo) or UNRESOLVED


def block_keys(doc: Document) -> Iterator[tuple[etree._Element, frozenset[str], str]]:
    """``(key element, scopes, owner)`` for every key of every block (see
    :func:`checked_scopes` for blocks whose reference names nothing)."""
    for gazebo in doc.gazebo:
        scopes = checked_scopes(doc, gazebo)
        owner = describe(doc, gazebo)
        for el in keys_of(gazebo):
            yield el, scopes, owner


def blocks_for(doc: Document, name: str) -> list[etree._Element]:
    """The ``<gazebo reference="name">`` blocks (indexed once per document: a rule that asks
    for every link stays linear in the number of blocks)."""
    index = once(doc.robot, "gazebo.by_reference", lambda: _by_reference(doc))
    return list(index.get(name, ()))


def _by_reference(doc: Document) -> dict[str | None, list[etree._Element]]:
    index: dict[str | None, list[etree._Element]] = {}
    for block in doc.gazebo:
        index.setdefault(block.get("reference"), []).append(block)
    return index


def value_of(el: etree._Element) -> str:
    """What sdformat reads as the key's value: the ``value`` attribute, else the text."""
    raw = el.get("value")
    if raw is None:
        raw = el.text or ""
    return raw.strip()


def describe(doc: Document, gazebo: etree._Element) -> str:
    """``link 'x'``, ``joint 'j'`` or ``the robot`` for messages."""
    ref = gazebo.get("reference")
    if not ref:
        return "the robot"
    if ref in doc.link_map:
        return f"link {ref!r}"
    if ref in doc.joint_map:
        return f"joint {ref!r}"
    return f"the undefined reference {ref!r}"


def homes(name: str) -> list[str]:
    """The scopes where ``name`` is a converter key or a meaningful SDF element."""
    found = []
    key = KEYS.get(name)
    if key is not None:
        found.append(key.scope)
    found += [s for s, names in SDF_ELEMENTS.items() if name in names and s not in found]
    return found


def belongs(name: str, scopes: frozenset[str]) -> bool:
    """Whether ``name`` means something in a block of these scopes."""
    return any(scope in scopes for scope in homes(name))


def candidates() -> frozenset[str]:
    """Every name a ``<gazebo>`` child could be meant to be (for typo detection)."""
    return frozenset(KEYS).union(*SDF_ELEMENTS.values())


# -- values -------------------------------------------------------------------------------


def value_problem(key: Key, text: str) -> tuple[str, bool] | None:
    """Why ``text`` is not a valid value of ``key``: ``(reason, is_range_problem)``."""
    if has_xacro(text) or key.kind in ("string", "element"):
        return None
    if not text:
        reads = " (sdformat reads it as false)" if key.kind == "bool" else ""
        if key.name == "turnGravityOff":
            reads = " (sdformat reads it as true)"
        return f"is empty{reads}", False
    low = text.lower()
    if key.kind == "bool":
        if low in CONVERTER_TRUE or low in CONVERTER_FALSE:
            return None
        reads = "true" if key.name == "turnGravityOff" else "false"
        return f"is {text!r}, not a boolean (sdformat reads it as {reads})", False
    if key.kind == "sdfbool":
        if low in SDF_BOOLS:
            return None
        return f"is {text!r}, not a boolean (SDF takes true, false, 1 or 0)", False
    if key.kind == "vector3":
        values = parse_numbers(text)
        if values is None or len(values) != 3:
            return f"is {text!r}, not three numbers", False
        return None
    if key.kind == "int":
        if not text.lstrip("+-").isdigit():
            return f"is {text!r}, not an integer", False
        return _range(key, float(text))
    if key.kind == "double":
        value = parse_number(text)
        if value is None:
            return f"is {text!r}, not a number", False
        return _range(key, value)
    return None


def _range(key: Key, value: float) -> tuple[str, bool] | None:
    low, high = key.minimum, key.maximum
    if (low is not None and value < low) or (high is not None and value > high):
        if high is None:
            return f"is {fmt(value)}, below {fmt(low or 0.0)}", True
        return f"is {fmt(value)}, outside [{fmt(low or 0.0)}, {fmt(high)}]", True
    return None


def canonical(key: str, el: etree._Element) -> tuple[str, str] | None:
    """``(property, value)`` for a :data:`LINK_LEVEL` key, values normalised for comparison."""
    if key not in LINK_LEVEL:
        return None
    prop, _ = LINK_LEVEL[key]
    if key == "velocity_decay":
        return prop, " ".join(etree.tostring(el, encoding="unicode", with_tail=False).split())
    text = value_of(el).lower()
    if key == "dampingFactor":
        number = parse_number(text)
        return prop, "0" if number is None or number == 0 else repr(number)
    if key == "turnGravityOff":
        truth = text in CONVERTER_FALSE  # gravity stays on only for false/no/0
    elif key in ("gravity", "self_collide", "kinematic", "enable_wind", "must_be_base_link"):
        truth = text in ("true", "1")  # SDF booleans
    else:
        truth = text in CONVERTER_TRUE
    return prop, "true" if truth else "false"


# -- fixed-joint lumping ------------------------------------------------------------------


def preserved_joints(doc: Document) -> frozenset[str]:
    """Fixed joints kept by ``<disableFixedJointLumping>`` or ``<preserveFixedJoint>`` true."""
    kept = set()
    for gazebo in doc.gazebo:
        ref = gazebo.get("reference")
        for el in keys_of(gazebo):
            flag = el.tag in ("disableFixedJointLumping", "preserveFixedJoint")
            if flag and ref and value_of(el).lower() in CONVERTER_TRUE:
                kept.add(ref)
    return frozenset(kept)


def lumped_into(doc: Document, link: str, kept: frozenset[str]) -> tuple[Joint, str] | None:
    """``(fixed joint, surviving link)`` when sdformat merges ``link`` into an ancestor.

    A link is merged when its parent joint is fixed, not kept by a Gazebo flag, and its
    parent is not the ``world`` link (sdformat never lumps into ``world``).
    """
    graph = doc.graph
    joint = graph.parent_joint(link)
    target = _lumped_parent(joint, kept)
    if joint is None or target is None:
        return None
    seen = {link}
    while target not in seen:
        seen.add(target)
        above = _lumped_parent(graph.parent_joint(target), kept)
        if above is None:
            break
        target = above
    return joint, target


def _lumped_parent(joint: Joint | None, kept: frozenset[str]) -> str | None:
    """The parent link a fixed ``joint`` merges its child into, else ``None``."""
    if joint is None or joint.type != "fixed" or joint.name in kept:
        return None
    return joint.parent if joint.parent not in (None, "world") else None


# -- names --------------------------------------------------------------------------------


@cache
def materials() -> tuple[frozenset[str], frozenset[str]]:
    """Gazebo Classic's stock material scripts: ``(for links, rendering internals)``."""
    text = (
        resources.files("urdflint")
        .joinpath("data/gazebo-classic-materials.txt")
        .read_text(encoding="utf-8")
    )
    groups: list[set[str]] = [set()]
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("#"):
            continue
        if not line:
            if groups[-1]:
                groups.append(set())
            continue
        groups[-1].add(line)
    link = frozenset(groups[0])
    internal = frozenset().union(*groups[1:]) if len(groups) > 1 else frozenset()
    return link, frozenset(internal)


__all__ = ["distance", "near_miss", "suggest"]  # did-you-mean lives in urdflint.model.spelling
