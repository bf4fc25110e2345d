"""urdflint/schema.py: the URDF element table and its number checks (X004, X005, X007)."""

from __future__ import annotations

import pytest
from lxml import etree

from urdflint.model.schema import (
    Kind,
    describe,
    homes,
    is_xacro,
    malformed,
    owner,
    walk,
    wrong_arity,
)


@pytest.mark.parametrize("value", ["1", "-0.5", "+2", ".5", "1.", "1e-3", "2E+2", " 1"])
def test_valid_scalars(value: str) -> None:
    assert malformed(value, Kind.NUMBER) is None


@pytest.mark.parametrize(
    ("value", "why"),
    [
        ("", "is empty"),
        ("nan", "is not a finite number"),
        ("inf", "is not a finite number"),
        ("1_0", "is not a finite number"),
        ("1,5", "is not a finite number"),
        ("0x10", "is not a finite number"),
        ("0.1 0.2", "must be a single number"),
        ("1.0 ", "ends with whitespace, which urdfdom refuses"),
    ],
)
def test_malformed_scalars(value: str, why: str) -> None:
    assert malformed(value, Kind.NUMBER) == why


def test_vectors_report_a_bad_token_once_and_leave_the_count_to_arity() -> None:
    assert malformed("0,0,1", Kind.VECTOR3) == "contains '0,0,1', which is not a finite number"
    assert wrong_arity("0,0,1", Kind.VECTOR3) is None  # X004's, not X005's
    assert malformed("0 0", Kind.VECTOR3) is None
    assert wrong_arity("0 0", Kind.VECTOR3) == 2
    assert wrong_arity("", Kind.VECTOR3) == 0
    assert wrong_arity(" 0  0 1 ", Kind.VECTOR3) is None
    assert wrong_arity("1 0 0", Kind.RGBA) == 3
    assert wrong_arity("1", Kind.NUMBER) is None


ROBOT = b"""<robot name="r"
  xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:drake="http://drake.mit.edu">
  <link name="a"><inertia/><contact><anything/></contact>
    <visual><geometry><capsule/></geometry></visual></link>
  <gazebo><whatever/></gazebo>
  <xacro:property name="p" value="1"/>
  <joint name="j"><drake:rotor_inertia value="1"/><limit/></joint>
</robot>"""


def test_walk_classifies_known_unknown_and_skips_extensions() -> None:
    robot = etree.fromstring(ROBOT)
    seen = {(v.element.tag, v.key, v.parent_key) for v in walk(robot)}
    assert ("inertia", None, "link") in seen
    assert ("capsule", "capsule", "geometry") in seen
    assert ("limit", "limit", "joint") in seen
    tags = {tag for tag, _, _ in seen}
    assert not tags & {"contact", "anything", "gazebo", "whatever"}
    assert not any(tag.startswith("{") for tag in tags)


def test_homes_owner_and_xacro() -> None:
    assert homes("inertia") == ["inertial"]
    assert homes("origin") == ["collision", "inertial", "joint", "visual"]
    assert homes("gazebo") == ["robot"]
    assert homes("nothing") == []
    robot = etree.fromstring(ROBOT)
    inertia = robot.find("link/inertia")
    assert owner(inertia) == "link 'a'"
    assert describe(robot.find("link/visual")) == "the <visual> of link 'a'"
    assert describe(robot) == "the robot"
    assert [is_xacro(el) for el in robot] == [False, False, True, False]
