"""The inertia maths behind the I rules: eigenvalues, primitives, bounding boxes, lumping."""

from __future__ import annotations

import math
import random

import pytest
from lxml import etree

from urdflint.model.bodies import bodies
from urdflint.model.document import Document
from urdflint.model.geometry import Shape, read_shape
from urdflint.model.inertia import (
    aabb,
    eigenvalues,
    judge,
    matrix,
    primitive_moments,
    principal_moments,
    read_inertial,
    rotate,
    rpy_matrix,
    times,
)

approx = pytest.approx


def shape(xml: str) -> Shape:
    owner = etree.fromstring(f"<collision><geometry>{xml}</geometry></collision>")
    found = read_shape(owner)
    assert found is not None
    return found


def test_eigenvalues_of_a_diagonal_matrix_are_sorted() -> None:
    assert eigenvalues(matrix((3.0, 1.0, 2.0, 0.0, 0.0, 0.0))) == (1.0, 2.0, 3.0)


def test_eigenvalues_with_repeated_values() -> None:
    assert eigenvalues(matrix((2.0, 2.0, 2.0, 0.0, 0.0, 0.0))) == (2.0, 2.0, 2.0)
    # [[2,1,0],[1,2,0],[0,0,3]] has eigenvalues 1, 3, 3
    assert eigenvalues(matrix((2.0, 2.0, 3.0, 1.0, 0.0, 0.0))) == approx((1.0, 3.0, 3.0))


def test_eigenvalues_of_the_all_ones_matrix() -> None:
    assert eigenvalues(matrix((1.0, 1.0, 1.0, 1.0, 1.0, 1.0))) == approx((0.0, 0.0, 3.0), abs=1e-12)


def test_eigenvalues_of_an_indefinite_matrix() -> None:
    assert eigenvalues(matrix((1.0, 1.0, 1.0, 2.0, 0.0, 0.0))) == approx((-1.0, 1.0, 3.0))


def test_eigenvalues_survive_tiny_and_huge_scales() -> None:
    for scale in (1e-20, 1e-9, 1.0, 1e9):
        t = tuple(v * scale for v in (2.0, 2.0, 3.0, 1.0, 0.0, 0.0))
        assert eigenvalues(matrix(t)) == approx((1.0 * scale, 3.0 * scale, 3.0 * scale), rel=1e-9)


def test_eigenvalues_are_invariant_under_rotation() -> None:
    rng = random.Random(7)
    diagonal = matrix((0.1, 0.2, 0.25, 0.0, 0.0, 0.0))
    for _ in range(50):
        r = rpy_matrix(tuple(rng.uniform(-math.pi, math.pi) for _ in range(3)))  # type: ignore[arg-type]
        assert eigenvalues(rotate(diagonal, r)) == approx((0.1, 0.2, 0.25), rel=1e-9)


def test_eigenvalues_of_the_zero_matrix() -> None:
    assert eigenvalues(matrix((0.0,) * 6)) == (0.0, 0.0, 0.0)


def test_rpy_matrix_follows_urdf_fixed_axis_convention() -> None:
    # yaw 90 degrees turns x into y
    r = rpy_matrix((0.0, 0.0, math.pi / 2))
    assert [r[i][0] for i in range(3)] == approx([0.0, 1.0, 0.0], abs=1e-12)
    # roll 90 degrees turns y into z
    r = rpy_matrix((math.pi / 2, 0.0, 0.0))
    assert [r[i][1] for i in range(3)] == approx([0.0, 0.0, 1.0], abs=1e-12)


def test_judge_sorts_tensors_into_valid_degenerate_and_impossible() -> None:
    assert judge(principal_moments((0.00833, 0.00833, 0.00167, 0, 0, 0))) == "valid"
    assert judge((0.0, 0.0, 0.0)) == "degenerate"  # a point mass
    assert judge((0.0, 1.0, 1.0)) == "degenerate"  # a thin rod
    assert judge((0.001, 0.001, 0.01)) == "impossible"  # A + B < C
    assert judge((0.0, 0.0, 0.002)) == "impossible"
    assert judge((-1.0, 1.0, 3.0)) == "impossible"
    assert judge((0.0075, 0.0025, 0.01)) == "valid"  # a thin plate: A + B = C


def test_box_cylinder_sphere_and_capsule_formulas() -> None:
    assert primitive_moments(shape('<box size="0.1 0.2 0.3"/>'), 12.0) == approx((0.13, 0.1, 0.05))
    assert primitive_moments(shape('<cylinder radius="0.1" length="0.3"/>'), 4.0) == approx(
        (4 * (3 * 0.01 + 0.09) / 12, 4 * (3 * 0.01 + 0.09) / 12, 4 * 0.01 / 2)
    )
    assert primitive_moments(shape('<sphere radius="0.5"/>'), 2.0) == approx((0.2, 0.2, 0.2))


def test_capsule_tends_to_sphere_and_cylinder() -> None:
    ball = primitive_moments(shape('<capsule radius="0.1" length="1e-9"/>'), 1.0)
    assert ball == approx((0.004, 0.004, 0.004), rel=1e-6)
    long = primitive_moments(shape('<capsule radius="0.001" length="1"/>'), 1.0)
    assert long is not None and long[0] == approx(1 / 12, rel=1e-2)


def test_bounding_box_of_rotated_primitives() -> None:
    owner = etree.fromstring(
        '<collision><origin xyz="0 0.25 0" rpy="1.5707963 0 0"/>'
        '<geometry><cylinder radius="0.05" length="0.6"/></geometry></collision>'
    )
    cylinder = read_shape(owner)
    assert cylinder is not None
    lo, hi = aabb(cylinder)  # type: ignore[misc]
    assert lo == approx((-0.05, -0.05, -0.05), abs=1e-6) and hi == approx(
        (0.05, 0.55, 0.05), abs=1e-6
    )
    owner = etree.fromstring(
        '<collision><origin rpy="0 0 0.7853982"/>'
        '<geometry><box size="1 1 1"/></geometry></collision>'
    )
    box = read_shape(owner)
    assert box is not None
    lo, hi = aabb(box)  # type: ignore[misc]
    assert hi == approx((math.sqrt(0.5), math.sqrt(0.5), 0.5), abs=1e-6)


def test_invalid_shape_has_no_inertia() -> None:
    assert primitive_moments(shape('<box size="0 1 1"/>'), 1.0) is None


def test_read_inertial_and_malformed_values() -> None:
    link = etree.fromstring(
        '<link name="a"><inertial><origin xyz="1 2 3"/><mass value="2"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="x"/></inertial></link>'
    )
    inertial = read_inertial(link)
    assert inertial is not None
    assert inertial.mass == 2.0 and inertial.xyz == (1.0, 2.0, 3.0)
    assert inertial.rpy == (0.0, 0.0, 0.0)
    assert inertial.tensor is None
    assert read_inertial(etree.fromstring('<link name="b"/>')) is None


LUMPED = b"""<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm"/>
  <joint name="f" type="fixed"><origin xyz="1 0 0"/><parent link="arm"/><child link="mass"/></joint>
  <link name="mass"><inertial><mass value="2"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="g" type="fixed"><origin xyz="-1 0 0"/>
    <parent link="arm"/><child link="other"/></joint>
  <link name="other"><inertial><mass value="2"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
</robot>"""


def test_lumped_body_combines_point_masses_with_the_parallel_axis_theorem() -> None:
    b = bodies(Document("r.urdf", LUMPED))
    assert b.merged("mass") and not b.merged("arm")
    assert b.body_of("mass") == "arm"
    found = b.inertia("arm")
    assert found is not None
    mass, com, tensor = found
    assert mass == 4.0 and com == approx((0.0, 0.0, 0.0))
    # two 2 kg point masses at x = +-1: a rod along x
    assert eigenvalues(tensor) == approx((0.0, 4.0, 4.0), abs=1e-12)
    assert not b.body_is_sound("mass")  # a rod has a zero moment


def test_times_rounds_ratios_for_messages() -> None:
    assert times(999.8) == "1000"
    assert times(15.04) == "15"
    assert times(3.0556e11) == "3.1e+11"
