"""A mesh is over 10 m or under 1 mm across after its `scale`: probably not in metres.

## What it does
Loads each mesh, applies the unit a Collada file declares
(`<asset><unit meter="0.001"/>`) and the `<mesh scale>`, and reports a bounding
box whose largest side is over 10 m or under 1 mm. When dividing by 1000
(millimetres), 100 (centimetres), or multiplying by 1000 (a scale applied
twice), gives a plausible part size (1 cm to 2 m), the message suggests that
`scale`; both millimetres and centimetres when both fit.

The Collada unit is applied because the tools that show and simulate a ROS
robot apply it: Gazebo Classic and Gazebo Sim (`ColladaLoader::Load` multiplies
the mesh by `meter`; `<up_axis>` is not applied, here neither), RViz
(`getMeshUnitRescale` in its mesh loader) and PyBullet (a 10-unit cube
declaring `meter="0.0254"` gets a 0.254 m bounding box, one declaring
`meter="0.001"` a 0.01 m one). A Collada file exported in millimetres with its
unit set is therefore already in metres; adding `scale="0.001 0.001 0.001"`
to it shrinks it a thousand times, which this rule reports. Pinocchio 4.1
(coal, through assimp) ignores the unit and reads the same cube as 10 m
across, so its collision geometry differs from Gazebo's for such files. STL
and OBJ carry no unit. MuJoCo and Drake do not read Collada at all (C009).

A model that is a lone static object, not a robot (one link, no joints, no mass: a ground
plane, a terrain, a building, as in `pybullet_data`'s `plane.urdf`, a 30 m plane), may be
large: for it only a side over 1 km counts as too large (a part of a metre or more
exported in millimetres).

## Why is this bad?
REP 103 fixes the unit of every ROS description at the metre, and so do
Gazebo, MuJoCo, PyBullet, Drake and Pinocchio. STL has no unit at all and CAD
tools export millimetres by default, so a part exported without conversion is
1000 times too large: RViz shows a giant, Gazebo collides with a building-sized
box, and the link's inertia no longer matches what is drawn. Nothing warns:
every consumer takes the numbers as metres.

## How to fix
Export the mesh in metres, or set the conversion on the mesh:
`<mesh filename="..." scale="0.001 0.001 0.001"/>` for millimetres. For a
Collada file, either set its `<unit meter>` correctly and drop the URDF scale,
or keep `meter="1"` and convert with the scale, never both.
"""

from __future__ import annotations

from collections.abc import Iterator

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.model.structure import q
from urdflint.model.values import fmt
from urdflint.sources.meshes import MAX_EXTENT, load, references, scale_hint, suspicious_size

SCENERY_MAX = 1000.0  # m: the largest side a lone static object may have


def lone_static_object(doc: Document) -> bool:
    """One link, no joints and no mass (absent or zero): scenery (PyBullet loads mass 0 as
    a static body), not a robot."""
    if len(doc.links) != 1 or doc.joints:
        return False
    mass = doc.links[0].inertial
    if mass is None:
        return True
    value = mass.find("mass")
    try:
        return value is None or float(value.get("value") or "0") <= 0
    except ValueError:
        return False


@rule(
    "C006",
    "mesh-scale-suspicious",
    Severity.WARNING,
    fix="Export the mesh in metres (REP 103) or set <mesh scale> to convert it.",
    needs=("trimesh",),
)
def check(doc: Document) -> Iterator[Hit]:
    scenery = lone_static_object(doc)
    for ref in references(doc):
        info = load(doc, ref)
        scale = ref.scale
        if info is None or scale is None or not suspicious_size(info):
            continue
        if scenery and MAX_EXTENT < info.largest <= SCENERY_MAX:
            continue  # a plane or a terrain may be large
        size = info.largest
        shown = " ".join(fmt(v) for v in scale)
        what = f"{ref.tag} mesh {ref.uri!r} of link {q(ref.link)}"
        where = f"{fmt(size)} m across with scale {shown}"
        if info.unit != 1.0:
            where += f" and its Collada unit of {fmt(info.unit)} m"
        hints = scale_hint(size)
        if scenery and size > SCENERY_MAX:
            hints = [(0.001, "millimetres")]
        if not hints:
            band = "over 10 m" if size > MAX_EXTENT else "under 1 mm"
            yield Hit(ref.element, f"{what} is {where}, {band}: check its unit")
            continue
        options = []
        for factor, unit in hints:
            better = " ".join(fmt(float(f"{v * factor:.6g}")) for v in scale)
            new_size = fmt(float(f"{size * factor:.3g}"))
            options.append((unit, better, new_size))
        text = " or ".join(
            f'{unit} (scale="{better}" makes it {new_size} m)' for unit, better, new_size in options
        )
        yield Hit(
            ref.element,
            f"{what} is {where}: probably {text}",
            fix=f'Set scale="{options[0][1]}" on the <mesh>, or export the mesh in metres.',
        )
