"""Unit tests for urdflint.gazebo_spec: tables, value checks, lumping, names."""

from __future__ import annotations

from lxml import etree

from urdflint.model import gazebo_spec as gs
from urdflint.model.document import Document

ROBOT = b"""<robot name="r">
  <link name="world"/>
  <joint name="fix_world" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/></joint>
  <link name="arm"/>
  <joint name="f1" type="fixed"><parent link="arm"/><child link="tool"/></joint>
  <link name="tool"/>
  <joint name="f2" type="fixed"><parent link="tool"/><child link="tip"/></joint>
  <link name="tip"/>
  <joint name="f3" type="fixed"><parent link="arm"/><child link="kept"/></joint>
  <link name="kept"/>
  <gazebo reference="f3"><preserveFixedJoint>yes</preserveFixedJoint></gazebo>
  <gazebo reference="nothing"/>
  <gazebo reference="arm"/>
  <gazebo/>
</robot>"""


def test_materials_are_loaded_and_split() -> None:
    stock, internal = gs.materials()
    assert "Gazebo/Orange" in stock and "Gazebo/FlatBlack" in stock
    assert "Gazebo/DepthMap" in internal and "Gazebo/DepthMap" not in stock
    assert gs.materials() is gs.materials()  # cached


def test_value_problems() -> None:
    mu1, fdir1, maxc = gs.KEYS["mu1"], gs.KEYS["fdir1"], gs.KEYS["maxContacts"]
    assert gs.value_problem(mu1, "0.8") is None
    assert gs.value_problem(mu1, "${mu}") is None
    assert gs.value_problem(mu1, "0.8.1") == ("is '0.8.1', not a number", False)
    assert gs.value_problem(mu1, "-1") == ("is -1, below 0", True)
    assert gs.value_problem(fdir1, "1 0 0") is None
    assert gs.value_problem(fdir1, "1 0") is not None
    assert gs.value_problem(maxc, "3") is None
    assert gs.value_problem(maxc, "2.5") is not None
    assert gs.value_problem(gs.KEYS["fudgeFactor"], "1.5") == ("is 1.5, outside [0, 1]", True)
    assert gs.value_problem(gs.KEYS["selfCollide"], "YES") is None
    assert "reads it as false" in str(gs.value_problem(gs.KEYS["selfCollide"], "on"))
    assert "reads it as true" in str(gs.value_problem(gs.KEYS["turnGravityOff"], "on"))
    assert gs.value_problem(gs.KEYS["gravity"], "yes") is not None  # SDF bool
    assert gs.value_problem(gs.KEYS["material"], "") is None


def test_value_of_prefers_the_value_attribute() -> None:
    assert gs.value_of(etree.fromstring('<mu1 value=" 2 ">1</mu1>')) == "2"
    assert gs.value_of(etree.fromstring("<mu1> 1 </mu1>")) == "1"


def test_canonical_link_level_values() -> None:
    def canon(tag: str, text: str) -> tuple[str, str] | None:
        return gs.canonical(tag, etree.fromstring(f"<{tag}>{text}</{tag}>"))

    assert canon("turnGravityOff", "true") == ("gravity", "false")
    assert canon("turnGravityOff", "no") == ("gravity", "true")
    assert canon("gravity", "0") == ("gravity", "false")
    assert canon("selfCollide", "1") == ("self_collide", "true")
    assert canon("mu1", "1") is None


def test_scopes_and_lumping() -> None:
    doc = Document("r.urdf", ROBOT)
    blocks = {g.get("reference"): g for g in doc.gazebo}
    assert gs.scopes_of(doc, blocks["f3"]) == {gs.JOINT}
    assert gs.scopes_of(doc, blocks["arm"]) == {gs.LINK}
    assert gs.scopes_of(doc, blocks[None]) == {gs.ROBOT}
    assert gs.scopes_of(doc, blocks["nothing"]) is None
    kept = gs.preserved_joints(doc)
    assert kept == {"f3"}
    assert gs.lumped_into(doc, "base", kept) is None  # parent is world
    assert gs.lumped_into(doc, "arm", kept) is None  # revolute
    assert gs.lumped_into(doc, "kept", kept) is None  # preserved
    lumped = gs.lumped_into(doc, "tip", kept)
    assert lumped is not None
    assert (lumped[0].name, lumped[1]) == ("f2", "arm")  # through tool, also lumped


def test_homes() -> None:
    assert gs.homes("mu1") == [gs.LINK]
    assert set(gs.homes("sensor")) == {gs.LINK, gs.JOINT}
    assert gs.homes("plugin") == [gs.ROBOT]
    assert gs.homes("robotNamespace") == []
    assert gs.belongs("self_collide", frozenset({gs.ROBOT}))


def test_names() -> None:
    assert gs.distance("mu", "mu1") == 1
    assert gs.distance("ab", "ba") == 1
    known = gs.candidates()
    assert gs.near_miss("mu", known) in ("mu1", "mu2")
    assert gs.near_miss("selfcollide", known) == "selfCollide"
    assert gs.near_miss("max_contacts", known) == "maxContacts"
    assert gs.near_miss("robotNamespace", known) is None
    assert gs.near_miss("mu1", known) is None
    assert gs.suggest("Organge", ["Orange", "Grey"]) == "Orange"
    assert gs.suggest("stick_link", ["imu_link", "base_link"]) is None


def test_a_dangling_block_is_checked_as_a_link_or_joint_block() -> None:
    doc = Document("r.urdf", ROBOT)
    blocks = {g.get("reference"): g for g in doc.gazebo}
    assert gs.checked_scopes(doc, blocks["nothing"]) == {gs.LINK, gs.JOINT}
    assert gs.checked_scopes(doc, blocks["arm"]) == {gs.LINK}
    assert gs.describe(doc, blocks["nothing"]) == "the undefined reference 'nothing'"
    assert [owner for _, _, owner in gs.block_keys(doc)] == ["joint 'f3'"]


def test_every_problem_of_a_dangling_block_is_reported_in_one_run() -> None:
    """Fixing the reference (G001) must not reveal a second round of findings."""
    from tests.helpers import lint_text

    text = """<robot name="r">
      <link name="base_link"/>
      <gazebo reference="base_lnk">
        <material>Gazebo/Organge</material>
        <mu1>0.8.1</mu1>
        <mu>1</mu>
        <static>true</static>
        <stopKp>1</stopKp>
      </gazebo>
    </robot>"""
    found = lint_text(text, select=("G",))
    assert sorted(f.code for f in found) == ["G001", "G003", "G004", "G005", "G006", "G007"]
    fixed = lint_text(text.replace("base_lnk", "base_link"), select=("G",))
    assert {f.code for f in fixed} <= {f.code for f in found} - {"G001"}
    assert len(fixed) == len(found) - 1
