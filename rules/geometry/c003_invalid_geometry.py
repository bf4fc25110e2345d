"""A `<visual>` or `<collision>` has no usable shape: missing, several, unknown or degenerate.

## What it does
Reports, for every `<visual>` and `<collision>` of a link:
- no `<geometry>` (on the `<visual>`/`<collision>`);
- a `<geometry>` with no shape, or with several (on the `<geometry>`);
- a `<geometry>` whose first child is not its shape, such as a `<material>`
  written inside it before the `<box>` (on the `<geometry>`);
- an unknown shape tag such as `<cube>` (on that element);
- a missing dimension, or one that is zero or negative: box `size`, sphere,
  cylinder and capsule `radius` and `length` (on the shape);
- a `<mesh>` without a `filename`, or with a zero `scale` component.

Warnings, not errors: `<plane>` (a PyBullet extension), `<capsule>` in a robot
that does not declare `version="1.2"`, and a mesh `scale` with an odd number
of negative components, which mirrors the mesh (info on a `<visual>`).
Malformed numbers are left to X004 and X005, namespaced shapes
(`drake:capsule`, `xacro:*`) to X007 and X008. URDF elements of other places
written inside `<geometry>` (`<material>`, `<origin>`) are not shapes: X007
reports them, and they count here only when they come first.

## Why is this bad?
urdfdom reads only the first child of `<geometry>`. When a `<visual>` or
`<collision>` has no geometry, an empty `<geometry>` ("Geometry tag contains no
child element"), an unknown shape or another element first ("Unknown geometry
type 'material'") or a shape without its attribute ("Mesh must contain a
filename attribute"), urdfdom logs "Could not parse visual element for Link" and
stops reading that link: `check_urdf` 3.0.1 (and sdformat 12, Pinocchio 4.1)
still load the model, but the link loses that visual or collision and every
collision after it (a bad visual takes all the link's collisions with it).
PyBullet refuses the file ("failed to parse link"), and MuJoCo refuses an
unknown collision shape. Of several shapes urdfdom reads the first, while
yourdfpy rejects them ("Too many of <sphere>, <cylinder>, <box>, <mesh>").
`<capsule>` is URDF 1.2 (urdfdom 6.0); older urdfdom, and sdformat with it, drop
it as an unknown geometry type (`check_urdf` 3.0.1 and sdformat 12.3: "Unknown
geometry type 'capsule'"), while Drake, PyBullet and MuJoCo read it. Zero and
negative sizes pass urdfdom (before URDF 1.2) but Drake aborts the process on a
negative box, MuJoCo refuses it ("size 0 must be positive"), and the sdformat
converter (Gazebo) silently drops the visual; a zero-size collision collides
with nothing. Mirrored meshes swap inside and outside in several engines: gz-sim
rejects them as collisions (gazebosim/gz-sim#2656), MuJoCo computes inward
normals (google-deepmind/mujoco#3604), and Ogre 2 renders them inside out
(gazebosim/gz-rendering#267).

## How to fix
Give each `<visual>` and `<collision>` exactly one `<box size>`,
`<cylinder radius length>`, `<sphere radius>` or `<mesh filename>` with
positive dimensions (metres). For a mirrored part, export a mirrored copy of
the mesh instead of using a negative scale.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree
from urdflint.rules import consequences as K

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.geometry import shape_elements
from urdflint.model.schema import homes
from urdflint.model.structure import closest, q
from urdflint.model.values import fmt, number, vector

ALIASES = {"cube": "box", "ball": "sphere"}
DIMENSIONS = {
    "box": ("size",),
    "sphere": ("radius",),
    "cylinder": ("radius", "length"),
    "capsule": ("radius", "length"),
}


@rule("C003", "invalid-geometry", Severity.ERROR, effects={"degenerate": K.DEGENERATE_SHAPE})
def check(doc: Document) -> Iterator[Hit]:
    for link in doc.links:
        for owner in link.visuals + link.collisions:
            yield from _owner(doc, owner, f"{owner.tag} of link {q(link.name)}")


def _owner(doc: Document, owner: etree._Element, where: str) -> Iterator[Hit]:
    geometry = owner.find("geometry")
    if geometry is None:
        yield Hit(owner, f"{where} has no <geometry>", fix="Add a <geometry> with one shape.")
        return
    found = shape_elements(owner)
    plain = [el for el in found if not str(el.tag).startswith("{")]
    if found and not plain:
        return  # only namespaced shapes (drake:capsule, xacro:...): X007/X008, not URDF
    shapes = [el for el in plain if _may_be_shape(str(el.tag))]
    if not shapes:
        yield Hit(geometry, f"<geometry> of the {where} has no shape", fix="Add one shape.")
    elif len(shapes) > 1:
        tags = ", ".join(f"<{el.tag}>" for el in shapes)
        yield Hit(
            geometry,
            f"<geometry> of the {where} has {len(shapes)} shapes ({tags})",
            fix="Keep one shape; put the others in their own <visual>/<collision>.",
        )
    else:
        if plain[0] is not shapes[0]:
            yield Hit(
                geometry,
                f"<geometry> of the {where} starts with <{plain[0].tag}>, not its shape "
                f"<{shapes[0].tag}>; urdfdom reads only the first child and drops the {owner.tag}",
                fix=f"Move <{plain[0].tag}> out of <geometry>; the shape must be its only child.",
            )
        yield from _shape(doc, shapes[0], owner, where)


def _may_be_shape(tag: str) -> bool:
    """A shape, or an unknown tag meant as one; not a URDF element of another place."""
    places = homes(tag)
    return not places or "geometry" in places


def _shape(
    doc: Document, shape: etree._Element, owner: etree._Element, where: str
) -> Iterator[Hit]:
    tag = str(shape.tag)
    if tag == "plane" or (tag == "capsule" and not _urdf_12(doc)):
        yield _extension(shape, where)
    if tag == "mesh":
        yield from _mesh(shape, owner, where)
    elif tag in DIMENSIONS:
        yield from _dimensions(shape, where)
    elif tag != "plane":
        match = ALIASES.get(tag) or closest(tag, ("box", "cylinder", "sphere", "mesh"))
        yield Hit(
            shape,
            f"{where} has unknown geometry type <{tag}>",
            fix=f"Did you mean <{match}>?"
            if match
            else "Use <box>, <cylinder>, <sphere> or <mesh>.",
        )


def _urdf_12(doc: Document) -> bool:
    """Whether the robot declares URDF 1.2 or later (urdfdom 6 reads <capsule>)."""
    parts = (doc.robot.get("version") or "1.0").strip().split(".")
    try:
        return tuple(int(p) for p in parts) >= (1, 2)
    except ValueError:
        return False


def _extension(shape: etree._Element, where: str) -> Hit:
    if shape.tag == "plane":
        message = f"{where} uses <plane>, a PyBullet extension that urdfdom refuses"
        fix = "Use a thin <box> instead of <plane>."
    else:
        message = f"{where} uses <capsule>, which urdfdom before 6.0 (URDF 1.2) refuses"
        fix = 'Declare <robot version="1.2"> for urdfdom 6, or use a cylinder and two spheres.'
    return Hit(shape, message, fix=fix, severity=Severity.WARNING)


def _dimensions(shape: etree._Element, where: str) -> Iterator[Hit]:
    kind = str(shape.tag)
    for attr in DIMENSIONS[kind]:
        raw = shape.get(attr)
        if raw is None:
            yield Hit(
                shape, f"{kind} of the {where} has no {attr}", fix=f"Add the {attr} attribute."
            )
            continue
        values = vector(shape, attr, 3) if attr == "size" else (number(shape, attr),)
        if values is None or None in values:
            continue  # malformed: X004
        if any(v <= 0 for v in values):  # type: ignore[operator]
            yield Hit(
                shape,
                f"{kind} of the {where} has {attr} {' '.join(fmt(v) for v in values)}",  # type: ignore[arg-type]
                fix=f"Make every {attr} positive (metres).",
                variant="degenerate",
            )


def _mesh(mesh: etree._Element, owner: etree._Element, where: str) -> Iterator[Hit]:
    if not (mesh.get("filename") or "").strip():
        yield Hit(mesh, f"mesh of the {where} has no filename", fix="Set filename to the mesh URI.")
    scale = vector(mesh, "scale", 3)
    if scale is None:
        return  # absent (1 1 1) or malformed (X004)
    text = " ".join(fmt(v) for v in scale)
    if any(v == 0 for v in scale):
        yield Hit(
            mesh,
            f"mesh of the {where} has scale {text}, which flattens it",
            fix="Make every scale component non-zero.",
        )
    elif scale[0] * scale[1] * scale[2] < 0:
        severity = Severity.WARNING if owner.tag == "collision" else Severity.INFO
        yield Hit(
            mesh,
            f"mesh of the {where} is mirrored by scale {text}",
            severity=severity,
            fix="Export a mirrored copy of the mesh and use a positive scale.",
        )
