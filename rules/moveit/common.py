"""What the M rules share: the SRDF of a document, hits that point into it, and the parts of
MoveIt's model the rules need (which joints a group holds, a joint's position bounds).

The model follows srdfdom (``src/model.cpp``: ``srdf::Model::initXml`` and its ``load*``
functions, which drop the elements naming unknown links or joints) and moveit_core
(``moveit_core/robot_model/src/robot_model.cpp``: ``RobotModel::addJointModelGroup``,
``buildGroupStates``, ``constructJointModel``, ``jointBoundsFromURDF``).
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from urdflint.engine.registry import Hit
from urdflint.model.document import Document, children
from urdflint.model.finding import Severity
from urdflint.model.values import number
from urdflint.sources import srdf as srdf_source
from urdflint.sources.srdf import Srdf, name_of

__all__ = ["Model", "Srdf", "hit", "model", "name_of", "srdf_of"]

ASSUMED_ROOT = "ASSUMED_FIXED_ROOT_JOINT"  # MoveIt's root joint without a virtual joint
VIRTUAL_TYPES = {"fixed": 0, "planar": 3, "floating": 7}  # srdfdom's types: variable counts
URDF_VARIABLES = {"revolute": 1, "continuous": 1, "prismatic": 1, "fixed": 0, "planar": 3,
                  "floating": 7}  # fmt: skip


def srdf_of(doc: Document) -> Srdf | None:
    """The document's usable SRDF (``None`` when there is none or it cannot be read)."""
    srdf = srdf_source.load(doc)
    return srdf if srdf is not None and srdf.root is not None else None


def hit(
    srdf: Srdf,
    el: etree._Element,
    message: str,
    *,
    attribute: str | None = None,
    fix: str | None = None,
    severity: Severity | None = None,
) -> Hit:
    """A hit on an SRDF element: the finding names the SRDF file and line."""
    path, line, column = srdf.position(el, attribute)
    return Hit(el, message, fix=fix, severity=severity, line=line, column=column, path=path)


@dataclass
class Model:
    """The URDF plus the SRDF, as MoveIt builds them into a robot model."""

    doc: Document
    srdf: Srdf

    # -- joints ---------------------------------------------------------------------------

    def virtual_joints(self) -> dict[str, str]:
        """Virtual joints srdfdom keeps: name -> type (an unknown type becomes ``fixed``)."""
        found: dict[str, str] = {}
        for el in self.srdf.elements("virtual_joint"):
            name, child = name_of(el), name_of(el, "child_link")
            kind = (name_of(el, "type") or "").lower()
            if name and child in self.doc.link_map and el.get("parent_frame") is not None and kind:
                found.setdefault(name, kind if kind in VIRTUAL_TYPES else "fixed")
        return found

    def known_joint(self, name: str) -> bool:
        """srdfdom's ``isValidJoint``: a URDF joint or a virtual joint."""
        return name in self.doc.joint_map or name in self.virtual_joints()

    def root_joint(self) -> str:
        """The name MoveIt gives the joint above the URDF root (``constructJointModel``)."""
        root = self.doc.graph.root
        for el in self.srdf.elements("virtual_joint"):
            name, child = name_of(el), name_of(el, "child_link")
            if name in self.virtual_joints() and child == root and name_of(el, "parent_frame"):
                return name
        return ASSUMED_ROOT

    def variables(self, joint: str) -> int | None:
        """How many values a joint takes in a group state (``None``: not a joint)."""
        if joint in self.doc.joint_map:
            return URDF_VARIABLES.get(self.doc.joint_map[joint].type or "")
        kind = self.virtual_joints().get(joint)
        return VIRTUAL_TYPES[kind] if kind is not None else None

    def parent_joint(self, link: str) -> str | None:
        joint = self.doc.graph.parent_joint(link)
        if joint is not None:
            return joint.name
        return self.root_joint() if link == self.doc.graph.root else None

    # -- groups ---------------------------------------------------------------------------

    def chain(self, base: str, tip: str) -> list[str]:
        """The joints MoveIt puts in a group for ``<chain base_link tip_link>``."""
        graph = self.doc.graph
        tip_side: list[str | None] = []
        link: str | None = tip
        while link is not None and link != base:
            tip_side.append(self.parent_joint(link))
            link = graph.parent_link(link)
        if link == base:
            return [j for j in tip_side if j]
        base_side: list[str | None] = []
        link = base
        while link is not None:
            joint = self.parent_joint(link)
            if joint in tip_side:
                index = tip_side.index(joint) + 1
                return [j for j in (*tip_side[:index], *base_side) if j]
            base_side.append(joint)
            link = graph.parent_link(link)
        return []

    def group_elements(self) -> dict[str, etree._Element]:
        """The first ``<group>`` of each name (MoveIt does not add a second)."""
        found: dict[str, etree._Element] = {}
        for el in self.srdf.elements("group"):
            name = name_of(el)
            if name is not None:
                found.setdefault(name, el)
        return found

    def own_joints(self, group: etree._Element) -> set[str]:
        """A group's joints from its own ``<joint>``, ``<link>`` and ``<chain>`` elements."""
        joints: set[str] = set()
        for el in children(group, "joint"):
            name = name_of(el)
            if name and self.known_joint(name):
                joints.add(name)
        for el in children(group, "link"):
            link = name_of(el)
            parent = self.parent_joint(link) if link in self.doc.link_map else None
            if parent:
                joints.add(parent)
        for el in children(group, "chain"):
            base, tip = name_of(el, "base_link"), name_of(el, "tip_link")
            if base in self.doc.link_map and tip in self.doc.link_map:
                joints.update(self.chain(base, tip))  # type: ignore[arg-type]
        return joints

    def groups(self) -> dict[str, set[str]]:
        """The groups MoveIt builds, with their joints (subgroups resolved, cycles dropped)."""
        elements = self.group_elements()
        built: dict[str, set[str]] = {}
        pending = dict(elements)
        while pending:
            progress = False
            for name, el in list(pending.items()):
                subs = [name_of(s) for s in children(el, "group")]
                if any(s not in built and s in pending for s in subs if s):
                    continue
                if any(s not in elements for s in subs if s):  # srdfdom drops it
                    del pending[name]
                    continue
                joints = self.own_joints(el)
                for sub in subs:
                    joints |= built.get(sub or "", set())
                if joints:
                    built[name] = joints
                del pending[name]
                progress = True
            if not progress:
                break  # the rest wait on each other: a subgroup cycle
        return built

    def group_links(self, joints: set[str]) -> set[str]:
        """The links of a group: the child links of its joints (``hasLinkModel``)."""
        links = {
            j.child for j in self.doc.joints if j.name in joints and j.child in self.doc.link_map
        }
        root = self.doc.graph.root
        if root is not None and self.root_joint() in joints:
            links.add(root)
        return {link for link in links if link is not None}


def model(doc: Document, srdf: Srdf) -> Model:
    return Model(doc, srdf)


def bounds(doc: Document, joint: str) -> tuple[float, float] | None:
    """MoveIt's position bounds of a URDF joint (``jointBoundsFromURDF``): the ``<limit>``
    intersected with the ``<safety_controller>`` soft limits; ``None`` when unbounded."""
    found = doc.joint_map.get(joint)
    if found is None or found.type not in ("revolute", "prismatic"):
        return None  # continuous joints are unbounded (RevoluteJointModel::setContinuous)
    limit, safety = found.find("limit"), found.find("safety_controller")
    lower = number(limit, "lower", 0.0) if limit is not None else None  # urdfdom's defaults
    upper = number(limit, "upper", 0.0) if limit is not None else None
    if limit is not None and (lower is None or upper is None):
        return None  # malformed: the X rules report it
    if safety is not None:
        soft_lower, soft_upper = (
            number(safety, "soft_lower_limit", 0.0),
            number(safety, "soft_upper_limit", 0.0),
        )
        if soft_lower is None or soft_upper is None:
            return None
        lower = soft_lower if limit is None else max(lower, soft_lower)  # type: ignore[type-var]
        upper = soft_upper if limit is None else min(upper, soft_upper)  # type: ignore[type-var]
    if lower is None or upper is None:
        return None
    return lower, upper


def parse_values(text: str) -> list[float] | None:
    """A group state's ``value``: whitespace-separated numbers (``None`` when one is not)."""
    values: list[float] = []
    for token in text.split():
        try:
            values.append(float(token))
        except ValueError:
            return None
    return values
