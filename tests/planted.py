"""Defect planters for the planted-defect suite (see ``bench/engine_agreement.py``).

A planter takes the lxml tree of a base robot, plants one defect in it in place and returns
the element it planted the defect in, or ``None`` when the defect does not apply to that
robot (for example, no prismatic joint, no moving link with a mass). The base robots are
the four of ``fixtures/planted/`` or any real URDF file (:func:`load` takes a path), so a
planter never assumes more than a ``<robot>`` with links: it skips what it cannot use.

Planters choose their elements deterministically, first as the fixtures were designed for,
then, when that element is unsuitable, the next suitable one in document order:

- "the first moving link" is the child of the first non-fixed joint; for inertial
  defects, the first such child (in joint order) whose ``<inertial>`` has a positive mass
  and positive ``ixx``, ``iyy``, ``izz`` ("the body");
- "the limited joint" is the second revolute or prismatic joint (else the first), for limit
  defects the first of those (in that order) whose ``<limit>`` has ``lower < upper``;
- "the second moving joint" is the second non-fixed joint (else the first); its
  ``<limit>``, else the first other moving joint's with a positive effort (velocity).

Geometry defects use an existing collision element and add one (to the first moving link)
when the robot has none of the kind. A repeated element is a changed copy of the original,
written right after it. This module holds no tests.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import TypeAlias, TypeVar

from lxml import etree

BASES = Path(__file__).resolve().parent.parent / "fixtures" / "planted"
ROBOTS = ("arm", "rover", "gripper", "legged")

Tree: TypeAlias = etree._ElementTree
Element: TypeAlias = etree._Element
Planter: TypeAlias = Callable[[Tree], Element | None]
T = TypeVar("T")

MOMENTS = ("ixx", "iyy", "izz")
PRODUCTS = ("ixy", "ixz", "iyz")
LIMITED = ("revolute", "prismatic")


def load(robot: str | Path) -> Tree:
    """A fresh tree of the base robot ``robot``: one of :data:`ROBOTS`, or a URDF file."""
    path = BASES / f"{robot}.urdf" if isinstance(robot, str) and robot in ROBOTS else robot
    parser = etree.XMLParser(remove_blank_text=False)
    return etree.parse(str(path), parser)


def plant(robot: str | Path, defect: str) -> tuple[Tree, Element | None]:
    """The base robot with ``defect`` planted, and the element it is in (None: not applicable)."""
    tree = load(robot)
    return tree, DEFECTS[defect](tree)


def xpath(tree: Tree, element: Element | None) -> str | None:
    """The element's path in the tree (for reports), e.g. ``/robot/joint[2]/limit``."""
    return None if element is None else tree.getpath(element)


# --- choosing elements ------------------------------------------------------------------


def _root(tree: Tree) -> Element:
    return tree.getroot()


def links(tree: Tree) -> list[Element]:
    return _root(tree).findall("link")


def joints(tree: Tree) -> list[Element]:
    return _root(tree).findall("joint")


def link(tree: Tree, name: str) -> Element | None:
    return next((e for e in links(tree) if e.get("name") == name), None)


def child_name(joint: Element) -> str:
    child = joint.find("child")
    return "" if child is None else child.get("link", "")


def parent_name(joint: Element) -> str:
    parent = joint.find("parent")
    return "" if parent is None else parent.get("link", "")


def root_link(tree: Tree) -> Element | None:
    """The first link that is no joint's child (None: every link is)."""
    children = {child_name(j) for j in joints(tree)}
    return next((e for e in links(tree) if e.get("name") not in children), None)


def moving_joints(tree: Tree) -> list[Element]:
    return [j for j in joints(tree) if j.get("type") != "fixed"]


def second_moving_joint(tree: Tree) -> Element | None:
    moving = moving_joints(tree)
    return moving[1] if len(moving) > 1 else next(iter(moving), None)


def _second_first(items: list[T]) -> list[T]:
    """The second item, the first, then the rest (the order planters try joints in)."""
    return [*items[1:2], *items[:1], *items[2:]]


def limited_joint(tree: Tree) -> Element | None:
    """The second revolute or prismatic joint (else the first; None: there is none)."""
    return next(iter(_second_first(_limited(tree))), None)


def _limited(tree: Tree) -> list[Element]:
    return [j for j in joints(tree) if j.get("type") in LIMITED]


def moving_links(tree: Tree) -> Iterator[Element]:
    """The children of the non-fixed joints, in joint order (each once)."""
    seen: set[str] = set()
    for joint in moving_joints(tree):
        name = child_name(joint)
        found = link(tree, name)
        if found is not None and name not in seen:
            seen.add(name)
            yield found


def first_moving_link(tree: Tree) -> Element | None:
    return next(moving_links(tree), None)


def last_link(tree: Tree) -> Element | None:
    return next(iter(links(tree)[-1:]), None)


def _float(element: Element | None, attribute: str, default: str = "0") -> float | None:
    """The attribute as a number (None: no element, or not a number)."""
    if element is None:
        return None
    try:
        return float(element.get(attribute, default))
    except ValueError:
        return None


def _positive(element: Element | None, *attributes: str) -> bool:
    return element is not None and all((_float(element, a) or 0.0) > 0 for a in attributes)


def _is_body(link_: Element) -> bool:
    """Whether the link's ``<inertial>`` has a positive mass and positive moments."""
    body = link_.find("inertial")
    if body is None:
        return False
    return _positive(body.find("mass"), "value") and _positive(body.find("inertia"), *MOMENTS)


def body_link(tree: Tree) -> Element | None:
    """The first moving link with a positive mass and moments (None: there is none)."""
    return next((e for e in moving_links(tree) if _is_body(e)), None)


def inertial(tree: Tree) -> Element | None:
    """The ``<inertial>`` of the body (see :func:`body_link`)."""
    found = body_link(tree)
    return None if found is None else found.find("inertial")


def inertia(tree: Tree) -> Element | None:
    body = inertial(tree)
    return None if body is None else body.find("inertia")


def mass(tree: Tree) -> Element | None:
    body = inertial(tree)
    return None if body is None else body.find("mass")


def collision_shape(tree: Tree, shape: str, size: str) -> Element | None:
    """The first ``<shape>`` collision geometry whose first ``size`` number is positive,
    moving links first, then the others (root last)."""
    root = root_link(tree)
    ordered = [e for e in links(tree) if e is not root] + ([] if root is None else [root])
    found = (s for e in ordered for s in e.iterfind(f"collision/geometry/{shape}"))
    return next((s for s in found if _first(s.get(size, "")) > 0), None)


def _first(text: str) -> float:
    try:
        return float(text.split()[0])
    except (IndexError, ValueError):
        return 0.0


def _descendants(tree: Tree, name: str) -> set[str]:
    """The links below link ``name`` (through any joint)."""
    below: dict[str, list[str]] = {}
    for joint in joints(tree):
        below.setdefault(parent_name(joint), []).append(child_name(joint))
    found: set[str] = set()
    todo = list(below.get(name, ()))
    while todo:
        child = todo.pop()
        if child not in found:
            found.add(child)
            todo.extend(below.get(child, ()))
    return found


def _names(elements: Iterable[Element | None]) -> list[str]:
    return [name for e in elements if e is not None and (name := e.get("name"))]


def _number(element: Element, attribute: str) -> float:
    return float(element.get(attribute, "0"))


def _set(element: Element, attribute: str, value: float) -> Element:
    element.set(attribute, f"{value:g}")
    return element


# --- new elements -----------------------------------------------------------------------


def _append(tree: Tree, element: Element) -> Element:
    """Append ``element`` at the end of the robot, on its own indented line."""
    return _append_to(_root(tree), element, "\n  ")


def _append_to(parent: Element, element: Element, indent: str) -> Element:
    """Append ``element`` as the last child of ``parent``, on its own ``indent``-ed line."""
    if len(parent):
        last = parent[-1]
        element.tail, last.tail = last.tail, indent
    parent.append(element)
    return element


def new_link(name: str) -> Element:
    """A 1 kg link with a 0.1 m cube collision and matching inertia."""
    link_ = etree.Element("link", name=name)
    body = etree.SubElement(link_, "inertial")
    etree.SubElement(body, "mass", value="1")
    moment = f"{1 / 12 * 0.02:g}"
    etree.SubElement(body, "inertia", ixx=moment, ixy="0", ixz="0", iyy=moment, iyz="0", izz=moment)
    geometry = etree.SubElement(etree.SubElement(link_, "collision"), "geometry")
    etree.SubElement(geometry, "box", size="0.1 0.1 0.1")
    return link_


def new_fixed_joint(name: str, parent: str, child: str) -> Element:
    joint = etree.Element("joint", name=name, type="fixed")
    etree.SubElement(joint, "parent", link=parent)
    etree.SubElement(joint, "child", link=child)
    etree.SubElement(joint, "origin", xyz="0 0 0.05", rpy="0 0 0")
    return joint


def _new_collision(link_: Element, shape: str, **attributes: str) -> Element:
    """A new ``<collision>`` of ``link_`` holding one ``<shape>``; the shape."""
    collision = etree.Element("collision")
    shape_ = etree.SubElement(etree.SubElement(collision, "geometry"), shape, **attributes)
    _append_to(link_, collision, "\n    ")
    return shape_


def _unused(tree: Tree, tag: str, name: str) -> str:
    """``name``, else ``name_2``, ``name_3``...: the first that no ``<tag>`` of the robot has."""
    taken = set(_names(_root(tree).findall(tag)))
    found, n = name, 1
    while found in taken:
        n += 1
        found = f"{name}_{n}"
    return found


# --- inertial defects -------------------------------------------------------------------


def negative_mass(tree: Tree) -> Element | None:
    element = mass(tree)
    return None if element is None else _set(element, "value", -_number(element, "value"))


def zero_mass_moving_link(tree: Tree) -> Element | None:
    """Mass and inertia of the body (the first moving link with mass) both zero: a massless
    moving body (products of inertia the robot writes zeroed too)."""
    moments, element = inertia(tree), mass(tree)
    if moments is None or element is None:
        return None
    for name in _components(moments):
        _set(moments, name, 0.0)
    return _set(element, "value", 0.0)


def _components(element: Element) -> list[str]:
    """The moments, and the products of inertia ``element`` writes."""
    return [*MOMENTS, *(name for name in PRODUCTS if element.get(name) is not None)]


def missing_inertial_moving_link(tree: Tree) -> Element | None:
    """The body (the first moving link with mass) loses its ``<inertial>``."""
    link_, body = body_link(tree), inertial(tree)
    if link_ is None or body is None:
        return None
    link_.remove(body)
    return link_


def negative_ixx(tree: Tree) -> Element | None:
    element = inertia(tree)
    return None if element is None else _set(element, "ixx", -_number(element, "ixx"))


def not_positive_definite(tree: Tree) -> Element | None:
    """Positive moments, but ixy larger than sqrt(ixx*iyy): a negative principal moment."""
    element = inertia(tree)
    if element is None:
        return None
    return _set(element, "ixy", _number(element, "ixx") + _number(element, "iyy"))


def triangle_violated(tree: Tree) -> Element | None:
    """izz three times ixx + iyy (positive definite, but no body has these moments)."""
    element = inertia(tree)
    if element is None:
        return None
    return _set(element, "izz", 3 * (_number(element, "ixx") + _number(element, "iyy")))


def zero_moment_rod(tree: Tree) -> Element | None:
    """ixx and the products zero, iyy = izz: a thin rod along x (singular, but A + B >= C)."""
    element = inertia(tree)
    if element is None:
        return None
    side = max(_number(element, "iyy"), _number(element, "izz"))
    for name in ("ixx", *PRODUCTS):
        _set(element, name, 0.0)
    _set(element, "iyy", side)
    return _set(element, "izz", side)


def singular_welded_link(tree: Tree) -> Element | None:
    """On the first link welded by a fixed joint to a link (not world) that has a mass, every
    moment and product equal: a rank-1 tensor (principal moments 0, 0, 3x), as a CAD export
    with placeholder products writes it (anymal_c's hatch)."""
    for joint in joints(tree):
        if joint.get("type") != "fixed" or parent_name(joint) == "world":
            continue
        child = link(tree, child_name(joint))
        moments = child.find("inertial/inertia") if child is not None else None
        if moments is None or not _positive(child.find("inertial/mass"), "value"):
            continue
        value = _float(moments, "ixx") or 0.001
        for name in (*MOMENTS, *PRODUCTS):
            _set(moments, name, value if value > 0 else 0.001)
        return moments
    return None


def tiny_mass(tree: Tree) -> Element | None:
    """1e-9 kg, the inertia (moments and products) scaled down with it."""
    element, moments = mass(tree), inertia(tree)
    if element is None or moments is None:
        return None
    scale = 1e-9 / _number(element, "value")
    for name in _components(moments):
        _set(moments, name, (_float(moments, name) or 0.0) * scale)
    return _set(element, "value", 1e-9)


def repeated_inertial(tree: Tree) -> Element | None:
    """A second ``<inertial>`` after the body's: its copy with the mass and every moment and
    product of inertia five times larger (the same centre of mass). Returns the copy."""
    body = inertial(tree)
    if body is None:
        return None
    twin = _twin(body)
    weight, moments = twin.find("mass"), twin.find("inertia")
    assert weight is not None and moments is not None  # the body has both (body_link)
    _set(weight, "value", 5 * _number(weight, "value"))
    for name in _components(moments):
        _set(moments, name, 5 * (_float(moments, name) or 0.0))
    return twin


def _twin(element: Element) -> Element:
    """A copy of ``element`` written right after it, on its own line with the same
    indentation; the copy."""
    before = element.getprevious()
    parent = element.getparent()
    indent = before.tail if before is not None else parent.text if parent is not None else None
    twin = copy.deepcopy(element)
    twin.tail, element.tail = element.tail, indent or "\n"
    element.addnext(twin)
    return twin


def invalid_number(tree: Tree) -> Element | None:
    element = mass(tree)
    if element is not None:
        element.set("value", "abc")
    return element


def root_link_with_mass_only(tree: Tree) -> Element | None:
    """Only the root has mass and every joint is fixed: one rigid body, which KDL (ignoring
    the root's inertia) sees as massless. A control: engines should load it unchanged.
    A root without a positive mass gets a 1 kg inertial."""
    root = root_link(tree)
    if root is None:
        return None
    for link_ in links(tree):
        body = link_.find("inertial")
        if link_ is not root and body is not None:
            link_.remove(body)
    for joint in joints(tree):
        joint.set("type", "fixed")
        for extra in joint.findall("mimic"):
            joint.remove(extra)
    body = root.find("inertial")
    if body is not None and not _positive(body.find("mass"), "value"):
        root.remove(body)
        body = None
    if body is None:
        donor = new_link("donor").find("inertial")
        assert donor is not None
        root.insert(0, donor)
        body = donor
    return body


# --- joint defects ----------------------------------------------------------------------


def _ranged_limit(tree: Tree) -> Element | None:
    """The ``<limit>`` of the limited joint, else of the first other revolute or prismatic
    joint, whose ``lower < upper``."""
    for joint in _second_first(_limited(tree)):
        element = joint.find("limit")
        lower, upper = _float(element, "lower"), _float(element, "upper")
        if element is not None and lower is not None and upper is not None and lower < upper:
            return element
    return None


def inverted_limits(tree: Tree) -> Element | None:
    element = _ranged_limit(tree)
    if element is None:
        return None
    lower, upper = element.get("lower", "0"), element.get("upper", "0")
    element.set("lower", upper)
    element.set("upper", lower)
    return element


def repeated_limit(tree: Tree) -> Element | None:
    """A second ``<limit>`` after the limited joint's ranged one: its copy with the lower and
    upper bounds twice as far from zero (the same effort and velocity). Returns the copy."""
    element = _ranged_limit(tree)
    if element is None:
        return None
    twin = _twin(element)
    for name in ("lower", "upper"):
        _set(twin, name, 2 * _number(twin, name))
    return twin


def equal_limits(tree: Tree) -> Element | None:
    element = _ranged_limit(tree)
    if element is not None:
        element.set("upper", element.get("lower", "0"))
    return element


def _axis(tree: Tree) -> Element | None:
    joint = second_moving_joint(tree)
    if joint is None:
        return None
    element = joint.find("axis")
    return etree.SubElement(joint, "axis", xyz="1 0 0") if element is None else element


def _xyz(element: Element) -> list[float]:
    """The axis's ``xyz`` (URDF's default ``1 0 0`` when absent or not three numbers)."""
    try:
        values = [float(v) for v in element.get("xyz", "1 0 0").split()]
    except ValueError:
        values = []
    return values if len(values) == 3 else [1.0, 0.0, 0.0]


def zero_axis(tree: Tree) -> Element | None:
    element = _axis(tree)
    if element is not None:
        element.set("xyz", "0 0 0")
    return element


def non_unit_axis(tree: Tree) -> Element | None:
    """The axis scaled to length 2 (its norm, if it is no unit axis: skipped)."""
    element = _axis(tree)
    if element is None:
        return None
    values = _xyz(element)
    if abs(sum(v * v for v in values) - 1) > 1e-6:
        return None
    element.set("xyz", " ".join(f"{2 * v:g}" for v in values))
    return element


def _retype(joint: Element | None, kind: str) -> Element | None:
    if joint is not None:
        joint.set("type", kind)
    return joint


def planar_joint(tree: Tree) -> Element | None:
    return _retype(second_moving_joint(tree), "planar")


def floating_joint(tree: Tree) -> Element | None:
    return _retype(second_moving_joint(tree), "floating")


def unknown_joint_type(tree: Tree) -> Element | None:
    return _retype(second_moving_joint(tree), "hinge")


def missing_limit_revolute(tree: Tree) -> Element | None:
    """The first revolute joint with a ``<limit>`` loses it."""
    joint = next(
        (j for j in joints(tree) if j.get("type") == "revolute" and j.find("limit") is not None),
        None,
    )
    if joint is None:
        return None
    joint.remove(joint.find("limit"))
    return joint


def _moving_limit(tree: Tree, attribute: str) -> Element | None:
    """The ``<limit>`` of the second moving joint (continuous joints included), else of the
    first other moving joint; with a positive ``attribute``."""
    for joint in _second_first(moving_joints(tree)):
        element = joint.find("limit")
        if _positive(element, attribute):
            return element
    return None


def negative_effort(tree: Tree) -> Element | None:
    element = _moving_limit(tree, "effort")
    return None if element is None else _set(element, "effort", -_number(element, "effort"))


def zero_velocity(tree: Tree) -> Element | None:
    element = _moving_limit(tree, "velocity")
    return None if element is None else _set(element, "velocity", 0.0)


def mimic_of_undefined_joint(tree: Tree) -> Element | None:
    """The existing mimic (else a new one on the second moving joint) names a missing joint."""
    joint = second_moving_joint(tree)
    if joint is None:
        return None
    element = joint.find("mimic")
    if element is None:
        element = etree.SubElement(joint, "mimic", multiplier="1", offset="0")
    element.set("joint", "ghost_joint")
    return element


def calibration_and_safety_controller(tree: Tree) -> Element | None:
    """Valid but rarely supported: ``<calibration>`` and ``<safety_controller>`` inside the
    limits of the limited joint (replacing any it has)."""
    limit = _ranged_limit(tree)
    joint = None if limit is None else limit.getparent()
    if joint is None or limit is None:
        return None
    for old in [*joint.findall("calibration"), *joint.findall("safety_controller")]:
        joint.remove(old)
    lower, upper = _number(limit, "lower"), _number(limit, "upper")
    margin = (upper - lower) / 10
    etree.SubElement(joint, "calibration", rising=f"{lower + margin:g}")
    controller = etree.SubElement(joint, "safety_controller", k_position="100", k_velocity="10")
    _set(controller, "soft_lower_limit", lower + margin)
    return _set(controller, "soft_upper_limit", upper - margin)


# --- structure defects ------------------------------------------------------------------


def two_parents(tree: Tree) -> Element | None:
    """A second (fixed) joint to the last link that has a parent, from the root, or from the
    first moving link when the root already is its parent (no joint parallel to an existing
    one, no loop through the child's own subtree)."""
    children = {child_name(j) for j in joints(tree)}
    child = next((n for n in reversed(_names(links(tree))) if n in children), None)
    if child is None:
        return None
    taken = {child, *(parent_name(j) for j in joints(tree) if child_name(j) == child)}
    taken |= _descendants(tree, child)
    candidates = _names([root_link(tree), first_moving_link(tree)])
    parent = next((name for name in candidates if name not in taken), None)
    if parent is None:
        return None
    return _append(
        tree, new_fixed_joint(_unused(tree, "joint", "second_parent_joint"), parent, child)
    )


def second_root(tree: Tree) -> Element:
    return _append(tree, new_link(_unused(tree, "link", "spare_part")))


def undefined_link(tree: Tree) -> Element | None:
    """A fixed joint from the last link to a link that is not defined."""
    parent = next(iter(_names([last_link(tree)])), None)
    if parent is None:
        return None
    ghost = _unused(tree, "link", "ghost_link")
    return _append(tree, new_fixed_joint(_unused(tree, "joint", "ghost_mount"), parent, ghost))


def duplicate_link_name(tree: Tree) -> Element | None:
    """An exact copy of the first moving link, appended."""
    found = first_moving_link(tree)
    return None if found is None else _append(tree, copy.deepcopy(found))


def duplicate_joint_name(tree: Tree) -> Element | None:
    """A new fixed joint (to a new link) named like the second moving joint."""
    name = next(iter(_names([second_moving_joint(tree)])), None)
    parent = next(iter(_names([last_link(tree)])), None)
    if name is None or parent is None:
        return None
    extra = _unused(tree, "link", "extra_link")
    _append(tree, new_link(extra))
    return _append(tree, new_fixed_joint(name, parent, extra))


def world_root(tree: Tree) -> Element | None:
    """The root link renamed ``world`` (and every joint and ``<gazebo>`` reference to it);
    skipped when it already is, or a link named ``world`` exists."""
    root = root_link(tree)
    old = None if root is None else root.get("name")
    if root is None or not old or "world" in _names(links(tree)):
        return None
    for reference in _root(tree).iterfind("joint/parent"):
        if reference.get("link") == old:
            reference.set("link", "world")
    for gazebo in _root(tree).iterfind("gazebo"):
        if gazebo.get("reference") == old:
            gazebo.set("reference", "world")
    root.set("name", "world")
    return root


def version_1_2(tree: Tree) -> Element:
    robot = _root(tree)
    robot.set("version", "1.2")
    return robot


# --- geometry defects -------------------------------------------------------------------


def missing_mesh(tree: Tree) -> Element | None:
    """The first moving link's collision (else the first other moving link's that has one)
    becomes a mesh file that does not exist; with no collision on any moving link, the
    first moving link gets one."""
    geometry = next(
        (g for e in moving_links(tree) if (g := e.find("collision/geometry")) is not None), None
    )
    if geometry is not None:
        for shape in list(geometry):
            geometry.remove(shape)
        return etree.SubElement(geometry, "mesh", filename="meshes/missing_part.stl")
    found = first_moving_link(tree)
    if found is None:
        return None
    return _new_collision(found, "mesh", filename="meshes/missing_part.stl")


FLAT_FIRST_OBJECT = BASES / "meshes" / "flat_first_object.obj"


def mesh_first_object_flat(tree: Tree) -> Element | None:
    """Like :func:`missing_mesh`, the collision becomes a mesh: an OBJ file of two objects
    whose first is a flat square (MuJoCo reads the first object's faces only), named by its
    absolute path so that it resolves wherever the planted file is written."""
    geometry = next(
        (g for e in moving_links(tree) if (g := e.find("collision/geometry")) is not None), None
    )
    filename = str(FLAT_FIRST_OBJECT)
    if geometry is not None:
        for shape in list(geometry):
            geometry.remove(shape)
        return etree.SubElement(geometry, "mesh", filename=filename)
    found = first_moving_link(tree)
    return None if found is None else _new_collision(found, "mesh", filename=filename)


def negative_box_size(tree: Tree) -> Element | None:
    """The first collision box's first size negated; with no box, the first moving link gets
    a new collision box of size -0.05 0.05 0.05."""
    element = collision_shape(tree, "box", "size")
    if element is not None:
        sizes = element.get("size", "").split()
        element.set("size", " ".join([f"-{sizes[0]}", *sizes[1:]]))
        return element
    found = first_moving_link(tree)
    return None if found is None else _new_collision(found, "box", size="-0.05 0.05 0.05")


def zero_cylinder_radius(tree: Tree) -> Element | None:
    """The first collision cylinder's radius zero; with no cylinder, the first moving link
    gets a new collision cylinder of radius 0 and length 0.05."""
    element = collision_shape(tree, "cylinder", "radius")
    if element is not None:
        return _set(element, "radius", 0.0)
    found = first_moving_link(tree)
    if found is None:
        return None
    return _new_collision(found, "cylinder", radius="0", length="0.05")


DEFECTS: dict[str, Planter] = {
    planter.__name__: planter
    for planter in (
        negative_mass,
        zero_mass_moving_link,
        missing_inertial_moving_link,
        negative_ixx,
        not_positive_definite,
        triangle_violated,
        zero_moment_rod,
        singular_welded_link,
        tiny_mass,
        repeated_inertial,
        invalid_number,
        root_link_with_mass_only,
        inverted_limits,
        equal_limits,
        repeated_limit,
        zero_axis,
        non_unit_axis,
        planar_joint,
        floating_joint,
        unknown_joint_type,
        missing_limit_revolute,
        negative_effort,
        zero_velocity,
        mimic_of_undefined_joint,
        calibration_and_safety_controller,
        two_parents,
        second_root,
        undefined_link,
        duplicate_link_name,
        duplicate_joint_name,
        world_root,
        version_1_2,
        missing_mesh,
        mesh_first_object_flat,
        negative_box_size,
        zero_cylinder_radius,
    )
}
