"""C013 per target: each engine's contact filtering (urdflint.sources.contact_filters).

What each engine does was observed with bench/contact_agreement.py (MuJoCo 4.0, Drake 1.51,
PyBullet 3.2.7) and sdformat 12.3; the fixtures are cut down from real files.
"""

from __future__ import annotations

import sys
import types
from pathlib import Path

import pytest

from tests.test_self_collision import HERE, INERTIAL, arm, c013, depth_mm
from urdflint.engine import config, linter
from urdflint.model.finding import Severity
from urdflint.sources.contact_filters import Filters, drake_filtered

BOX = '<box size="0.1 0.1 0.1"/>'
ROOT_NOTE = "(MuJoCo welds the root link to the world, never filtered against its children)"


def effects(finding) -> dict[str, str]:
    return {target: effect.detail for target, effect in finding.effects}


# -- the fixtures: FANUC's base (MuJoCo) and Drake's iiwa spheres ---------------------------


def test_root_and_its_child_collide_in_mujoco_only() -> None:
    """ros-industrial/fanuc M-6iB: base_link and link_1 (joint_1) overlap by 54 mm; MuJoCo
    welds base_link to the world and reports (world, link_1) at qpos0."""
    [found] = c013(HERE / "bad_root_world.urdf", targets=["mujoco"])
    assert (Path(found.path).name, found.line, found.element, found.severity) == (
        "bad_root_world.urdf", 21, "/robot/link[@name='link_1']/collision", Severity.WARNING,
    )  # fmt: skip
    assert found.message == (
        "collision geometry of links 'base_link' and 'link_1' overlaps by 53.6 mm at the zero "
        "pose (meshes as their convex hulls); MuJoCo collides them from the start " + ROOT_NOTE
    )
    assert effects(found)["mujoco"].startswith("collides them: its URDF import welds the root")
    assert '<exclude body1="world" body2="link_1"/>' in (found.fix or "")
    others = ["gazebo-classic", "gz-sim", "drake", "pybullet", "isaac", "pinocchio", "ros"]
    assert c013(HERE / "bad_root_world.urdf", targets=others) == []


def test_iiwa_wrist_spheres_collide_in_mujoco_not_drake() -> None:
    """Drake's iiwa14_spheres_collision: iiwa_link_5 and iiwa_link_7, 14.9 mm; its
    drake:collision_filter_group filters them for Drake only (observed in all three)."""
    path = HERE / "bad_iiwa_spheres.urdf"
    [found] = c013(path, targets=["mujoco", "drake"])
    assert (found.line, found.element, found.severity) == (
        197, "/robot/link[@name='iiwa_link_7']/collision", Severity.WARNING,
    )  # fmt: skip
    assert found.message == (
        "collision geometry of links 'iiwa_link_5' and 'iiwa_link_7' overlaps by 14.9 mm at "
        "the zero pose; MuJoCo collides them from the start"
    )
    assert list(effects(found)) == ["mujoco"]
    [drake_only] = c013(path, targets=["drake"])
    assert (drake_only.severity, drake_only.effects) == (Severity.INFO, ())
    [pybullet] = c013(path, targets=["pybullet"])
    assert pybullet.severity is Severity.INFO  # only with URDF_USE_SELF_COLLISION


def test_unprefixed_collision_filter_group_filters_nothing_in_drake(tmp_path: Path) -> None:
    """The 2018 iiwa file wrote <collision_filter_group> without drake: (and its ignored
    group by a collision_filter_group attribute): Drake 1.51 reads neither, collides the pair."""
    text = (HERE / "bad_iiwa_spheres.urdf").read_text()
    text = text.replace("drake:", "").replace(' xmlns:drake="http://drake.mit.edu"', "")
    (tmp_path / "old.urdf").write_text(text)
    [found] = c013(tmp_path / "old.urdf", targets=["mujoco", "drake"])
    assert list(effects(found)) == ["mujoco", "drake"]


def test_drake_filter_groups_ignore_and_nested_members(tmp_path: Path) -> None:
    extra = """<drake:collision_filter_group xmlns:drake="http://drake.mit.edu" name="arm">
    <drake:member link="base_link"/><drake:member_group name="tip"/>
    <drake:ignored_collision_filter_group name="arm"/>
  </drake:collision_filter_group>
  <drake:collision_filter_group xmlns:drake="http://drake.mit.edu" name="tip">
    <drake:member link="forearm"/></drake:collision_filter_group>
  <drake:collision_filter_group xmlns:drake="http://drake.mit.edu" name="off" ignore="true">
    <drake:member link="upper_arm"/><drake:member link="forearm"/>
    <drake:ignored_collision_filter_group name="off"/></drake:collision_filter_group>"""
    path = arm(tmp_path, BOX, extra)
    doc = linter.load(path, str(path), config.Settings())
    assert drake_filtered(doc) == {frozenset(("base_link", "forearm"))}
    [found] = c013(path, targets=["mujoco", "drake"])
    assert list(effects(found)) == ["mujoco"]


# -- MuJoCo ----------------------------------------------------------------------------------


def _shoulder(tmp_path: Path, extra: str = "", name: str = "arm.urdf", elbow: bool = False) -> Path:
    """The arm with the upper arm's sphere 70 mm deep in the base (parent and child), the
    forearm's 1 cm cube far above (or, with ``elbow``, 15 mm into the upper arm's sphere)."""
    path = arm(tmp_path, '<box size="0.01 0.01 0.01"/>', extra, name)
    text = path.read_text().replace(
        '<link name="upper_arm">' + INERTIAL + "</link>",
        '<link name="upper_arm">' + INERTIAL + '<collision><origin xyz="0 0 -0.42"/>'
        '<geometry><sphere radius="0.05"/></geometry></collision></link>',
    )
    path.write_text(
        text.replace('xyz="0 0 -0.53"', 'xyz="0 0 -0.48"' if elbow else 'xyz="0 0 0.3"')
    )
    return path


def test_mujoco_option_flags_in_the_urdf(tmp_path: Path) -> None:
    """<mujoco><option><flag>: filterparent="disable" collides parents and children (observed
    on solo12: its lower legs against the upper legs), contact="disable" nothing."""
    path = _shoulder(tmp_path)
    [root] = c013(path, targets=["mujoco"])
    assert "'base_link' and 'upper_arm' overlaps by 70.0 mm" in root.message
    assert root.message.endswith(ROOT_NOTE)
    off = '<mujoco><option><flag contact="disable"/></option></mujoco>'
    assert c013(_shoulder(tmp_path, off, "off.urdf"), targets=["mujoco"]) == []
    assert len(c013(_shoulder(tmp_path, "", "elbow.urdf", elbow=True), targets=["mujoco"])) == 1
    flag = '<mujoco><option><flag filterparent="disable"/></option></mujoco>'
    both = c013(_shoulder(tmp_path, flag, "all.urdf", elbow=True), targets=["mujoco"])
    assert [depth_mm(f) for f in both] == [70.0, 15.0]  # the elbow's pair too
    fused = '<mujoco><compiler fusestatic="false"/></mujoco>'
    assert len(c013(_shoulder(tmp_path, fused, "f.urdf"), targets=["mujoco"])) == 1


def test_a_floating_root_is_not_welded(tmp_path: Path) -> None:
    """A root link named world with a floating joint to base_link: MuJoCo gives base_link a
    free joint, so it filters base_link against its child again."""
    path = _shoulder(tmp_path)
    text = path.read_text().replace(
        '<link name="base_link">',
        '<link name="world"/><joint name="free" type="floating"><parent link="world"/>'
        '<child link="base_link"/></joint>\n  <link name="base_link">',
    )
    (tmp_path / "free.urdf").write_text(text)
    found = c013(tmp_path / "free.urdf", targets=["mujoco"])
    assert [f for f in found if "'upper_arm'" in f.message] == []


def test_srdf_disabled_pair_still_collides_in_the_simulators(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    fake = types.ModuleType("urdflint.sources.srdf")
    fake.disabled_pairs = lambda doc: {frozenset(("forearm", "base_link"))}  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "urdflint.sources.srdf", fake)
    assert c013(HERE / "bad.urdf", targets=["ros", "gz-sim"]) == []
    [found] = c013(HERE / "bad.urdf", targets=["ros", "mujoco"])
    assert list(effects(found)) == ["mujoco"]
    assert found.message.endswith("(the SRDF disables the pair for MoveIt only)")


# -- Drake -----------------------------------------------------------------------------------


def test_drake_collides_a_child_of_the_world_link(tmp_path: Path) -> None:
    """Drake filters the two links of a joint unless its parent is the world (a link named
    world); MuJoCo collides them too (the world body)."""
    path = _shoulder(tmp_path)
    text = path.read_text().replace('"base_link"', '"world"')
    (tmp_path / "world.urdf").write_text(text)
    found = c013(tmp_path / "world.urdf", targets=["mujoco", "drake"])
    [shoulder] = [f for f in found if "'upper_arm'" in f.message]
    assert list(effects(shoulder)) == ["mujoco", "drake"]


# -- Gazebo ----------------------------------------------------------------------------------


def test_gazebo_classic_reads_a_links_self_collide(tmp_path: Path) -> None:
    extra = '<gazebo reference="forearm"><selfCollide>true</selfCollide></gazebo>'
    path = arm(tmp_path, BOX, extra)
    [classic] = c013(path, targets=["gazebo-classic"])
    assert classic.severity is Severity.WARNING and "Gazebo Classic collides" in classic.message
    [sim] = c013(path, targets=["gz-sim"])  # gz-physics reads the model's only
    assert sim.severity is Severity.INFO


def test_gazebo_model_self_collide_and_link_override(tmp_path: Path) -> None:
    model = "<gazebo><self_collide>true</self_collide></gazebo>"
    [both] = c013(arm(tmp_path, BOX, model), targets=["gazebo-classic", "gz-sim"])
    assert list(effects(both)) == ["gazebo-classic", "gz-sim"]
    override = model + "".join(
        f'<gazebo reference="{link}"><self_collide>false</self_collide></gazebo>'
        for link in ("base_link", "forearm")
    )
    [sim] = c013(arm(tmp_path, BOX, override, "o.urdf"), targets=["gazebo-classic", "gz-sim"])
    assert list(effects(sim)) == ["gz-sim"]  # Classic: each link's own value wins


def test_robot_level_camel_case_self_collide_is_dropped(tmp_path: Path) -> None:
    """sdformat 12 turns a robot-level <self_collide> into the model's, and drops a
    robot-level <selfCollide> (observed)."""
    path = arm(tmp_path, BOX, "<gazebo><selfCollide>true</selfCollide></gazebo>")
    [found] = c013(path, targets=["gazebo-classic", "gz-sim"])
    assert found.severity is Severity.INFO


def test_a_lumped_links_self_collide_moves_to_its_body(tmp_path: Path) -> None:
    """sdformat lumps a link fixed to base_link into it, with its <selfCollide>."""
    extra = f"""<joint name="cover_joint" type="fixed"><parent link="base_link"/>
    <child link="cover"/></joint><link name="cover">{INERTIAL}</link>
  <gazebo reference="cover"><selfCollide>true</selfCollide></gazebo>"""
    path = arm(tmp_path, BOX, extra)
    doc = linter.load(path, str(path), config.Settings())
    filters = Filters(doc)
    relation = filters.relation("base_link", "forearm")
    assert filters.gazebo("gazebo-classic", "base_link", "forearm", relation)
    [found] = c013(path, targets=["gazebo-classic"])
    assert found.severity is Severity.WARNING


# -- the broad phase ---------------------------------------------------------------------------


def test_a_thin_plate_deep_inside_a_box_is_measured(tmp_path: Path) -> None:
    """A 0.5 mm plate 30 mm deep in a box: the boxes overlap by 0.5 mm along its normal, but
    coming apart takes 30 mm (PR2's accelerometer board inside its forearm: 36 mm)."""
    path = arm(tmp_path, '<box size="0.1 0.1 0.0005"/>')
    [found] = c013(path, targets=["mujoco"])
    assert depth_mm(found) == pytest.approx(30.25, abs=0.06)  # out through the base's top
