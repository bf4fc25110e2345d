"""C018 mesh-without-volume: a collision mesh as MuJoCo's compiler computes it.

The fixture is IsaacGymEnvs' factory_rectangular_hole_8mm (its OBJ's first object is flat);
the planted meshes are checked against MuJoCo itself when it is installed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.engine import config
from urdflint.model.finding import Finding, Severity
from urdflint.sources.mujoco_mesh import MINVAL, compile_mesh

HERE = FIXTURES / "rules" / "C018"
MESH = "/robot/link[@name='factory_rectangular_hole_8mm']/collision/geometry/mesh"
TOO_SMALL = "mesh volume is too small: {} . Try setting inertia to shell"
INERTIAL = """<inertial><mass value="0.05"/>
      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>"""


def c018(path: Path, targets: tuple[str, ...] = ("mujoco",)) -> list[Finding]:
    settings = config.from_mapping({"targets": list(targets)})
    return [f for f in lint_file(path, ("C018",), settings) if f.code == "C018"]


def write_obj(path: Path, parts: list[tuple[str, object]], tag: str = "o") -> Path:
    """An OBJ file of named objects (trimesh meshes), in order."""
    lines, offset = [], 1
    for name, mesh in parts:
        lines.append(f"{tag} {name}")
        lines += [f"v {x:.6g} {y:.6g} {z:.6g}" for x, y, z in mesh.vertices]  # type: ignore[attr-defined]
        lines += [f"f {a + offset} {b + offset} {c + offset}" for a, b, c in mesh.faces]  # type: ignore[attr-defined]
        offset += len(mesh.vertices)  # type: ignore[attr-defined]
    path.write_text("\n".join(lines) + "\n")
    return path


def robot(
    tmp_path: Path, mesh: str, role: str = "collision", extra: str = "", mujoco: str = ""
) -> Path:
    path = tmp_path / "part.urdf"
    path.write_text(f"""<?xml version="1.0"?>
<robot name="part">
  <link name="base"/>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="part"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.1" effort="10" velocity="1"/></joint>
  <link name="part">{extra}
    <{role}><geometry><mesh filename="{mesh}"/></geometry></{role}>
  </link>{mujoco}
</robot>
""")
    return path


@pytest.fixture
def trimesh():
    return pytest.importorskip("trimesh")


# -- the fixture --------------------------------------------------------------------------------


def test_isaac_gym_hole_exact_finding() -> None:
    [found] = c018(HERE / "bad.urdf")
    assert (Path(found.path).name, found.line, found.element, found.severity) == (
        "bad.urdf", 18, MESH, Severity.ERROR,
    )  # fmt: skip
    assert found.message == (
        "collision mesh 'meshes/factory_rectangular_hole_8mm_subdiv_3x.obj' of link "
        "'factory_rectangular_hole_8mm': MuJoCo refuses it (\""
        + TOO_SMALL.format("factory_rectangular_hole_8mm_subdiv_3x")
        + "\"): it reads only the first of the file's 10 objects, 'mesh0', 2 of 1,040 "
        "triangles, 0 m³"
    )
    [(target, effect)] = found.effects
    assert (target, effect.consequence.key) == ("mujoco", "refused")


def test_only_for_mujoco() -> None:
    assert c018(HERE / "bad.urdf", ("gazebo-classic", "drake", "pybullet", "pinocchio")) == []
    assert c018(HERE / "good.urdf") == []  # the same part, one object


def test_an_inertial_does_not_help(tmp_path: Path) -> None:
    """MuJoCo computes every collision mesh's volume, whether or not it weighs the link."""
    mesh = HERE / "meshes" / "factory_rectangular_hole_8mm_subdiv_3x.obj"
    assert len(c018(robot(tmp_path, str(mesh), extra=INERTIAL))) == 1


def test_visual_meshes_only_when_mujoco_keeps_them(tmp_path: Path) -> None:
    mesh = str(HERE / "meshes" / "factory_rectangular_hole_8mm_subdiv_3x.obj")
    assert c018(robot(tmp_path, mesh, "visual", INERTIAL)) == []
    keep = '<mujoco><compiler discardvisual="false"/></mujoco>'
    [found] = c018(robot(tmp_path, mesh, "visual", INERTIAL, keep))
    assert found.message.startswith("visual mesh ")


# -- what MuJoCo computes -----------------------------------------------------------------------


def test_first_object_of_an_obj(tmp_path: Path, trimesh) -> None:
    cube = trimesh.creation.box((0.04, 0.04, 0.04))
    flat = trimesh.Trimesh(
        [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], [[0, 1, 2], [0, 2, 3]]
    )
    for tag in ("o", "g"):
        first = compile_mesh(
            write_obj(tmp_path / f"f{tag}.obj", [("cap", flat), ("b", cube)], tag), (1, 1, 1)
        )
        assert first is not None and (first.faces, first.total, first.objects) == (2, 14, 2)
        assert first.first == "cap" and first.volume < MINVAL
        assert first.refusal("f") == TOO_SMALL.format("f")
    solid = compile_mesh(write_obj(tmp_path / "s.obj", [("b", cube), ("cap", flat)]), (1, 1, 1))
    assert (
        solid is not None and solid.volume == pytest.approx(6.4e-5) and solid.refusal("s") is None
    )


def test_obj_polygons_and_negative_indices(tmp_path: Path) -> None:
    path = tmp_path / "quad.obj"
    cube = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    quads = ["-8 -7 -5 -6", "1 5 6 2", "1 3 7 5", "2 6 8 4", "3 4 8 7", "5 7 8 6"]  # 1 2 4 3
    path.write_text(
        "".join(f"v {x} {y} {z}\n" for x, y, z in cube) + "".join(f"f {q}\n" for q in quads)
    )
    found = compile_mesh(path, (0.1, 0.1, 0.1))
    assert found is not None and (found.faces, found.objects) == (12, 1)
    assert found.volume == pytest.approx(1e-3)


@pytest.mark.parametrize(
    ("name", "refused"),
    [
        ("open", None),
        ("inverted", None),
        ("flat", "coplanar"),
        ("tiny", "too small"),
        ("cube", None),
    ],
)
def test_stl_meshes_as_mujoco_compiles_them(tmp_path: Path, trimesh, name: str, refused) -> None:
    """An open box loads (0.81 of the closed one's volume, MuJoCo's legacy inertia), an
    inside-out cube too; a flat plate has no hull; a 9 µm cube (7.3e-16 m³) is too small."""
    path = _stl(trimesh, tmp_path, name)
    found = compile_mesh(path, (1, 1, 1))
    assert found is not None
    message = found.refusal(name)
    assert (message is None) if refused is None else (refused in (message or ""))
    if name == "open":  # pyramids to the faces' centroid (MuJoCo then weighs it 0.815 kg)
        assert found.volume == pytest.approx(0.8111e-3, rel=1e-4)
    mujoco = pytest.importorskip("mujoco")
    try:
        mujoco.MjModel.from_xml_string(
            f'<mujoco><asset><mesh name="{name}" file="{path}"/></asset><worldbody><body>'
            f'<freejoint/><geom type="mesh" mesh="{name}"/></body></worldbody></mujoco>'
        )
        observed = None
    except ValueError as exc:
        observed = str(exc).splitlines()[0].removeprefix("Error: ")
    if message is None:
        assert observed is None or "mjMINVAL" in observed
    else:
        assert observed == message


def _stl(trimesh, folder: Path, name: str) -> Path:
    box = trimesh.creation.box((0.1, 0.1, 0.1))
    if name == "open":
        box.update_faces(np.arange(len(box.faces)) >= 2)
    elif name == "inverted":
        box.invert()
    elif name == "flat":
        box = trimesh.Trimesh(
            [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], [[0, 1, 2], [0, 2, 3]]
        )
    elif name == "tiny":
        box = trimesh.creation.box((9e-6, 9e-6, 9e-6))
    path = folder / f"{name}.stl"
    box.export(path)
    return path


def test_scale_applies(tmp_path: Path, trimesh) -> None:
    path = _stl(trimesh, tmp_path, "cube")
    assert compile_mesh(path, (5e-5, 5e-5, 5e-5)).refusal("cube") == TOO_SMALL.format("cube")  # type: ignore[union-attr]
    assert compile_mesh(tmp_path / "none.dae", (1, 1, 1)) is None
