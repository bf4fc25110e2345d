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

The package: :func:`build` and its guards (the static pre-check, the size limits) here;
the :class:`Physics` result in ``result``; Pinocchio's refusals translated in ``errors``;
the numbers of a built model in ``compute``; the configuration ``q`` in ``configuration``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from urdflint.engine.physics.compute import compute, urdf_masses
from urdflint.engine.physics.configuration import configuration, joint_label
from urdflint.engine.physics.errors import captured_output, messages, translate
from urdflint.engine.physics.result import (
    MASS_ATOL,
    MASS_RTOL,
    Blocker,
    Physics,
    QProblem,
    Vec,
    close,
    unverifiable,
)
from urdflint.model.finding import Severity

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

__all__ = [
    "BLOCKING",
    "HARMLESS_PLACES",
    "MASS_ATOL",
    "MASS_RTOL",
    "MAX_DEPTH",
    "MAX_LINKS",
    "VALUE_RULES",
    "Blocker",
    "Physics",
    "QProblem",
    "Vec",
    "blocker",
    "build",
    "captured_output",
    "close",
    "configuration",
    "depth",
    "joint_label",
    "messages",
    "translate",
    "unverifiable",
    "urdf_masses",
]

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


# -- building -------------------------------------------------------------------------------


def _xml(doc: Document) -> str:
    try:
        return doc.source.decode("utf-8-sig")
    except UnicodeDecodeError:
        from lxml import etree

        return etree.tostring(doc.robot, encoding="unicode")


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
    return compute(doc, pin, model, base, static)


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
