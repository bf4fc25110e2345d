"""C014 non-portable-mesh-path, C015 package-not-a-dependency, C016 path-case-mismatch and
the package.xml reader they share (urdflint.sources.package_xml)."""

from __future__ import annotations

from pathlib import Path, PurePosixPath

from urdflint.rules.geometry.c014_non_portable_mesh_path import local_path
from urdflint.rules.geometry.c016_path_case_mismatch import case_variant

from tests.helpers import lint_file, lint_text
from urdflint.engine import config
from urdflint.model.finding import Severity
from urdflint.sources import package_xml

INERTIAL = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
)


def robot(*filenames: str) -> str:
    visuals = "".join(
        f'\n    <visual><geometry><mesh filename="{f}"/></geometry></visual>' for f in filenames
    )
    return f'<robot name="r">\n  <link name="base">{INERTIAL}{visuals}\n  </link>\n</robot>\n'


def manifest(name: str, *deps: tuple[str, str], fmt: int = 3) -> str:
    lines = "".join(f"  <{tag}>{dep}</{tag}>\n" for tag, dep in deps)
    head = f'<?xml version="1.0"?>\n<package format="{fmt}">\n  <name>{name}</name>\n'
    return f"{head}{lines}</package>\n"


def make_package(root: Path, name: str, *deps: tuple[str, str]) -> Path:
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "meshes" / "box.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (root / "package.xml").write_text(manifest(name, *deps))
    return root


def lint(path: Path, code: str) -> list:
    return [f for f in lint_file(path, (code,), config.Settings()) if f.code == code]


# -- C014 --------------------------------------------------------------------------------


def test_local_path_kinds() -> None:
    assert local_path("file:///home/a/x.stl") == ("file", "/home/a/x.stl")
    assert local_path("file://meshes/x.stl") == ("file-relative", "meshes/x.stl")
    assert local_path("/home/a/x.stl") == ("absolute", "/home/a/x.stl")
    assert local_path("C:\\robots\\x.stl") == ("absolute", "C:\\robots\\x.stl")
    assert local_path("C:/robots/x.stl") == ("absolute", "C:/robots/x.stl")
    for portable in ("package://p/x.stl", "meshes/x.stl", "model://m/x.stl", "x.stl"):
        assert local_path(portable) is None


def test_absolute_path_inside_a_package_names_its_package_uri(tmp_path: Path) -> None:
    pkg = make_package(tmp_path / "src" / "demo", "demo_description")
    mesh = pkg / "meshes" / "box.obj"
    urdf = pkg / "urdf" / "robot.urdf"
    urdf.write_text(robot(str(mesh), f"file://{mesh}"))
    found = lint(urdf, "C014")
    assert [(f.line, f.element, f.severity) for f in found] == [
        (3, "/robot/link[@name='base']/visual[1]/geometry/mesh", Severity.WARNING),
        (4, "/robot/link[@name='base']/visual[2]/geometry/mesh", Severity.WARNING),
    ]
    assert "is an absolute path" in found[0].message
    assert "MuJoCo cannot open file:// URIs" in found[1].message
    for finding in found:
        assert (
            finding.fix
            == "Write 'package://demo_description/meshes/box.obj': the file is inside that package."
        )


def test_install_layout_suggests_the_package_and_relative_file_uri_is_reported() -> None:
    text = robot("/opt/ros/humble/share/arm_description/meshes/base.stl", "file://meshes/box.stl")
    found = [f for f in lint_text(text, ("C014",)) if f.code == "C014"]
    assert [f.line for f in found] == [3, 4]
    assert found[0].fix == (
        "Write 'package://arm_description/meshes/base.stl' "
        "(the path is inside that package's install folder)."
    )
    assert "relative path" in found[1].message


def test_portable_references_are_not_reported() -> None:
    text = robot("package://p/meshes/a.stl", "meshes/a.stl", "model://m/a.stl")
    assert [f for f in lint_text(text, ("C014",)) if f.code == "C014"] == []


def test_xacro_find_is_not_reported_but_a_literal_path_is(tmp_path: Path) -> None:
    pkg = make_package(tmp_path / "demo", "demo_description")
    xacro = pkg / "urdf" / "robot.urdf.xacro"
    xacro.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <link name="base">{INERTIAL}\n'
        '    <visual><geometry><mesh filename="file://$(find demo_description)/meshes/box.obj"/>'
        "</geometry></visual>\n"
        '    <visual><geometry><mesh filename="/tmp/elsewhere/box.obj"/></geometry></visual>\n'
        "  </link>\n</robot>\n"
    )
    found = lint(xacro, "C014")
    assert [(Path(f.path).name, f.line) for f in found] == [("robot.urdf.xacro", 4)]


# -- package.xml ---------------------------------------------------------------------------


def test_manifest_runtime_tags(tmp_path: Path) -> None:
    deps = [
        ("depend", "a"), ("exec_depend", "b"), ("build_export_depend", "c"),
        ("buildtool_export_depend", "d"), ("build_depend", "no1"), ("test_depend", "no2"),
        ("doc_depend", "no3"),
    ]  # fmt: skip
    (tmp_path / "package.xml").write_text(manifest("me", *deps))
    read = package_xml.read(tmp_path)
    assert read.problem is None and read.name == "me"
    assert read.runtime == {"a", "b", "c", "d"}
    assert read.provides("me") and read.provides("b") and not read.provides("no1")


def test_manifest_format_1_run_depend(tmp_path: Path) -> None:
    (tmp_path / "package.xml").write_text(manifest("old", ("run_depend", "x"), fmt=1))
    assert package_xml.read(tmp_path).runtime == {"x"}


def test_malformed_manifests(tmp_path: Path) -> None:
    cases = {
        "broken": "<package><name>x</name>",
        "wrong_root": "<manifest><name>x</name></manifest>",
        "entity": '<!DOCTYPE p [<!ENTITY e "dep">]><package><name>x</name>'
        "<depend>&e;</depend></package>",
    }
    for folder, text in cases.items():
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "package.xml").write_text(text)
    assert "not well-formed" in (package_xml.read(tmp_path / "broken").problem or "")
    assert "no <package> root" in (package_xml.read(tmp_path / "wrong_root").problem or "")
    entity = package_xml.read(tmp_path / "entity")
    assert "dep" not in entity.runtime  # never expanded
    (tmp_path / "big").mkdir()
    (tmp_path / "big" / "package.xml").write_bytes(b" " * ((1 << 20) + 1))
    assert "over 1 MiB" in (package_xml.read(tmp_path / "big").problem or "")


def test_enclosing_and_package_uri(tmp_path: Path) -> None:
    pkg = make_package(tmp_path / "ws" / "demo", "demo_description")
    mesh = pkg / "meshes" / "box.obj"
    assert package_xml.enclosing(mesh) == pkg
    assert package_xml.enclosing(mesh, stop=pkg / "meshes") is None
    assert package_xml.package_uri(mesh) == "package://demo_description/meshes/box.obj"
    guess = package_xml.installed_package_uri(PurePosixPath("/x/install/p/share/p/m/a.stl"))
    assert guess == "package://p/m/a.stl"
    assert package_xml.installed_package_uri(PurePosixPath("/home/a/b.stl")) is None


# -- C015 --------------------------------------------------------------------------------


def test_undeclared_package_once_per_package(tmp_path: Path) -> None:
    pkg = make_package(tmp_path / "demo", "demo_description", ("exec_depend", "declared"))
    urdf = pkg / "urdf" / "robot.urdf"
    urdf.write_text(
        robot(
            "package://demo_description/meshes/box.obj",
            "package://declared/meshes/a.stl",
            "package://other/meshes/a.stl",
            "package://other/meshes/b.stl",
        )
    )
    found = lint(urdf, "C015")
    assert [(f.line, f.element, f.severity) for f in found] == [
        (5, "/robot/link[@name='base']/visual[3]/geometry/mesh", Severity.WARNING)
    ]
    assert found[0].message.startswith("2 references to package 'other'")
    assert found[0].fix == f"Add <exec_depend>other</exec_depend> to {pkg / 'package.xml'}."


def test_no_package_no_finding_and_malformed_manifest_is_one_info(tmp_path: Path) -> None:
    loose = tmp_path / "loose.urdf"
    loose.write_text(robot("package://other/a.stl"))
    assert lint(loose, "C015") == []
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>x</name>")
    urdf = pkg / "robot.urdf"
    urdf.write_text(robot("package://other/a.stl", "package://third/a.stl"))
    found = lint(urdf, "C015")
    assert [(f.line, f.severity) for f in found] == [(3, Severity.INFO)]
    assert "not well-formed" in found[0].message


def test_xacro_macro_is_checked_against_the_package_that_writes_it(tmp_path: Path) -> None:
    lib = make_package(tmp_path / "lib", "lib_description")
    (lib / "urdf" / "part.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="part">\n'
        f'    <link name="part">{INERTIAL}\n'
        '      <visual><geometry><mesh filename="package://lib_description/meshes/box.obj"/>'
        "</geometry></visual>\n"
        '      <visual><geometry><mesh filename="package://vendor_meshes/a.stl"/>'
        "</geometry></visual>\n"
        "    </link>\n  </xacro:macro>\n</robot>\n"
    )
    app = make_package(tmp_path / "app", "app_description", ("exec_depend", "lib_description"))
    main = app / "urdf" / "robot.urdf.xacro"
    main.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find lib_description)/urdf/part.xacro"/>\n'
        "  <xacro:part/>\n</robot>\n"
    )
    found = lint(main, "C015")
    assert [(Path(f.path).name, f.line) for f in found] == [("part.xacro", 5)]
    assert "'lib_description' does not declare it" in found[0].message


# -- C016 --------------------------------------------------------------------------------


def test_case_variant_folder_and_file(tmp_path: Path) -> None:
    (tmp_path / "Meshes").mkdir()
    (tmp_path / "Meshes" / "Arm.STL").write_text("solid x\nendsolid x\n")
    assert case_variant(tmp_path / "meshes" / "arm.stl") == tmp_path / "Meshes" / "Arm.STL"
    assert case_variant(tmp_path / "Meshes" / "Arm.STL") is None  # exact
    assert case_variant(tmp_path / "meshes" / "leg.stl") is None  # nothing like it


def test_case_mismatch_through_a_package(tmp_path: Path) -> None:
    pkg = make_package(tmp_path / "demo", "demo_description")
    urdf = pkg / "urdf" / "robot.urdf"
    urdf.write_text(robot("package://demo_description/Meshes/Box.obj"))
    found = lint(urdf, "C016")
    assert [(f.line, f.severity) for f in found] == [(3, Severity.ERROR)]
    assert "('Meshes/Box.obj' is 'meshes/box.obj' on disk)" in found[0].message
    assert found[0].fix == "Write 'meshes/box.obj' as it is on disk."
