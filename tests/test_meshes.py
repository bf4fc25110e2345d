"""Mesh loading (urdflint.meshes) and the mesh rules C004-C009, I007/I008 beyond their fixtures."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests.conftest import FIXTURES, ROOT
from tests.helpers import lint_file
from urdflint.engine import config, linter, registry
from urdflint.engine.context import Context
from urdflint.model import optional
from urdflint.model.finding import Severity
from urdflint.sources.mesh_cache import MeshCache
from urdflint.sources.mesh_formats import suffix
from urdflint.sources.meshes import scale_hint

trimesh = pytest.importorskip("trimesh")

BOX_OBJ = FIXTURES / "rules" / "I007" / "meshes" / "box.obj"  # 0.1 x 0.1 x 0.3 m, z 0..0.3
OPEN_OBJ = FIXTURES / "rules" / "I007" / "meshes" / "open_box.obj"  # the same without its top
BOX_MM = FIXTURES / "rules" / "C006" / "meshes" / "box_mm.obj"
approx = pytest.approx


def robot(body: str, extra: str = "") -> str:
    """A valid two-link URDF whose moving link has ``body`` after its inertial."""
    return (
        textwrap.dedent(
            """\
        <?xml version="1.0"?>
        <robot name="arm">
          <link name="base_link"/>
          <joint name="shoulder" type="revolute">
            <parent link="base_link"/>
            <child link="upper_arm"/>
            <axis xyz="0 0 1"/>
            <limit lower="-1" upper="1" effort="30" velocity="2"/>
          </joint>
          <link name="upper_arm">
            <inertial>
              <origin xyz="0 0 0.15"/>
              <mass value="1"/>
              <inertia ixx="0.00833" ixy="0" ixz="0" iyy="0.00833" iyz="0" izz="0.00167"/>
            </inertial>
        """
        )
        + textwrap.indent(textwrap.dedent(body), "    ")
        + "  </link>\n"
        + extra
        + "</robot>\n"
    )


def lint(
    text: str,
    folder: Path,
    select: tuple[str, ...],
    context: Context | None = None,
    **settings: object,
) -> linter.Result:
    path = folder / "robot.urdf"
    path.write_text(text)
    base = config.from_mapping(dict(settings)) if settings else config.Settings()
    chosen = config.Settings(**{**base.__dict__, "select": select})
    return linter.lint_path(path, str(path), chosen, context or Context())


def mesh(filename: str, tag: str = "collision", scale: str | None = None) -> str:
    scale_attr = f' scale="{scale}"' if scale else ""
    return f'<{tag}><geometry><mesh filename="{filename}"{scale_attr}/></geometry></{tag}>\n'


# -- MeshCache ------------------------------------------------------------------------------


def test_box_is_read_with_its_size_and_mass_properties() -> None:
    info = MeshCache().load(BOX_OBJ, (1.0, 1.0, 1.0))
    assert info.error is None and info.format == "obj"
    assert (info.faces, info.vertices) == (12, 8)
    assert info.lo == approx((-0.05, -0.05, 0.0)) and info.hi == approx((0.05, 0.05, 0.3))
    assert info.extents == approx((0.1, 0.1, 0.3)) and info.largest == approx(0.3)
    assert info.watertight and info.volume == approx(0.003)
    tensor, kind = info.inertia(2.0)
    assert kind == "mesh"
    assert [tensor[i][i] for i in range(3)] == approx([2 * 0.1 / 12, 2 * 0.1 / 12, 2 * 0.02 / 12])
    com, _ = info.center_mass()
    assert com == approx((0.0, 0.0, 0.15), abs=1e-12)


def test_scale_applies_to_bounds_volume_and_inertia() -> None:
    info = MeshCache().load(BOX_MM, (0.001, 0.001, 0.001))
    assert info.extents == approx((0.1, 0.1, 0.3))
    assert info.volume == approx(0.003)
    stretched = MeshCache().load(BOX_OBJ, (2.0, 1.0, 1.0))
    assert stretched.extents == approx((0.2, 0.1, 0.3))
    assert stretched.volume == approx(0.006)


def test_mirroring_scale_keeps_a_positive_solid() -> None:
    info = MeshCache().load(BOX_OBJ, (1.0, -1.0, 1.0))
    assert info.lo == approx((-0.05, -0.05, 0.0)) and info.hi == approx((0.05, 0.05, 0.3))
    assert info.watertight and info.volume == approx(0.003)
    tensor, kind = info.inertia(1.0)
    assert kind == "mesh" and tensor[2][2] == approx(0.02 / 12)
    flipped = MeshCache().load(BOX_OBJ, (-1.0, -1.0, -1.0))
    assert flipped.volume == approx(0.003) and flipped.lo[2] == approx(-0.3)


def test_open_mesh_falls_back_to_its_convex_hull() -> None:
    info = MeshCache().load(OPEN_OBJ, (1.0, 1.0, 1.0))
    assert info.error is None and not info.watertight and info.volume is None
    tensor, kind = info.inertia(1.0)
    assert kind == "convex hull"
    assert tensor[0][0] == approx(0.1 / 12)
    assert info.center_mass()[0] == approx((0.0, 0.0, 0.15), abs=1e-9)


def test_flat_mesh_has_no_solid(tmp_path: Path) -> None:
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")
    info = MeshCache().load(flat, (1.0, 1.0, 1.0))
    assert info.error is None and info.solid() is None and info.inertia(1.0) is None


def test_loaded_once_per_path_and_scale() -> None:
    cache = MeshCache()
    first = cache.load(BOX_OBJ, (1.0, 1.0, 1.0))
    again = cache.load(BOX_OBJ.parent / "." / BOX_OBJ.name, (1, 1, 1))  # same file, other spelling
    assert again is first and cache.loads == 1
    cache.load(BOX_OBJ, (2.0, 1.0, 1.0))
    assert cache.loads == 2 and len(cache) == 2


def test_every_mesh_rule_shares_one_load(tmp_path: Path) -> None:
    (tmp_path / "box.obj").write_bytes(BOX_OBJ.read_bytes())
    text = robot(mesh("box.obj", "visual") + mesh("box.obj"))
    context = Context()
    selected = ("C004", "C005", "C006", "C007", "C008", "C009", "I007", "I008")
    result = lint(text, tmp_path, selected, context)
    assert not result.crashed
    assert context.meshes.loads == 1


@pytest.mark.parametrize(
    ("name", "content", "reason"),
    [
        ("empty.stl", b"", "the file is empty"),
        ("solid.stl", b"solid x\nendsolid x\n", "the file holds no triangles"),
        ("lfs.stl", b"version https://git-lfs.github.com/spec/v1\noid sha256:00\n", "Git LFS"),
        ("page.stl", b"<!DOCTYPE html><html><body>404</body></html>", "HTML page"),
        ("junk.obj", b"v 1 2\nf 1 2 3 4 5\nv nan nan nan\n", ""),
        ("noise.stl", bytes(range(256)) * 40, ""),
        ("bad.dae", b"<COLLADA><library_geometries><geometry>", "trimesh could not read it"),
    ],
)
def test_broken_files_become_errors_never_exceptions(
    tmp_path: Path, name: str, content: bytes, reason: str
) -> None:
    path = tmp_path / name
    path.write_bytes(content)
    info = MeshCache().load(path, (1.0, 1.0, 1.0))
    assert info.error is not None and reason in info.error
    assert "\n" not in info.error and not info.unsupported


def test_collada_with_a_doctype_is_not_read(tmp_path: Path) -> None:
    path = tmp_path / "bomb.dae"
    path.write_text('<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "aaaa">]><COLLADA/>')
    info = MeshCache().load(path, (1.0, 1.0, 1.0))
    assert info.error is not None and "DOCTYPE" in info.error


def test_formats_trimesh_does_not_read_and_size_cap_are_unsupported(tmp_path: Path) -> None:
    blend = tmp_path / "part.blend"
    blend.write_bytes(b"BLENDER-v300")
    info = MeshCache().load(blend, (1.0, 1.0, 1.0))
    assert info.unsupported and "cannot read" in (info.error or "")
    big = MeshCache(max_bytes=100).load(BOX_OBJ, (1.0, 1.0, 1.0))
    assert big.unsupported and "limit" in (big.error or "")
    missing = MeshCache().load(tmp_path / "missing.stl", (1.0, 1.0, 1.0))
    assert missing.error is not None and "cannot read the file" in missing.error


def test_root_confines_mesh_reads(tmp_path: Path) -> None:
    inside = tmp_path / "inside"
    inside.mkdir()
    (inside / "box.obj").write_bytes(BOX_OBJ.read_bytes())
    cache = MeshCache(root=inside)
    assert cache.load(inside / "box.obj", (1.0, 1.0, 1.0)).error is None
    outside = cache.load(BOX_OBJ, (1.0, 1.0, 1.0))
    assert outside.error is not None and "outside the allowed folder" in outside.error
    assert cache.loads == 1


def test_obj_materials_and_textures_are_not_read(tmp_path: Path) -> None:
    (tmp_path / "box.mtl").write_text("newmtl m\nmap_Kd /etc/passwd\n")
    (tmp_path / "box.obj").write_text("mtllib box.mtl\nusemtl m\n" + BOX_OBJ.read_text())
    info = MeshCache(root=tmp_path).load(tmp_path / "box.obj", (1.0, 1.0, 1.0))
    assert info.error is None and info.faces == 12


def test_scale_hint() -> None:
    assert scale_hint(300.0) == [(0.001, "millimetres")]
    assert [f for f, _ in scale_hint(20.0)] == [0.001, 0.01]
    assert [f for f, _ in scale_hint(0.0003)] == [1000.0]
    assert scale_hint(1e9) == [] and scale_hint(0.5) == []
    assert suffix("package://p/m/Link.STL") == "stl" and suffix("meshes/noext") == ""


# -- optional modules -----------------------------------------------------------------------


def test_only_loading_rules_need_trimesh() -> None:
    rules = registry.load_rules()
    for code in ("C005", "C006", "C007"):
        assert rules[code].needs == ("trimesh",)
    for code in ("C004", "C008", "C009", "I007", "I008"):
        assert rules[code].needs == ()


def _imports(script: str) -> set[str]:
    code = textwrap.dedent(script) + "\nimport sys\nprint(' '.join(sorted(sys.modules)))\n"
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    return set(proc.stdout.split())


def test_a_urdf_without_meshes_never_imports_trimesh() -> None:
    modules = _imports(
        f"""
        from pathlib import Path
        from urdflint.engine import config, linter
        linter.lint_path(Path({str(FIXTURES / "models" / "template_good.urdf")!r}), "x",
                         config.Settings(select=("C", "I")))
        """
    )
    assert "trimesh" not in modules


def test_unresolved_meshes_and_c004_never_import_trimesh() -> None:
    modules = _imports(
        f"""
        from pathlib import Path
        from urdflint.engine import config, linter
        linter.lint_path(Path({str(FIXTURES / "rules" / "C002" / "good.urdf")!r}), "x",
                         config.Settings())
        linter.lint_path(Path({str(FIXTURES / "rules" / "C004" / "good.urdf")!r}), "x",
                         config.Settings(select=("C004", "C008", "C009")))
        """
    )
    assert "trimesh" not in modules


def test_light_install_keeps_the_primitive_checks(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(optional, "available", lambda module: module != "trimesh")
    primitive = FIXTURES / "rules" / "I007" / "bad.urdf"
    assert [f.code for f in lint_file(primitive, select=("I007",))] == ["I007"]
    for code in ("I007", "I008"):
        bad = FIXTURES / "rules" / code / "bad_mesh.urdf"
        assert lint_file(bad, select=(code,)) == []
    skipped = linter.lint_path(
        FIXTURES / "rules" / "C006" / "bad.urdf", "x", config.Settings(select=("C006",))
    ).skipped
    assert skipped == {"C006": ("trimesh",)}


# -- C004 -----------------------------------------------------------------------------------


def test_unconfigured_packages_give_one_note_per_package(tmp_path: Path) -> None:
    body = "".join(
        mesh(f"package://{pkg}/meshes/{n}.stl", tag)
        for pkg, n, tag in [("a", "x", "visual"), ("a", "y", "collision"), ("b", "z", "visual")]
    )
    found = lint(robot(body), tmp_path, ("C004",), Context(environ={})).findings
    assert [(f.severity, f.line) for f in found] == [(Severity.INFO, 16), (Severity.INFO, 18)]
    assert "its 2 mesh references are not checked" in found[0].message
    assert "package 'b' was not found" in found[1].message


def test_configured_packages_report_every_missing_mesh(tmp_path: Path) -> None:
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "pkg" / "meshes" / "box.obj").write_bytes(BOX_OBJ.read_bytes())
    body = (
        mesh("package://pkg/meshes/box.obj", "visual")
        + mesh("package://pkg/meshes/box.stl", "visual")
        + mesh("package:///pkg/meshes/gone.stl")
        + mesh("package://other/meshes/box.obj")
    )
    context = Context(package_paths={"pkg": tmp_path / "pkg"}, environ={})
    found = lint(robot(body), tmp_path, ("C004",), context).findings
    assert [(f.line, f.severity) for f in found] == [
        (17, Severity.ERROR),
        (18, Severity.ERROR),
        (19, Severity.WARNING),
    ]
    assert f"no file at {tmp_path / 'pkg' / 'meshes' / 'box.stl'}" in found[0].message
    assert found[0].message.endswith("; the folder has 'box.obj'")
    assert found[1].message.endswith(f"no file at {tmp_path / 'pkg' / 'meshes' / 'gone.stl'}")
    assert "package 'other' was not found (looked in: package path" not in found[2].message
    assert "looked in:" in found[2].message


def test_ros_package_path_and_package_xml_are_searched(tmp_path: Path) -> None:
    pkg = tmp_path / "ws" / "src" / "my_robot"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>my_robot</name></package>")
    (pkg / "meshes" / "box.obj").write_bytes(BOX_OBJ.read_bytes())
    text = robot(mesh("package://my_robot/meshes/box.obj"))
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "ws")}
    assert lint(text, tmp_path, ("C004", "C005"), Context(environ=env)).findings == []
    (pkg / "urdf").mkdir()
    path = pkg / "urdf" / "robot.urdf"
    path.write_text(text)
    result = linter.lint_path(
        path, str(path), config.Settings(select=("C004",)), Context(environ={})
    )
    assert result.findings == []


def test_confined_root_refuses_paths_outside(tmp_path: Path) -> None:
    text = robot(mesh(f"file://{BOX_OBJ}") + mesh("../escape.stl", "visual"))
    found = lint(text, tmp_path, ("C004", "C005"), Context(root=tmp_path, environ={})).findings
    assert {f.code for f in found} == {"C004"}
    assert all("outside the allowed folder" in f.message for f in found)


def test_unsupported_scheme_is_a_note(tmp_path: Path) -> None:
    found = lint(robot(mesh("model://arm/meshes/a.dae")), tmp_path, ("C004",)).findings
    assert [(f.severity, f.code) for f in found] == [(Severity.INFO, "C004")]
    assert "model:// scheme is not supported" in found[0].message


# -- C006 to C009 and I007/I008 on generated files ---------------------------------------------


def test_c006_suggests_centimetres_and_inches(tmp_path: Path) -> None:
    box = trimesh.creation.box((20.0, 10.0, 10.0))  # 20 cm across, written in centimetres
    box.export(tmp_path / "cm.stl")
    found = lint(robot(mesh("cm.stl")), tmp_path, ("C006",)).findings
    assert len(found) == 1
    assert found[0].message.endswith(
        'probably millimetres (scale="0.001 0.001 0.001" makes it 0.02 m) '
        'or centimetres (scale="0.01 0.01 0.01" makes it 0.2 m)'
    )


def test_c007_counts_collada_scenes_and_respects_the_option(tmp_path: Path) -> None:
    sphere = trimesh.creation.icosphere(subdivisions=3)  # 1280 faces
    parts = [sphere, sphere.copy().apply_translation((3, 0, 0))]
    (tmp_path / "two.dae").write_bytes(trimesh.exchange.dae.export_collada(parts))
    text = robot(mesh("two.dae", scale="0.1 0.1 0.1"))
    found = lint(text, tmp_path, ("C007",), rules={"C007": {"max-faces": 2000}}).findings
    assert len(found) == 1 and "2,560 triangles" in found[0].message
    assert lint(text, tmp_path, ("C007",)).findings == []


def test_c009_checks_every_selected_target(tmp_path: Path) -> None:
    body = mesh("a.glb") + mesh("b.dae", "visual")
    found = lint(robot(body), tmp_path, ("C009",), targets=["gazebo-classic", "mujoco"]).findings
    assert [(f.severity, f.line) for f in found] == [(Severity.ERROR, 16)]
    assert found[0].message.startswith("Gazebo Classic and MuJoCo cannot load GLB")
    assert lint(robot(body), tmp_path, ("C009",), targets=["gz-sim"]).findings == []


def test_i007_skips_meshes_that_c006_reports(tmp_path: Path) -> None:
    (tmp_path / "box_mm.obj").write_bytes(BOX_MM.read_bytes())
    found = lint(robot(mesh("box_mm.obj")), tmp_path, ("I007", "C006")).findings
    assert [f.code for f in found] == ["C006"]


def test_i008_places_rotated_meshes_in_the_link_frame(tmp_path: Path) -> None:
    (tmp_path / "box.obj").write_bytes(BOX_OBJ.read_bytes())
    # the 0.3 m box lies along +x once rotated by -90 degrees about y; the COM is at z 0.15
    rotated = (
        '<collision><origin rpy="0 -1.5707963 0"/>'
        '<geometry><mesh filename="box.obj"/></geometry></collision>\n'
    )
    found = lint(robot(rotated), tmp_path, ("I008",)).findings
    assert len(found) == 1 and "x -3e-08…0.3" not in found[0].message
    assert "outside its geometry (x" in found[0].message
    upright = lint(robot(mesh("box.obj")), tmp_path, ("I008",)).findings
    assert upright == []


# -- Collada units ---------------------------------------------------------------------------


def collada_box(path: Path, size: tuple[float, float, float], unit: str | None) -> Path:
    """A Collada box ``size`` file units across (z from 0), declaring ``unit`` metres per unit."""
    sx, sy, sz = size
    corners = [(x, y, z) for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2) for z in (0, sz)]
    positions = " ".join(f"{v:g}" for corner in corners for v in corner)
    triangles = "0 3 1 0 2 3 4 5 7 4 7 6 0 1 5 0 5 4 2 6 7 2 7 3 0 4 6 0 6 2 1 3 7 1 7 5"
    asset = f'<unit name="u" meter="{unit}"/>' if unit is not None else ""
    path.write_text(
        '<?xml version="1.0"?>\n'
        '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">'
        f"<asset>{asset}<up_axis>Z_UP</up_axis></asset>"
        '<library_geometries><geometry id="g"><mesh><source id="p">'
        f'<float_array id="a" count="24">{positions}</float_array><technique_common>'
        '<accessor source="#a" count="8" stride="3"><param name="X" type="float"/>'
        '<param name="Y" type="float"/><param name="Z" type="float"/></accessor>'
        '</technique_common></source><vertices id="v"><input semantic="POSITION" source="#p"/>'
        '</vertices><triangles count="12"><input semantic="VERTEX" source="#v" offset="0"/>'
        f"<p>{triangles}</p></triangles></mesh></geometry></library_geometries>"
        '<library_visual_scenes><visual_scene id="s"><node id="n" name="n">'
        '<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>'
        '<scene><instance_visual_scene url="#s"/></scene></COLLADA>\n'
    )
    return path


@pytest.mark.parametrize(
    ("unit", "size"),
    [("0.0254", 0.254), ("0.001", 0.01), ("1", 10.0), (None, 10.0), ("abc", 10.0), ("0", 10.0)],
)
def test_collada_unit_is_applied_like_gazebo_and_rviz(
    tmp_path: Path, unit: str | None, size: float
) -> None:
    """A 10-unit cube: PyBullet reports a 0.254 m / 0.01 m box for inches / millimetres."""
    path = collada_box(tmp_path / "cube.dae", (10.0, 10.0, 10.0), unit)
    info = MeshCache().load(path)
    assert info.error is None
    assert info.extents == approx((size, size, size))
    assert info.unit == approx(size / 10.0)
    assert info.volume == approx(size**3)


def test_collada_unit_combines_with_the_urdf_scale(tmp_path: Path) -> None:
    path = collada_box(tmp_path / "box.dae", (100.0, 100.0, 300.0), "0.001")
    info = MeshCache().load(path, (2.0, 1.0, 1.0))
    assert info.extents == approx((0.2, 0.1, 0.3))
    assert info.center_mass()[0] == approx((0.0, 0.0, 0.15))


def test_c006_names_the_collada_unit_when_scaled_twice(tmp_path: Path) -> None:
    collada_box(tmp_path / "box.dae", (100.0, 100.0, 300.0), "0.001")
    assert lint(robot(mesh("box.dae")), tmp_path, ("C006",)).findings == []
    found = lint(robot(mesh("box.dae", scale="0.001 0.001 0.001")), tmp_path, ("C006",)).findings
    assert len(found) == 1
    assert "0.0003 m across with scale 0.001 0.001 0.001 and its Collada unit of 0.001 m" in (
        found[0].message
    )


def test_i007_and_i008_see_the_collada_unit(tmp_path: Path) -> None:
    """0.05 x 0.05 x 0.15 m written in inches: 5.9 units tall, plausible in metres too."""
    inches = 1 / 0.0254
    collada_box(tmp_path / "in.dae", (0.05 * inches, 0.05 * inches, 0.15 * inches), "0.0254")
    inertia = (
        '<inertial><origin xyz="0 0 0.075"/><mass value="1"/>'
        '<inertia ixx="0.002083" ixy="0" ixz="0" iyy="0.002083" iyz="0" izz="0.000417"/>'
        "</inertial>"
    )
    body = f'<link name="part">{inertia}{mesh("in.dae")}</link>'
    text = robot("", extra=_fixed_to_arm("part") + body)
    assert lint(text, tmp_path, ("I007", "I008", "C006")).findings == []
    far = text.replace('<origin xyz="0 0 0.075"/>', '<origin xyz="0 0 0.5"/>')
    assert [f.code for f in lint(far, tmp_path, ("I008",)).findings] == ["I008"]
    heavy = text.replace('ixx="0.002083"', 'ixx="2"').replace('iyy="0.002083"', 'iyy="2"')
    assert [f.code for f in lint(heavy, tmp_path, ("I007",)).findings] == ["I007"]


def _fixed_to_arm(child: str) -> str:
    return (
        f'<joint name="{child}_joint" type="fixed"><parent link="upper_arm"/>'
        f'<child link="{child}"/></joint>\n'
    )


def test_collada_up_axis_is_not_applied_like_gazebo(tmp_path: Path) -> None:
    """Gazebo's ColladaLoader reads <unit> but not <up_axis>; trimesh ignores it too."""
    path = collada_box(tmp_path / "y_up.dae", (10.0, 20.0, 40.0), "0.01")
    path.write_text(path.read_text().replace("Z_UP", "Y_UP"))
    assert MeshCache().load(path).extents == approx((0.1, 0.2, 0.4))


def test_collada_with_a_broken_texture_binding_is_read_without_its_materials() -> None:
    pytest.importorskip("collada")
    path = FIXTURES / "rules" / "C005" / "meshes" / "broken_texture_binding.dae"
    info = MeshCache().load(path)
    assert info.error is None and info.faces == 4
    assert info.hi == pytest.approx((0.1, 0.1, 0.1), rel=1e-6)  # node transform applied
