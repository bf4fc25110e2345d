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

Scenery may be large: terrains, ground planes, ramps and stairs written as URDF files for
a simulator to load beside the robot (`pybullet_data`'s `plane.urdf`, a 30 m plane;
Bullet's `terrain.urdf`, 29 × 29 m; a quadruped's 16 m ramps). For a mesh of scenery only a
side over 1 km counts as too large (a part of a metre or more exported in millimetres),
and the heuristic, `urdflint.model.scenery`, calls a mesh scenery when:
- the model is static: no joint moves (every joint is `fixed`, or there is none) and
  either nothing has mass (PyBullet leaves a massless base where it is) or the root link
  is the world (`world`, `map`, `ground`, `terrain`, `floor`, `scene`), to which the rest
  is welded;
- or its link, or the mesh file, is named like scenery: a word of the name (split at
  non-letters and before a capital: `terrainLink`, `ground_plane`, `ramps.obj`) is ground,
  terrain, floor, ramp(s), stair(s), staircase, scene, world, plane, heightfield,
  heightmap, arena or slope.

A robot part is never exempt: a link with a joint that moves, named like a part, keeps
the 10 m limit, and a mesh under 1 mm is reported on scenery too.

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
from urdflint.model.scenery import scenery as scenery_of
from urdflint.model.structure import q
from urdflint.model.values import fmt
from urdflint.sources.meshes import MAX_EXTENT, load, references, scale_hint, suspicious_size

SCENERY_MAX = 1000.0  # m: the largest side scenery (a terrain, a scene) may have


@rule(
    "C006",
    "mesh-scale-suspicious",
    Severity.WARNING,
    fix="Export the mesh in metres (REP 103) or set <mesh scale> to convert it.",
    needs=("trimesh",),
)
def check(doc: Document) -> Iterator[Hit]:
    for ref in references(doc):
        info = load(doc, ref)
        scale = ref.scale
        if info is None or scale is None or not suspicious_size(info):
            continue
        scenery = info.largest > MAX_EXTENT and scenery_of(doc, ref.link, ref.uri) is not None
        if scenery and info.largest <= SCENERY_MAX:
            continue  # a terrain, a plane or a scene may be large
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
