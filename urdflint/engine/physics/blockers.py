"""The static findings the Pinocchio build cites: what explains a refusal, what Pinocchio misreads.

:func:`blocker` runs chosen static rules on the document and returns their first
error-level finding (by line). :func:`misread` says, for a model Pinocchio built,
what it read differently from the file.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from urdflint.engine.physics.result import Blocker
from urdflint.model.finding import Severity
from urdflint.model.values import fmt

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document

# value-level rules whose findings in these places leave the dynamics intact
VALUE_RULES = frozenset({"X003", "X004", "X005", "X008"})
HARMLESS_PLACES = frozenset({"visual", "collision", "material"})
MOVING_AXES = frozenset({"revolute", "continuous", "prismatic"})  # Pinocchio ignores a planar axis

Keep = Callable[[str, "etree._Element | None"], bool]


def blocker(doc: Document, codes: tuple[str, ...], keep: Keep | None = None) -> Blocker | None:
    """The first error-level finding of the rules ``codes`` (that ``keep`` accepts)."""
    from urdflint.engine import registry
    from urdflint.engine.linter import stamp

    rules = registry.load_rules()
    found: list[Blocker] = []
    for code in codes:
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
            if code in VALUE_RULES and inside(hit.element, HARMLESS_PLACES):
                continue
            if code == "X008" and _is_xacro_element(hit.element):
                continue
            if keep is not None and not keep(code, hit.element):
                continue
            finding = stamp(doc, rule, hit, doc.settings)
            where = f"line {finding.line}"
            if finding.path != doc.path:
                where = f"{finding.path}:{finding.line}"
            found.append(Blocker(code, rule.name, hit.message, hit.element, finding.line, where))
            break
    if not found:
        return None
    return min(found, key=urdfdom_order)


# urdfdom's parseURDF reads the robot's name and version, then every <material>, every
# <link>, every <joint>, and only then builds the tree; Pinocchio checks its own after it.
TREE_RULES = frozenset({"S003", "S004", "S005"})
PINOCCHIO_RULES = frozenset({"J010", "S008"})
PARTS = {"material": 1, "link": 2, "joint": 3}


def urdfdom_order(found: Blocker) -> tuple[int, int, str]:
    """Where urdfdom (then Pinocchio) stops: the first cause is the one to name."""
    if found.code in PINOCCHIO_RULES:
        phase = 5
    elif found.code in TREE_RULES:
        phase = 4
    else:
        phase, node = 0, found.element
        while node is not None:
            parent = node.getparent()
            if parent is not None and parent.getparent() is None and node.tag in PARTS:
                phase = PARTS[node.tag]  # a child of <robot>
                break
            node = parent
    return phase, found.line, found.code


def inside(el: etree._Element | None, tags: frozenset[str]) -> bool:
    """Whether ``el`` is, or lies inside, an element named in ``tags``."""
    node = el
    while node is not None:
        if node.tag in tags:
            return True
        node = node.getparent()
    return False


def _is_xacro_element(el: etree._Element | None) -> bool:
    from urdflint.model.schema import is_xacro

    return el is not None and isinstance(el.tag, str) and el.tag[:1] == "{" and is_xacro(el)


def _misread_kept() -> Keep:
    def keep(code: str, el: etree._Element | None) -> bool:
        if code == "J007":
            joint = _ancestor(el, "joint")
            return joint is not None and joint.get("type") in MOVING_AXES
        return inside(el, frozenset({"inertial"}))

    return keep


def misread(doc: Document, model: Any, codes: tuple[str, ...]) -> tuple[Blocker, str] | None:
    """What Pinocchio's model of ``doc`` says differently from the file, and the finding why.

    ``codes``: the static rules whose errors Pinocchio misreads (``MISREAD``).
    """
    from urdflint.engine.physics.compute import link_masses

    found = blocker(doc, codes, _misread_kept())
    if found is None:
        return None
    cause = f"{found.code} on {found.where}: {found.message}"
    if found.code == "J007":
        joint = _ancestor(found.element, "joint")
        name = joint.get("name") if joint is not None else "?"
        return found, (
            f"Pinocchio misreads joint '{name}': it builds the joint about the zero axis, so "
            f"the joint cannot move (its entry of the mass matrix is 0; {cause})"
        )
    link = _ancestor(found.element, "link")
    name = link.get("name") if link is not None else "?"
    held = link_masses(model).get(name or "", 0.0)
    return found, (
        f"Pinocchio misreads link '{name}': urdfdom cannot read its <inertial>, so Pinocchio "
        f"holds the link with {fmt(held)} kg and a zero inertia tensor ({cause})"
    )


def _ancestor(el: etree._Element | None, tag: str) -> etree._Element | None:
    node = el
    while node is not None and node.tag != tag:
        node = node.getparent()
    return node
