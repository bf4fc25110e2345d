"""The Pinocchio view of a document: total mass, centre of mass and degrees of freedom.

:func:`build` is called once per document, lazily, through ``Document.physics``,
and only by the P rules and ``urdflint info``; Pinocchio (and numpy) are imported
inside the functions, never at module level.

**Build, then judge.** urdflint hands Pinocchio every usable document, with two
exceptions, and judges the result (verified with pin 4.1, the PyPI build):

- never built: S005 (a link with two parent joints, or a loop). urdfdom does not
  notice it, and Pinocchio then refuses the model ("Model does not have any body
  named X"), silently builds it without one of the joints, or crashes the process
  (a link that is its own parent: SIGSEGV). Nor are trees deeper than
  :data:`MAX_DEPTH` or larger than :data:`MAX_LINKS` (:attr:`Physics.limited`).
- refused: Pinocchio's own reason (urdfdom's messages, captured from the C++
  output) is translated into a sentence naming the element. When a static error
  explains it (:data:`BLOCKING`: missing names, duplicates, an undefined link, a
  missing ``<limit>``, a negative effort...), the sentence cites it.
- built but misread (:data:`MISREAD`): a malformed or incomplete ``<inertial>``
  (X004, X005, X008 and I012 inside it: urdfdom drops the tensor, and the mass
  too when ``<mass>`` or the origin is at fault) and a zero axis on a revolute,
  continuous or prismatic joint (J007: the joint cannot move, its entry of the
  mass matrix is 0). The numbers are not used; P001 says what Pinocchio misreads.
- built and read as written: everything else, even when a static rule reports
  an error (an S008 mimic that names no joint: Pinocchio ignores ``<mimic>``;
  negative masses, inverted limits...). The centre of mass is not computed when
  a mass is negative or the total is not positive (Pinocchio would return NaN or
  garbage).

Findings of X003, X004, X005 and X008 inside ``<visual>``, ``<collision>`` or a
``<material>`` are never cited: urdfdom skips that geometry and the dynamics are
intact; nor are leftover xacro elements (X008 says the model may be incomplete).

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

The package: :func:`build` and its guards here; the static findings it cites in
``blockers``; the :class:`Physics` result in ``result``; Pinocchio's refusals
translated in ``errors``; the numbers of a built model in ``compute``; the
configuration ``q`` in ``configuration``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from urdflint.engine import causes
from urdflint.engine.physics.blockers import HARMLESS_PLACES, VALUE_RULES, blocker, misread
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

if TYPE_CHECKING:
    from urdflint.model.document import Document

__all__ = [
    "BLOCKING",
    "HARMLESS_PLACES",
    "MASS_ATOL",
    "MASS_RTOL",
    "MAX_DEPTH",
    "MAX_LINKS",
    "MISREAD",
    "NEVER_BUILT",
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
    "misread",
    "translate",
    "unverifiable",
    "urdf_masses",
]

# Static errors that explain a refusal (cited by P001 when Pinocchio refuses the model).
BLOCKING = causes.BLOCKING
# Never handed to Pinocchio: it refuses, misreads or crashes (pin 4.1: SIGSEGV on a self-parent).
NEVER_BUILT = ("S005",)
# Built, but read differently from the file (see the module docstring).
MISREAD = ("X004", "X005", "X008", "I012", "J007")
MAX_DEPTH = 200  # real robots: at most 21 (tiago); Pinocchio's parser crashes near 4000
MAX_LINKS = 2000  # real robots: at most 96 (eve_r3); 3000 take 0.6 s to parse, 20000 take 2 min


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
    stopped = _not_built(doc, base)
    if stopped is not None:
        return stopped
    try:
        import pinocchio as pin
    except ImportError:
        base.missing = True
        from urdflint.model.optional import install_command

        base.reason = f"Pinocchio is not installed ({install_command('dynamics')})"
        return base
    with captured_output() as output:
        try:
            model = pin.buildModelFromXML(_xml(doc))
            error = None
        except Exception as exc:  # Pinocchio raises ValueError, RuntimeError, std::exception
            error = str(exc) or type(exc).__name__
    if error is not None:
        return _refused(doc, base, error, "".join(output))
    wrong = misread(doc, model, MISREAD)
    if wrong is not None:
        base.blocker, base.element = wrong[0], wrong[0].element
        base.reason, base.misread = wrong[1], True
        return base
    return compute(doc, pin, model, base, static)


def _not_built(doc: Document, base: Physics) -> Physics | None:
    """``base`` with the reason, when urdflint does not hand Pinocchio this document."""
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
    loop = blocker(doc, NEVER_BUILT)
    first = blocker(doc, BLOCKING) if loop is not None else None
    if first is not None and first is not loop and first.code != loop.code:  # type: ignore[union-attr]
        base.blocker, base.element = first, first.element
        base.reason = (
            "Pinocchio refuses the model: urdfdom, its parser, stops at an error before the "
            f"loop (see {first.code} {first.name} on {first.where})"
        )
        return base
    if loop is not None:
        base.blocker, base.element = loop, loop.element
        base.reason = (
            f"the model was not given to Pinocchio because of {loop.code} {loop.name} on "
            f"{loop.where}: {loop.message}; urdfdom does not notice it, and Pinocchio then "
            "refuses the model, builds it without one of the joints, or crashes"
        )
        return base
    return None


def _refused(doc: Document, base: Physics, error: str, output: str) -> Physics:
    """``base`` with Pinocchio's refusal translated, citing the static error behind it."""
    base.reason, base.element = translate(doc, error, output)
    cause = blocker(doc, BLOCKING)
    if cause is not None:
        base.blocker = cause
        base.reason += f" (see {cause.code} {cause.name} on {cause.where})"
        if base.element is None:
            base.element = cause.element
    return base


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
