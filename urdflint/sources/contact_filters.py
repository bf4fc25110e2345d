"""Which pairs of links each engine collides: its contact filtering, as read in its source and
checked against its contacts at rest (C013; ``bench/contact_agreement.py``).

Links welded by ``fixed`` joints form one rigid body (MuJoCo's weld, Drake's welded
subgraph, Gazebo's lumped link). Then, per engine:

- MuJoCo 4.0 (``engine_collision_driver.c``, ``filterBodyPair``; ``xml_urdf.cc``): every
  collision geom has ``contype = conaffinity = 1`` (the URDF import sets both, nothing in a
  URDF changes them); two bodies are filtered when they are one weld, both have no degree
  of freedom, or one is the other's parent weld *unless either is the world*. The import
  never gives the root link a joint: it is welded to the world (``fusestatic``, on by
  default for URDF, merges it into the world body), so a root body collides with its own
  children. ``<mujoco><option><flag filterparent="disable"/>`` collides parents and
  children too, ``contact="disable"`` nothing.
- Drake 1.51 (``MultibodyPlant::ApplyDefaultCollisionFilters``): filters each welded
  subgraph, and the two bodies (links) of each joint, except a joint whose parent is the
  world (a link named ``world``) or a floating joint; then the ``<drake:collision_filter_group>``
  pairs (``detail_common.cc``: only ``drake:``-prefixed elements, ``ignore="true"`` skips a
  group, ``<drake:member_group>`` nests one).
- Gazebo: links connected by a joint never collide (after lumping); otherwise two links
  collide when either self-collides: Gazebo Classic takes a link's own ``<self_collide>``
  (``<selfCollide>`` or ``<self_collide>`` in its ``<gazebo reference>``; sdformat moves a
  lumped link's to its body) else the model's; Gazebo Sim only the model's (gz-physics
  ``setSelfCollisionCheck(model.SelfCollide())``). The model's is ``<self_collide>`` in a
  robot-level ``<gazebo>``; sdformat 12 drops a robot-level ``<selfCollide>``.
- PyBullet 3.2.7 with ``URDF_USE_SELF_COLLISION`` (none without it): every pair of links but
  a parent and child of one joint (``fixed`` ones included).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

from urdflint.model.document import children, local_tag

if TYPE_CHECKING:
    from lxml import etree

    from urdflint.model.document import Document, Joint

TRUE = ("true", "1")
WORLD = "world"  # the link name Drake's and MuJoCo's URDF parsers take for the world


@dataclass(frozen=True, slots=True)
class Relation:
    """How two links are joined: ``same_body`` (welded by fixed joints); ``joint`` the joint
    joining the two links themselves (None: none does); ``body_adjacent`` their rigid bodies
    are joined by a joint; ``roots`` how many of the two bodies hold a root link."""

    same_body: bool
    joint: Joint | None
    body_adjacent: bool
    roots: int


class Filters:
    """The contact filtering of each engine for one document."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.body = bodies(doc)
        self.joints: dict[frozenset[str], Joint] = {}
        self.joined: set[frozenset[int]] = set()
        for joint in doc.joints:
            if joint.parent in self.body and joint.child in self.body:
                pair = frozenset((str(joint.parent), str(joint.child)))
                self.joints.setdefault(pair, joint)
                self.joined.add(
                    frozenset((self.body[str(joint.parent)], self.body[str(joint.child)]))
                )
        self.roots = {self.body[name] for name in doc.graph.roots if name in self.body}

    def relation(self, a: str, b: str) -> Relation:
        first, second = self.body[a], self.body[b]
        return Relation(
            first == second,
            self.joints.get(frozenset((a, b))),
            frozenset((first, second)) in self.joined,
            len({first, second} & self.roots),
        )

    # -- MuJoCo ------------------------------------------------------------------------------

    @cached_property
    def mujoco_flags(self) -> dict[str, str]:
        """The ``<flag>`` attributes of ``<mujoco><option>`` in the URDF (the import reads the
        first ``<mujoco>`` child of the robot, and its first ``<option>``)."""
        extension = next((c for c in children(self.doc.robot) if local_tag(c) == "mujoco"), None)
        option = _first(extension, "option")
        flag = _first(option, "flag")
        return {} if flag is None else {k: str(v).strip() for k, v in flag.attrib.items()}

    def mujoco(self, relation: Relation) -> bool:
        flags = self.mujoco_flags
        if relation.same_body or relation.roots == 2 or flags.get("contact") == "disable":
            return False  # one weld, or two welds without a degree of freedom (the world)
        adjacent = relation.body_adjacent and flags.get("filterparent") != "disable"
        return not adjacent or relation.roots == 1

    def mujoco_body(self, link: str) -> str:
        """The MuJoCo body a link ends up in: ``world`` for a root's, else the body's top link
        (``fusestatic`` merges a link fixed to its parent into it)."""
        if self.body.get(link) in self.roots:
            return WORLD
        graph = self.doc.graph
        for _ in range(len(self.body)):
            joint = graph.parent_joint(link)
            if joint is None or joint.type != "fixed" or joint.parent is None:
                break
            link = joint.parent
        return link

    # -- Drake -------------------------------------------------------------------------------

    @cached_property
    def drake_groups(self) -> set[frozenset[str]]:
        return drake_filtered(self.doc)

    def drake(self, a: str, b: str, relation: Relation) -> bool:
        if relation.same_body or frozenset((a, b)) in self.drake_groups:
            return False
        joint = relation.joint
        return joint is None or joint.parent == WORLD or joint.type == "floating"

    # -- Gazebo ------------------------------------------------------------------------------

    @cached_property
    def self_collide(self) -> tuple[bool, dict[int, bool]]:
        """The model's ``<self_collide>``, and each body's own (its links' ``<gazebo
        reference>`` blocks; a true one wins, as sdformat merges lumped links)."""
        model = False
        own: dict[int, bool] = {}
        for gazebo in self.doc.gazebo:
            reference = gazebo.get("reference")
            for child in children(gazebo):
                tag = local_tag(child)
                value = (child.text or "").strip().lower() in TRUE
                if reference is None and tag == "self_collide":
                    model = value
                elif reference in self.body and tag in ("selfCollide", "self_collide"):
                    body = self.body[reference]
                    own[body] = own.get(body, False) or value
        return model, own

    def gazebo(self, target: str, a: str, b: str, relation: Relation) -> bool:
        if relation.same_body or relation.body_adjacent:
            return False  # lumped together, or connected by a joint
        model, own = self.self_collide
        if target == "gz-sim":
            return model
        return any(own.get(self.body[link], model) for link in (a, b))

    # -- PyBullet ------------------------------------------------------------------------------

    def pybullet(self, relation: Relation) -> bool:
        """With ``URDF_USE_SELF_COLLISION`` (welded links are left out: no motion follows)."""
        return not relation.same_body and relation.joint is None


def _first(parent: etree._Element | None, tag: str) -> etree._Element | None:
    if parent is None:
        return None
    return next((c for c in children(parent) if local_tag(c) == tag), None)


def bodies(doc: Document) -> dict[str, int]:
    """Each link's rigid body: links joined by ``fixed`` joints share a number."""
    parent = {name: name for name in doc.link_map}

    def find(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    for joint in doc.joints:
        if joint.type == "fixed" and joint.parent in parent and joint.child in parent:
            parent[find(str(joint.child))] = find(str(joint.parent))
    numbers: dict[str, int] = {}
    return {name: numbers.setdefault(find(name), len(numbers)) for name in doc.link_map}


def drake_filtered(doc: Document) -> set[frozenset[str]]:
    """Link pairs a ``<drake:collision_filter_group>`` ignores (Drake reads only the
    ``drake:`` spelling: an unprefixed ``<collision_filter_group>`` filters nothing)."""
    members: dict[str, set[str]] = {}
    nested: dict[str, set[str]] = {}
    ignores: dict[str, set[str]] = {}
    for group in children(doc.robot):
        if local_tag(group) != "drake:collision_filter_group" or not group.get("name"):
            continue
        if (group.get("ignore") or "").strip().lower() in TRUE:
            continue
        name = str(group.get("name"))
        members.setdefault(name, set())
        for child in children(group):
            tag = local_tag(child)
            if tag == "drake:member" and child.get("link"):
                members[name].add(str(child.get("link")))
            elif tag == "drake:member_group" and child.get("name"):
                nested.setdefault(name, set()).add(str(child.get("name")))
            elif tag == "drake:ignored_collision_filter_group" and child.get("name"):
                ignores.setdefault(name, set()).add(str(child.get("name")))
    links = {name: _members(name, members, nested, set()) for name in members}
    pairs: set[frozenset[str]] = set()
    for name, others in ignores.items():
        for other in others:
            for a in links.get(name, ()):
                pairs.update(frozenset((a, b)) for b in links.get(other, ()) if a != b)
    return pairs


def _members(
    name: str, members: dict[str, set[str]], nested: dict[str, set[str]], seen: set[str]
) -> set[str]:
    """A group's links, with those of the groups it nests (each group once)."""
    seen.add(name)
    found = set(members.get(name, ()))
    for inner in nested.get(name, ()):
        if inner not in seen:
            found |= _members(inner, members, nested, seen)
    return found
