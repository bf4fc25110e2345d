"""C013 self-collision: the pose, the pairs, the depth (coal and the numpy fallback), meshes."""

from __future__ import annotations

import sys
import types
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import FIXTURES
from tests.helpers import lint_file
from urdflint.engine import config
from urdflint.model.finding import Finding, Severity
from urdflint.sources import self_collision_depth as D
from urdflint.sources.self_collision import transform

HERE = FIXTURES / "rules" / "C013"
INERTIAL = """<inertial><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>"""


def c013(path: Path, **table: object) -> list[Finding]:
    settings = config.from_mapping(dict(table)) if table else config.Settings()
    return [f for f in lint_file(path, ("C013",), settings) if f.code == "C013"]


def arm(tmp_path: Path, shape: str, extra: str = "", name: str = "arm.urdf") -> Path:
    """base_link (a 0.2 m box) -> upper_arm (revolute, at z 0.5) -> forearm (revolute, at
    z 0.6) with ``shape`` as the forearm's collision, placed at z 0.07 in the world."""
    text = f"""<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link">{INERTIAL}
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute"><origin xyz="0 0 0.5"/>
    <parent link="base_link"/><child link="upper_arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="upper_arm">{INERTIAL}</link>
  <joint name="elbow" type="revolute"><origin xyz="0 0 0.1"/>
    <parent link="upper_arm"/><child link="forearm"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="forearm">{INERTIAL}
    <collision>
      <origin xyz="0 0 -0.53"/>
      <geometry>{shape}</geometry>
    </collision>
  </link>
{extra}
</robot>
"""
    path = tmp_path / name
    path.write_text(text)
    return path


def depth_mm(finding: Finding) -> float:
    return float(finding.message.split(" overlaps by ")[1].split(" mm")[0])


@pytest.fixture
def no_coal(monkeypatch: pytest.MonkeyPatch):
    """coal cannot be imported: the numpy fallback runs."""
    monkeypatch.setitem(sys.modules, "coal", None)
    D.coal_available.cache_clear()
    yield
    D.coal_available.cache_clear()


# -- the finding ------------------------------------------------------------------------------


def test_bad_fixture_exact_finding() -> None:
    [found] = c013(HERE / "bad.urdf")
    assert (found.line, found.element) == (47, "/robot/link[@name='forearm']/collision")
    assert found.message == (
        "collision geometry of links 'base_link' and 'forearm' overlaps by 80.0 mm at the zero pose"
    )
    assert found.severity is Severity.INFO  # Gazebo Classic (the default) does not self-collide
    assert '<disable_collisions link1="base_link" link2="forearm" reason="Default"/>' in (
        found.fix or ""
    )


def test_severity_follows_the_targets() -> None:
    [found] = c013(HERE / "bad.urdf", targets=["mujoco", "drake"])
    assert found.severity is Severity.WARNING
    assert found.message.endswith("; MuJoCo and Drake collide them from the start")
    assert [t for t, _ in found.effects] == ["mujoco", "drake"]
    [quiet] = c013(HERE / "bad.urdf", targets=["pybullet", "isaac", "pinocchio", "ros"])
    assert quiet.severity is Severity.INFO


def test_min_depth_option(tmp_path: Path) -> None:
    path = arm(tmp_path, '<box size="0.1 0.1 0.1"/>')
    assert c013(path, rules={"C013": {"min-depth": 79.0}})
    assert not c013(path, rules={"C013": {"min-depth": 81.0}})


def test_adjacent_and_welded_links_are_not_pairs() -> None:
    assert c013(HERE / "good.urdf", targets=["all"]) == []


def test_body_adjacent_pair_warns_for_drake_only(tmp_path: Path) -> None:
    """A link fixed to the upper arm overlapping the forearm: MuJoCo fuses it into the upper
    arm (the forearm's parent: filtered), Drake collides it (observed)."""
    extra = f"""<joint name="mount" type="fixed"><origin xyz="0 0 0.1"/>
    <parent link="upper_arm"/><child link="camera"/></joint>
  <link name="camera">{INERTIAL}
    <collision><origin xyz="0 0 -0.53"/><geometry><sphere radius="0.03"/></geometry></collision>
  </link>"""
    found = c013(arm(tmp_path, '<box size="0.01 0.01 0.01"/>', extra), targets=["mujoco", "drake"])
    camera = [f for f in found if "'camera'" in f.message and "'forearm'" in f.message]
    assert len(camera) == 1 and "; Drake collides them" in camera[0].message


def test_srdf_disabled_pairs_are_skipped(monkeypatch: pytest.MonkeyPatch) -> None:
    fake = types.ModuleType("urdflint.sources.srdf")
    fake.disabled_pairs = lambda doc: {frozenset(("forearm", "base_link"))}  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "urdflint.sources.srdf", fake)
    assert c013(HERE / "bad.urdf") == []


# -- the pose -------------------------------------------------------------------------------


def test_q_pose_and_mimic() -> None:
    path = HERE / "good_pose.urdf"
    assert c013(path) == []
    [found] = c013(path, expect={"q": {"left": 0.02}})
    assert (found.line, found.element) == (48, "/robot/link[@name='right_finger']/collision")
    assert depth_mm(found) == 20.0
    assert "at the configuration left=0.02, right=0.02" in found.message
    [half] = c013(path, expect={"q": {"left": 0.015}})  # 10 mm apart each side of x = 0
    assert depth_mm(half) == 10.0


def test_q_rotates_a_revolute_joint(tmp_path: Path) -> None:
    """Swinging the elbow by pi/2 lifts the forearm box out of the base."""
    path = arm(tmp_path, '<box size="0.1 0.1 0.1"/>')
    assert c013(path, expect={"q": {"elbow": 1.5707963}}) == []
    assert c013(path, expect={"q": {"shoulder": 1.0, "unknown": 3.0}})  # about its own axis


def test_rpy_matches_the_urdf_convention() -> None:
    """rpy is fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = 0.3, -0.7, 1.1
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    assert np.allclose(transform((0, 0, 0), (r, p, y))[:3, :3], rz @ ry @ rx)


# -- coal and the fallback ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("shape", "depth", "approximate"),
    [
        ('<box size="0.1 0.1 0.1"/>', 80.0, False),
        ('<sphere radius="0.05"/>', 80.0, False),  # centre at z 0.07, base top at 0.1
        ('<cylinder radius="0.05" length="0.1"/>', 80.0, True),
        ('<capsule radius="0.05" length="0.1"/>', 130.0, True),
    ],
)
def test_coal_and_fallback_agree(tmp_path: Path, shape: str, depth: float, approximate: bool):
    path = arm(tmp_path, shape)
    [exact] = c013(path, targets=["mujoco"])
    assert depth_mm(exact) == pytest.approx(depth, abs=0.1)
    assert exact.severity is Severity.WARNING and "bounding boxes" not in exact.message
    D.coal_available.cache_clear()
    with pytest.MonkeyPatch.context() as patch:
        patch.setitem(sys.modules, "coal", None)
        [fallback] = c013(path, targets=["mujoco"])
    D.coal_available.cache_clear()
    assert depth_mm(fallback) == pytest.approx(depth, abs=0.1)
    assert ("bounding boxes" in fallback.message) is approximate
    assert fallback.severity is (Severity.INFO if approximate else Severity.WARNING)


def _random_pair(rng: np.random.Generator, kinds: tuple[str, str]) -> tuple[D.Placed, D.Placed]:
    from scipy.spatial.transform import Rotation

    placed = []
    for kind in kinds:
        rotation = Rotation.random(random_state=rng).as_matrix()
        center = rng.uniform(-0.05, 0.05, 3)
        if kind == "sphere":
            r = float(rng.uniform(0.02, 0.06))
            placed.append(D.Placed("a", None, kind, rotation, center, np.full(3, r), radius=r))
        else:
            placed.append(D.Placed("b", None, kind, rotation, center, rng.uniform(0.01, 0.05, 3)))
    return placed[0], placed[1]


@pytest.mark.parametrize("kinds", [("box", "box"), ("sphere", "box"), ("sphere", "sphere")])
def test_numpy_fallback_matches_coal_on_random_poses(kinds: tuple[str, str]) -> None:
    pytest.importorskip("coal")
    pytest.importorskip("scipy")
    rng = np.random.default_rng(13)
    exact = D.CoalDepth()
    for _ in range(200):
        a, b = _random_pair(rng, kinds)
        assert D.numpy_depth(a, b)[0] == pytest.approx(exact(a, b)[0], abs=1e-6)


def test_without_coal_the_run_uses_numpy(no_coal: None) -> None:
    assert D.depth_function()[1] == "numpy"
    [found] = c013(HERE / "bad.urdf")
    assert depth_mm(found) == 80.0


# -- meshes -------------------------------------------------------------------------------------


def _write_meshes(folder: Path) -> None:
    trimesh = pytest.importorskip("trimesh")
    trimesh.creation.box(extents=(0.1, 0.1, 0.1)).export(folder / "cube.stl")
    # an L: two bars whose convex hull covers the empty corner at (+x, +z)
    bars = [
        trimesh.creation.box(extents=(0.3, 0.1, 0.05), transform=_at(0.15, 0, 0.025)),
        trimesh.creation.box(extents=(0.05, 0.1, 0.3), transform=_at(0.025, 0, 0.15)),
    ]
    trimesh.util.concatenate(bars).export(folder / "ell.stl")


def _at(x: float, y: float, z: float) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, 3] = (x, y, z)
    return matrix


def test_mesh_collision_as_convex_hull(tmp_path: Path) -> None:
    _write_meshes(tmp_path)
    [found] = c013(arm(tmp_path, '<mesh filename="cube.stl"/>'))
    assert depth_mm(found) == pytest.approx(80.0, abs=0.1)
    assert "(meshes as their convex hulls)" in found.message


def test_mesh_hull_overlap_inside_a_concave_mesh(tmp_path: Path) -> None:
    """A 2 cm sphere in the empty corner of an L: the mesh is not touched, its hull is (what
    MuJoCo, PyBullet and Drake collide); the L is scaled to show the scale is applied."""
    _write_meshes(tmp_path)
    extra = f"""<joint name="tool" type="revolute"><origin xyz="0.5 0 0"/>
    <parent link="base_link"/><child link="tool_link"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="tool_link">{INERTIAL}
    <collision><origin xyz="0.16 0 0.16"/><geometry><sphere radius="0.02"/></geometry></collision>
  </link>"""
    shape = '<mesh filename="ell.stl" scale="1 1 1"/>'
    path = arm(tmp_path, shape, extra).read_text().replace('xyz="0 0 -0.53"', 'xyz="0.5 0 -0.6"')
    (tmp_path / "ell.urdf").write_text(path)
    found = c013(tmp_path / "ell.urdf")
    hull = [f for f in found if "'forearm'" in f.message and "'tool_link'" in f.message]
    assert len(hull) == 1 and "convex hulls" in hull[0].message


def test_unreadable_mesh_is_left_out(tmp_path: Path) -> None:
    assert c013(arm(tmp_path, '<mesh filename="missing.stl"/>')) == []
