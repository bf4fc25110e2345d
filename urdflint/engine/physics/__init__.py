"""The Pinocchio view of a document: total mass, centre of mass and degrees of freedom.

:func:`build` is called once per document, lazily, through ``Document.physics``,
and only by the P rules and ``urdflint info``; Pinocchio (and numpy) are imported
inside the functions, never at module level.

**Never hand Pinocchio a broken document.** Before building, :func:`blocker` runs
the static rules whose error-level findings make urdfdom (which Pinocchio uses)
refuse the model, or, worse, read it into something other than what the file
says. The first such finding stops the build; P001 then names it:

- refused: X003 (missing names), X009 (robot version), S001/S002 (duplicate
  names), S003 (undefined link), S004 (several roots), S006 (unknown joint type),
  S007 (no parent/child), S008 (bad mimic reference or mimic cycle), S010
  (duplicate material), J001 errors (no ``<limit>`` or no effort/velocity),
  J010 errors (negative effort or velocity: "min_effort > max_effort"),
  J013 (``<dynamics>``/``<safety_controller>`` without their required attribute);
- misread: X004/X005 (a malformed number or vector in an ``<inertial>`` or
  ``<joint>`` makes urdfdom drop the inertial, so the mass turns into 0 and the
  COM into NaN), X008 errors on values (an unexpanded ``${...}`` in a number),
  S005 (a link with two parent joints is built twice and its mass counted twice),
  J007 (a zero axis becomes a NaN joint) and I012 (an incomplete ``<inertial>``
  is dropped silently).

Findings of X003, X004, X005 and X008 inside ``<visual>``, ``<collision>`` or a
``<material>`` do not block: urdfdom skips that geometry and the dynamics are
intact. Nor do leftover xacro elements (an unexpanded macro call or include):
urdfdom ignores them, so what is written is read correctly, and X008 reports
that the model may be incomplete (P003 catches the missing mass). Everything
else (negative masses, inverted limits...) is built; the centre of mass is not
computed when a mass is negative or the total is not positive (Pinocchio would
return NaN or garbage).

**The fixed-base pitfall.** The model is built with a fixed base (the URDF's
root link is the universe frame), so its joints and degrees of freedom are the
URDF's. Pinocchio puts the root link, and every link welded to it by fixed
joints, on the universe joint: ``model.inertias[0]``. ``computeTotalMass`` and
``centerOfMass`` sum joints 1..n only, so they leave those links out; the total
and the COM here include ``inertias[0]`` (equal to a free-flyer build's).

Mimic joints are built as ordinary joints (Pinocchio's own mimic support refuses
some valid trees, e.g. when the mimicking joint comes before its leader in
urdfdom's order); their position follows their leader (``multiplier * q + offset``)
and they do not count as degrees of freedom.
"""

from __future__ import annotations

import math
import os
import re
import sys
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdflint.model.finding import Severity
from urdflint.model.inertia import read_inertial
from urdflint.model.values import fmt, number

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document, Joint

Vec = tuple[float, float, float]

BLOCKING = (
    "X003",
    "X004",
    "X005",
    "X008",
    "X009",
    "S001",
    "S002",
    "S003",
    "S004",
    "S005",
    "S006",
    "S007",
    "S008",
    "S010",
    "J001",
    "J007",
    "J010",
    "J013",
    "I012",
)
# value-level rules whose findings in these places leave the dynamics intact
VALUE_RULES = frozenset({"X003", "X004", "X005", "X008"})
HARMLESS_PLACES = frozenset({"visual", "collision", "material"})
MAX_DEPTH = 200  # real robots: at most 21 (tiago); Pinocchio's parser crashes near 4000
MAX_LINKS = 2000  # real robots: at most 96 (eve_r3); 3000 take 0.6 s to parse, 20000 take 2 min
MASS_RTOL = 1e-9
MASS_ATOL = 1e-12


@dataclass(frozen=True, slots=True)
class Blocker:
    """A static finding that stops the Pinocchio build."""

    code: str
    name: str
    message: str
    element: etree._Element | None
    line: int
    where: str  # "line 12", or "file.xacro:12" when the line is in another file


@dataclass(frozen=True, slots=True)
class QProblem:
    """A ``--q``/``expect.q`` entry that cannot be applied."""

    joint: str
    message: str
    element: etree._Element | None = None
    fix: str | None = None


@dataclass
class Physics:
    """What Pinocchio made of one document.

    ``built`` is false when the static rules blocked the build (``blocker``), when
    Pinocchio refused the model (``reason`` translated, ``element`` named), when the
    model is too deep or too large for Pinocchio (``limited``) or when Pinocchio is
    not installed (``missing``). Masses are in kg, positions in metres
    in the root link's frame.
    """

    built: bool
    reason: str | None = None
    element: etree._Element | None = None
    blocker: Blocker | None = None
    missing: bool = False
    limited: bool = False  # too large for Pinocchio: urdflint's limit, not a defect
    name: str | None = None
    root: str | None = None
    dof: int = 0
    joint_names: list[str] = field(default_factory=list)  # Pinocchio joints, mimics included
    mimics: dict[str, tuple[str, float, float]] = field(default_factory=dict)
    urdf_mass: float = 0.0  # sum of the readable <mass> values
    mass: float = 0.0  # Pinocchio's total, inertias[0] included
    naive_mass: float = 0.0  # computeTotalMass on the fixed-base model
    universe_links: list[str] = field(default_factory=list)  # links on the universe joint
    link_masses: dict[str, float] = field(default_factory=dict)  # as Pinocchio holds them
    com: Vec | None = None
    com_problem: str | None = None
    q: dict[str, float] = field(default_factory=dict)  # applied positions, mimics included
    q_problems: list[QProblem] = field(default_factory=list)
    model: Any = None

    @property
    def mass_matches(self) -> bool:
        """Whether Pinocchio's total equals the sum of the URDF's ``<mass>`` values."""
        return close(self.mass, self.urdf_mass)


def close(a: float, b: float) -> bool:
    return abs(a - b) <= max(MASS_RTOL * max(abs(a), abs(b)), MASS_ATOL)


# -- static pre-check ---------------------------------------------------------------------


def blocker(doc: Document) -> Blocker | None:
    """The first error-level static finding that makes Pinocchio refuse or misread the model."""
    from urdflint.engine import registry
    from urdflint.engine.linter import stamp

    rules = registry.load_rules()
    found: list[Blocker] = []
    for code in BLOCKING:
        rule = rules.get(code)
        if rule is None:
            continue
        try:
            if rule.options:
                hits = list(rule.check(doc, doc.settings.options(code)))
            else:
                hits = list(rule.check(doc))
        except Exception:  # a crashing rule is U001's business, not a reason to block
            continue
        for hit in hits:
            if (hit.severity or rule.severity) is not Severity.ERROR:
                continue
            if code in VALUE_RULES and _harmless_place(hit.element):
                continue
            if code == "X008" and _is_xacro_element(hit.element):
                continue
            finding = stamp(doc, rule, hit, doc.settings)
            where = f"line {finding.line}"
            if finding.path != doc.path:
                where = f"{finding.path}:{finding.line}"
            found.append(Blocker(code, rule.name, hit.message, hit.element, finding.line, where))
            break
    if not found:
        return None
    return min(found, key=lambda b: (b.line, b.code))


def _is_xacro_element(el: etree._Element | None) -> bool:
    from urdflint.model.schema import is_xacro

    return el is not None and isinstance(el.tag, str) and el.tag[:1] == "{" and is_xacro(el)


def _harmless_place(el: etree._Element | None) -> bool:
    node = el
    while node is not None:
        if node.tag in HARMLESS_PLACES:
            return True
        node = node.getparent()
    return False


# -- Pinocchio messages -------------------------------------------------------------------

LOCATION_RE = re.compile(r"\s*at line \d+ in \S+")
GENERIC = (
    "joint xml is not initialized correctly",
    "the xml stream does not contain a valid urdf model",
)
LIMIT_RE = re.compile(r"min_(\w+?) (?:are|is) greater than max_\1|min_(\w+) > max_\2")
NAMED_RE = re.compile(r"\b(joint|link|material)\s+(?:\[\s*([^\]]*?)\s*\]|'([^']*)')", re.I)


def messages(captured: str) -> list[str]:
    """urdfdom's error lines without C++ source locations, each once, in order."""
    found: list[str] = []
    for raw in captured.splitlines():
        line = LOCATION_RE.sub("", raw).strip()
        if not line:
            continue
        for prefix in ("Error:", "Warning:", "Info:", "Debug:"):
            if line.startswith(prefix):
                line = line[len(prefix) :].strip()
                break
        if line and line not in found:
            found.append(line)
    return found


def translate(doc: Document, error: str, captured: str = "") -> tuple[str, etree._Element | None]:
    """A sentence naming the element for a Pinocchio/urdfdom refusal, and that element."""
    error = LOCATION_RE.sub("", error).strip()
    limit = LIMIT_RE.search(error)
    if limit:
        what = limit.group(1) or limit.group(2)
        found = _negative_limit(doc, what)
        if found is not None:
            return found
    lines = [m for m in messages(captured) if m.lower().rstrip(".") not in GENERIC]
    specific = lines[0] if lines else error
    element = next(
        (el for el in (_named(doc, m) for m in [specific, *lines]) if el is not None), None
    )
    return f"Pinocchio refuses the model: {_sentence(specific)}", element


def _sentence(text: str) -> str:
    text = LOCATION_RE.sub("", text).strip().rstrip(".")
    return text[:1].lower() + text[1:] if text[:2] != text[:2].upper() else text


def _named(doc: Document, message: str) -> etree._Element | None:
    """The first joint, link or material the message names that exists in the document."""
    tables: dict[str, dict[str, Any]] = {
        "joint": doc.joint_map,
        "link": doc.link_map,
        "material": doc.material_map,
    }
    for kind, table in tables.items():
        for match in NAMED_RE.finditer(message):
            if match.group(1).lower() != kind:
                continue
            name = match.group(2) if match.group(2) is not None else match.group(3)
            item = table.get(name)
            if item is not None:
                return item if kind == "material" else item.element
    return None


LIMIT_SOURCES = {
    "effort": ("limit", "effort"),
    "velocity": ("limit", "velocity"),
    "dry_friction": ("dynamics", "friction"),
    "friction": ("dynamics", "friction"),
    "damping": ("dynamics", "damping"),
}


def _negative_limit(doc: Document, what: str) -> tuple[str, etree._Element] | None:
    """Pinocchio checks ``-x <= x`` for effort, velocity and friction without naming the joint."""
    source = LIMIT_SOURCES.get(what)
    if source is None:
        return None
    tag, attr = source
    for joint in doc.joints:
        el = joint.find(tag)
        value = number(el, attr)
        if el is not None and value is not None and value < 0:
            sentence = (
                f"Pinocchio refuses the model: joint '{joint.name}' has {attr} {fmt(value)} in its "
                f"<{tag}>, and Pinocchio uses the range -{attr}..{attr}, so min_{what} > max_{what}"
            )
            return sentence, el
    return None


_LOCK = threading.Lock()


@contextmanager
def captured_output() -> Iterator[list[str]]:
    """Capture what C++ code writes to file descriptors 1 and 2 (urdfdom's console_bridge)."""
    out: list[str] = []
    with _LOCK:
        for stream in (sys.stdout, sys.stderr):
            with suppress(AttributeError, ValueError, OSError):
                stream.flush()
        saved: list[tuple[int, int]] = []
        with tempfile.TemporaryFile() as sink:
            try:
                for fd in (1, 2):
                    try:
                        saved.append((fd, os.dup(fd)))
                        os.dup2(sink.fileno(), fd)
                    except OSError:
                        continue
                yield out
            finally:
                for fd, copy in saved:
                    os.dup2(copy, fd)
                    os.close(copy)
                sink.seek(0)
                out.append(sink.read().decode("utf-8", "replace"))


# -- building -------------------------------------------------------------------------------


def _xml(doc: Document) -> str:
    try:
        return doc.source.decode("utf-8-sig")
    except UnicodeDecodeError:
        from lxml import etree

        return etree.tostring(doc.robot, encoding="unicode")


def urdf_masses(doc: Document) -> dict[str, float]:
    """Each link's readable ``<mass>`` (links without one are left out)."""
    found: dict[str, float] = {}
    for name, link in doc.link_map.items():
        inertial = read_inertial(link.element)
        if inertial is not None and inertial.mass is not None:
            found[name] = inertial.mass
    return found


def build(doc: Document) -> Physics:
    """Build the Pinocchio model of ``doc`` and compute mass, COM and DOF."""
    if not doc.ok:
        problem = doc.problem
        reason = (
            f"the file is not a usable URDF ({problem.code}: {problem.message})"
            if problem
            else None
        )
        return Physics(False, reason or "the file is not a usable URDF")
    name, root = doc.robot.get("name"), doc.graph.root
    static = urdf_masses(doc)
    base = Physics(False, name=name, root=root, urdf_mass=sum(static.values()))
    if doc.library:
        base.reason = "a xacro library file: no <link> after expansion"
        return base
    deepest = depth(doc)
    if deepest > MAX_DEPTH:
        base.limited = True
        base.reason = (
            f"the kinematic tree is {deepest} links deep; urdflint does not hand Pinocchio trees "
            f"deeper than {MAX_DEPTH} links (urdfdom and Pinocchio recurse once per link and "
            "overflow the stack)"
        )
        return base
    if len(doc.links) > MAX_LINKS:
        base.limited = True
        base.reason = (
            f"the model has {len(doc.links)} links; urdflint does not hand Pinocchio models of "
            f"more than {MAX_LINKS} links (its URDF parser takes quadratic time: minutes)"
        )
        return base
    found = blocker(doc)
    if found is not None:
        base.blocker, base.element = found, found.element
        base.reason = (
            f"the model was not given to Pinocchio because of {found.code} {found.name} "
            f"on {found.where}: {found.message}"
        )
        return base
    try:
        import pinocchio as pin
    except ImportError:
        base.missing = True
        base.reason = "Pinocchio is not installed (pip install 'urdflint[dynamics]')"
        return base
    with captured_output() as output:
        try:
            model = pin.buildModelFromXML(_xml(doc))
            error = None
        except Exception as exc:  # Pinocchio raises ValueError, RuntimeError, std::exception
            error = str(exc) or type(exc).__name__
    if error is not None:
        base.reason, base.element = translate(doc, error, "".join(output))
        return base
    return _compute(doc, pin, model, base, static)


def _compute(
    doc: Document, pin: Any, model: Any, result: Physics, static: dict[str, float]
) -> Physics:
    result.built = True
    result.model = model
    result.joint_names = list(model.names)[1:]
    result.mimics = _mimics(doc, set(result.joint_names))
    mimic_nv = sum(model.joints[model.getJointId(j)].nv for j in result.mimics)
    result.dof = int(model.nv) - mimic_nv
    result.naive_mass = float(pin.computeTotalMass(model))
    result.mass = float(sum(model.inertias[i].mass for i in range(model.njoints)))
    result.link_masses = _link_masses(model)
    result.universe_links = [
        f.name
        for f in model.frames
        if f.type == pin.FrameType.BODY and f.parentJoint == 0 and f.name in doc.link_map
    ]
    q, result.q, result.q_problems = _configuration(doc, pin, model, result.mimics)
    negative = sorted(n for n, m in static.items() if m < 0)
    if negative:
        listed = ", ".join(f"'{n}' ({fmt(static[n])} kg)" for n in negative)
        plural = len(negative) > 1
        result.com_problem = (
            f"link{'s' if plural else ''} {listed} {'have' if plural else 'has'} negative mass"
        )
    elif not result.mass > 0:
        result.com_problem = f"the total mass is {fmt(result.mass)} kg"
    else:
        result.com = _com(pin, model, q)
        if result.com is None:
            result.com_problem = "the centre of mass is not a finite number"
    return result


def _mimics(doc: Document, names: set[str]) -> dict[str, tuple[str, float, float]]:
    """``joint -> (leader, multiplier, offset)`` for mimic joints Pinocchio built."""
    found: dict[str, tuple[str, float, float]] = {}
    for joint in doc.joints:
        el = joint.find("mimic")
        if el is None or joint.name not in names or joint.type == "fixed":
            continue
        leader = el.get("joint")
        if leader is None:
            continue
        found[joint.name] = (  # type: ignore[index]
            leader,
            number(el, "multiplier", 1.0) or 0.0,
            number(el, "offset", 0.0) or 0.0,
        )
    return found


def _link_masses(model: Any) -> dict[str, float]:
    """Each link's own mass as Pinocchio holds it.

    A link behind a fixed joint keeps its inertia on that joint's frame; a link on a
    moving joint (or the root, on the universe joint) has the joint's inertia minus
    what the fixed joints lumped into it.
    """
    import pinocchio as pin

    frames = model.frames
    lumped = [0.0] * model.njoints
    for index, frame in enumerate(frames):
        if frame.type == pin.FrameType.FIXED_JOINT and index != 0:
            lumped[frame.parentJoint] += frame.inertia.mass
    found: dict[str, float] = {}
    for frame in frames:
        if frame.type != pin.FrameType.BODY:
            continue
        parent = frames[frame.parentFrame] if frame.parentFrame < len(frames) else None
        if (
            parent is not None
            and parent.type == pin.FrameType.FIXED_JOINT
            and frame.parentFrame != 0
        ):
            found[frame.name] = float(parent.inertia.mass)
        else:
            j = frame.parentJoint
            found[frame.name] = float(model.inertias[j].mass - lumped[j])
    return found


def joint_label(joint: Joint) -> str:
    return f"{joint.type} joint '{joint.name}'" if joint.type else f"joint '{joint.name}'"


def _configuration(
    doc: Document, pin: Any, model: Any, mimics: dict[str, tuple[str, float, float]]
) -> tuple[Any, dict[str, float], list[QProblem]]:
    """The configuration for ``settings.expect.q`` (neutral elsewhere), and what was wrong."""
    from urdflint.model.structure import did_you_mean

    requested = dict(doc.settings.expect.q)
    problems: list[QProblem] = []
    values: dict[str, float] = {}
    movable = set(model.names[1:])
    for name, value in requested.items():
        joint = doc.joint_map.get(name)
        if joint is None:
            fix = did_you_mean(name, model.names[1:], "joint")
            problems.append(
                QProblem(
                    name,
                    f"--q/expect.q names joint '{name}', which the model does not have",
                    None,
                    fix,
                )
            )
        elif name not in movable:
            problems.append(
                QProblem(
                    name,
                    f"--q/expect.q sets {joint_label(joint)}, which has no position",
                    joint.element,
                )
            )
        elif name in mimics:
            leader = mimics[name][0]
            problems.append(
                QProblem(
                    name,
                    f"--q/expect.q sets {joint_label(joint)}, which mimics '{leader}'; "
                    f"set '{leader}' instead",
                    joint.element,
                )
            )
        elif (nv := model.joints[model.getJointId(name)].nv) != 1:
            problems.append(
                QProblem(
                    name,
                    f"--q/expect.q sets {joint_label(joint)}, which has {nv} "
                    "degrees of freedom; only one-axis joints can be set",
                    joint.element,
                )
            )
        else:
            values[name] = value

    def position(name: str, depth: int = 0) -> float:
        if name in mimics and depth < 64:
            leader, multiplier, offset = mimics[name]
            return multiplier * position(leader, depth + 1) + offset
        return values.get(name, 0.0)

    applied = dict(values)
    for name in mimics:
        applied[name] = position(name)
    q = pin.neutral(model)
    for name, value in applied.items():
        if not model.existJointName(name):
            continue
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 1:
            q[joint.idx_q] = value
        elif joint.nq == 2 and joint.nv == 1:  # continuous: (cos, sin)
            q[joint.idx_q] = math.cos(value)
            q[joint.idx_q + 1] = math.sin(value)
    applied = {k: v for k, v in applied.items() if k in values or v != 0.0}
    return q, applied, problems


def depth(doc: Document) -> int:
    """How many joints the longest chain from the root has."""
    graph = doc.graph
    if graph.root is None:
        return 0
    deepest = 0
    seen: set[str] = set()
    stack = [(graph.root, 0)]
    while stack:
        name, level = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        deepest = max(deepest, level)
        stack.extend((child, level + 1) for child in graph.children(name))
    return deepest


def _com(pin: Any, model: Any, q: Any) -> Vec | None:
    """The COM of every body, the universe joint's included, in the root link frame.

    Forward kinematics joint by joint: ``model.createData()`` would allocate
    nv x nv matrices, gigabytes for a model with thousands of joints.
    """
    placements = [pin.SE3.Identity()] * model.njoints
    total = 0.0
    moment = [0.0, 0.0, 0.0]
    for i in range(model.njoints):
        if i:
            joint = model.joints[i]
            data = joint.createData()
            joint.calc(data, q)
            placements[i] = placements[model.parents[i]] * model.jointPlacements[i] * data.M
        inertia = model.inertias[i]
        if inertia.mass == 0.0:
            continue
        c = placements[i].act(inertia.lever)
        total += inertia.mass
        for k in range(3):
            moment[k] += inertia.mass * float(c[k])
    if not total > 0:
        return None
    com = (moment[0] / total, moment[1] / total, moment[2] / total)
    return com if all(math.isfinite(x) for x in com) else None


def unverifiable(doc: Document, physics: Physics) -> str | None:
    """Why an expectation cannot be checked, or ``None`` when P001 already reports it.

    A CI gate must not pass silently: when P001 is switched off for this file, or
    only warns (a model over urdflint's size limits), the rule whose expectation
    went unchecked says so itself.
    """
    settings = doc.settings
    if physics.missing or physics.limited or physics.reason is None:
        return physics.reason  # P001 only warns about urdflint's size limits
    if "P001" in settings.enabled() - settings.ignored_for(doc.path):
        return None
    return physics.reason
