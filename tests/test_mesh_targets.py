"""Issue 29: what each target does with a mesh format (C009), a package nobody resolves (C004)
and a terrain's size (C006), per target, on the fixtures cut down from real files.

The engines' behaviour behind each expectation was observed by loading the fixtures in
MuJoCo 4.0, PyBullet 3.2.7, Drake 1.51 and Pinocchio 4.1 (the rule pages quote them);
``test_agreement.py`` checks the same fixtures against the engines themselves.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.conftest import CORPUS, FIXTURES, needs_corpus
from tests.helpers import fixture_settings
from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.model.finding import Severity
from urdflint.model.scenery import scenery, static_model, words
from urdflint.sources.meshes import references

E, W, N = Severity.ERROR, Severity.WARNING, Severity.INFO  # N: a note (info)
C009 = FIXTURES / "rules" / "C009"
C004 = FIXTURES / "rules" / "C004"
C006 = FIXTURES / "rules" / "C006"
BOWL = "/robot/link[@name='bowl']"


def run(path: Path, targets: tuple[str, ...], select: str, **extra: object) -> list:
    settings = fixture_settings(path)
    settings = config.Settings(
        **{**settings.__dict__, "targets": targets, "select": (select,), **extra}
    )
    return [f for f in linter.lint_path(path, path.name, settings).findings if f.code == select]


def seen(findings: list) -> list[tuple[int, str, Severity, dict[str, str]]]:
    return [
        (f.line, f.element, f.severity, {t: e.consequence.key for t, e in f.effects})
        for f in findings
    ]


# -- C009: each target's mesh loaders ---------------------------------------------------------

VISUAL = f"{BOWL}/visual[@name='visual']/geometry/mesh"
COLLISION = f"{BOWL}/collision[@name='collision']/geometry/mesh"
# target -> the findings on bad_bowl.urdf: a glTF visual, a VTK collision (Drake's own model)
BOWL_BY_TARGET = {
    "pybullet": [
        (24, VISUAL, E, {"pybullet": "refused"}),
        (29, COLLISION, W, {"pybullet": "geometry dropped"}),  # "cannot extract mesh"
    ],
    "mujoco": [(29, COLLISION, E, {"mujoco": "refused"})],  # visuals discarded
    "pinocchio": [(29, COLLISION, E, {"pinocchio": "refused"})],
    "drake": [],  # glTF visual, VTK collision: both fine
    "gz-sim": [(29, COLLISION, W, {"gz-sim": "geometry dropped"})],
    "gazebo-classic": [
        (24, VISUAL, W, {"gazebo-classic": "geometry dropped"}),
        (29, COLLISION, W, {"gazebo-classic": "geometry dropped"}),
    ],
    "isaac": [],
    "ros": [],
}


@pytest.mark.parametrize("target", sorted(BOWL_BY_TARGET))
def test_c009_on_drakes_bowl_per_target(target: str) -> None:
    found = run(C009 / "bad_bowl.urdf", (target,), "C009")
    assert seen(found) == BOWL_BY_TARGET[target]


def test_c009_pybullet_refuses_drakes_gltf_visuals() -> None:
    found = run(C009 / "bad_pybullet.urdf", ("pybullet",), "C009")
    assert [(f.line, f.severity) for f in found] == [(18, E), (37, E)]
    assert found[0].message == (
        "PyBullet cannot load glTF visual mesh 'meshes/box.gltf' of link 'panda_hand' "
        "(PyBullet reads STL (.stl), OBJ and Collada)"
    )
    assert found[0].fix == (
        "Convert the mesh to OBJ, STL or Collada, which PyBullet reads (for example with trimesh)."
    )
    assert run(C009 / "good_pybullet.urdf", ("pybullet", "pinocchio"), "C009") == []


def test_c009_names_every_target_that_cannot_load_the_mesh() -> None:
    (_, found) = run(C009 / "bad_bowl.urdf", ("mujoco", "drake", "pybullet", "pinocchio"), "C009")
    assert found.message.startswith(
        "MuJoCo, PyBullet and Pinocchio cannot load VTK collision mesh 'meshes/tetra.vtk'"
    )
    assert found.fix == (
        "Convert the mesh to OBJ, which MuJoCo, Drake, PyBullet and Pinocchio all read"
        " (for example with trimesh)."
    )


# -- C004: a package nobody resolves ----------------------------------------------------------

PELVIS = "/robot/link[@name='pelvis']"
HIP = "/robot/link[@name='l_hip']"
POPPY_LINES = [24, 30, 43, 49]  # pelvis visual, collision; l_hip visual, collision


@pytest.mark.parametrize(
    ("target", "severities"),
    [
        ("drake", [E, E, E, E]),  # "refers to unknown package 'meshes'"
        ("pinocchio", [E, E, E, E]),  # "Mesh package://meshes/... could not be found"
        ("mujoco", [N, E, N, E]),  # collisions only: it discards visuals
        ("pybullet", [N, N, N, E]),  # finds meshes/*.STL but not l_hip_respondable.STL
        ("gazebo-classic", [W, W, W, W]),  # loads the model without the meshes
        ("isaac", [W, W, W, W]),
        ("ros", [N, N, N, N]),  # robot_state_publisher reads no mesh
    ],
)
def test_c004_a_folder_named_as_a_package_per_target(target: str, severities: list) -> None:
    found = run(C004 / "bad_poppy.urdf", (target,), "C004")
    assert [(f.line, f.severity) for f in found] == list(zip(POPPY_LINES, severities, strict=True))
    assert [f.element for f in found] == [
        f"{PELVIS}/visual/geometry/mesh",
        f"{PELVIS}/collision/geometry/mesh",
        f"{HIP}/visual/geometry/mesh",
        f"{HIP}/collision/geometry/mesh",
    ]


def test_c004_says_which_package_where_it_looked_and_what_pybullet_reads() -> None:
    found = run(C004 / "bad_poppy.urdf", ("drake", "pybullet"), "C004")
    folder = C004 / "meshes"
    message = found[0].message
    assert message.startswith(
        "visual mesh 'package://meshes/pelvis_visual.STL' of link 'pelvis' cannot be found: "
        "package 'meshes' was not found (looked in: "
    )
    assert "package.xml named 'meshes' above" in message
    assert (
        f"'meshes' is a folder of the description ({folder.absolute()}), not a package" in message
    )
    assert message.endswith(
        f"; PyBullet, which drops package://, reads {(folder / 'pelvis_visual.STL').absolute()}"
    )
    assert found[3].message.endswith("; the folder has 'l_hip_respondable.stl' (the case differs)")
    assert found[0].fix.startswith("Name the package that holds the mesh")
    assert {t for t, _ in found[0].effects} == {"drake"}  # PyBullet reads it: no effect
    assert {t for t, _ in found[3].effects} == {"drake", "pybullet"}


def test_c004_a_package_merely_not_configured_stays_one_note(tmp_path: Path) -> None:
    """The corpus' case: nothing says where packages live, and no folder of that name."""
    (tmp_path / "robot.urdf").write_text(
        (C004 / "bad_poppy.urdf").read_text().replace("package://meshes/", "package://poppy/")
    )
    path = tmp_path / "robot.urdf"
    settings = config.Settings(select=("C004",), targets=("drake", "pybullet"))
    result = linter.lint_path(path, str(path), settings, Context(environ={}))
    (note,) = result.findings
    assert note.severity is N
    assert note.message.startswith("package 'poppy' was not found (looked in: ")
    assert "ROS_PACKAGE_PATH and AMENT_PREFIX_PATH, which are not set" in note.message
    assert note.message.endswith(
        "so its 4 mesh references are not checked"
        " (first: visual mesh 'package://poppy/pelvis_visual.STL' of link 'pelvis')"
    )


def test_c004_a_configured_run_names_the_package_paths_given(tmp_path: Path) -> None:
    path = C004 / "bad.urdf"  # config.toml: package-paths fixture_description = "pkg"
    (found,) = [f for f in run(path, ("drake",), "C004") if "other_description" in f.message]
    assert found.severity is E  # Drake refuses the model
    assert "the package paths given (fixture_description)" in found.message
    (found,) = [f for f in run(path, ("ros",), "C004") if "other_description" in f.message]
    assert found.severity is N


# -- C006: scenery ------------------------------------------------------------------------------


def test_c006_leaves_a_terrain_welded_to_the_world_alone() -> None:
    path = C006 / "good_terrain.urdf"
    assert run(path, ("pybullet",), "C006") == []
    doc = linter.load(path, path.name, config.Settings())
    assert static_model(doc)
    assert scenery(doc, "stepOne", "meshes/terrain.obj") == (
        "the model is static scenery: no joint moves"
    )


def test_scenery_words() -> None:
    assert words("terrainLink") == {"terrain", "link"}
    assert words("ground_plane") == {"ground", "plane"}
    assert "plane" not in words("airplane_wing") and "floor" not in words("floorboard")


def fixed_link(name: str, filename: str) -> str:
    """A link with a visual mesh, welded to base_link."""
    return (
        f'<link name="{name}"><visual><geometry><mesh filename="{filename}"/></geometry>'
        f'</visual></link><joint name="{name}_joint" type="fixed"><parent link="base_link"/>'
        f'<child link="{name}"/></joint>'
    )


def test_c006_a_terrain_link_beside_a_robot_is_scenery_a_robot_part_is_not(tmp_path: Path) -> None:
    import trimesh

    trimesh.creation.box((16.0, 4.0, 1.4)).export(tmp_path / "ramps.obj")  # 16 m ramps
    trimesh.creation.box((16.0, 0.1, 0.1)).export(tmp_path / "beam.obj")
    text = (C006 / "bad.urdf").read_text()
    ramps = fixed_link("terrain", "ramps.obj")
    beam = fixed_link("boom", "beam.obj")
    (tmp_path / "robot.urdf").write_text(text.replace("</robot>", ramps + beam + "</robot>"))
    path = tmp_path / "robot.urdf"
    found = linter.lint_path(path, str(path), config.Settings(select=("C006",))).findings
    assert "ramps.obj" not in " ".join(f.message for f in found)
    assert [f.element for f in found if "beam.obj" in f.message] == [
        "/robot/link[@name='boom']/visual/geometry/mesh"
    ]


def test_c006_a_tiny_mesh_is_reported_on_scenery_too(tmp_path: Path) -> None:
    import trimesh

    trimesh.creation.box((0.0005, 0.0005, 0.0005)).export(tmp_path / "terrain.obj")
    text = (C006 / "good_terrain.urdf").read_text().replace("meshes/terrain.obj", "terrain.obj")
    (tmp_path / "scene.urdf").write_text(text)
    path = tmp_path / "scene.urdf"
    found = linter.lint_path(path, str(path), config.Settings(select=("C006",))).findings
    assert [f.severity for f in found] == [W, W]
    assert "under 1 mm" in found[0].message or "scaled twice" in found[0].message


@needs_corpus
def test_no_real_robot_is_taken_for_scenery() -> None:
    """A real-size check: on the 36 corpus robots no mesh is exempt, so a robot exported in
    millimetres keeps its finding (the ur5 with every mesh scaled by 1000 below)."""
    for model in sorted(CORPUS.glob("*/model.urdf")):
        doc = linter.load(model, str(model), config.Settings())
        assert not static_model(doc), model
        assert [r.uri for r in references(doc) if scenery(doc, r.link, r.uri)] == [], model


@needs_corpus
def test_a_real_robot_in_millimetres_keeps_its_c006_findings(tmp_path: Path) -> None:
    model = CORPUS / "ur5" / "model.urdf"
    mapping = json.loads((model.parent / "package_map.json").read_text())
    packages = {name: (model.parent / folder).resolve() for name, folder in mapping.items()}
    text = model.read_text().replace("<mesh filename=", '<mesh scale="1000 1000 1000" filename=')
    path = tmp_path / "model.urdf"
    path.write_text(text)
    context = Context(package_paths=packages, environ={})
    found = linter.lint_path(path, str(path), config.Settings(select=("C006",)), context)
    doc = linter.load(model, str(model), config.Settings())
    assert len(found.findings) == len(references(doc)) > 0
