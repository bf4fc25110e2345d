"""Inertials computed from a link's geometry, and MuJoCo's balancing (``urdflint fix``)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from urdflint.engine.config import Settings
from urdflint.engine.context import Context
from urdflint.model.document import Document
from urdflint.model.inertia import Mat, eigenvalues, judge, matrix, rotate, rpy_matrix
from urdflint.sources.inertia_from_geometry import (
    Estimate,
    balance,
    geometry_inertial,
    inertia_attributes,
    inertial_xml,
)

approx = pytest.approx
FLOAT32 = 1e-6  # STL files store single precision


def document(body: str, base: Path | None = None) -> Document:
    """A robot with one link ``part`` holding ``body``."""
    text = f'<robot name="r"><link name="part">{body}</link></robot>'
    return Document("r.urdf", text.encode(), settings=Settings(), context=Context(), base_dir=base)


def collision(shape: str, origin: str = "") -> str:
    return f"<collision>{origin}<geometry>{shape}</geometry></collision>"


def estimate(body: str, mass: float | None = 2.0, **kwargs: object) -> Estimate:
    found = geometry_inertial(document(body), "part", mass, **kwargs)  # type: ignore[arg-type]
    assert found is not None
    return found


def diagonal(a: float, b: float, c: float) -> Mat:
    return ((a, 0.0, 0.0), (0.0, b, 0.0), (0.0, 0.0, c))


def same(found: Mat, expected: Mat, rel: float = 1e-9) -> None:
    scale = max(abs(v) for row in expected for v in row)
    for row, want in zip(found, expected, strict=True):
        assert list(row) == approx(list(want), rel=rel, abs=rel * 1e-3 * scale)


# -- primitives at the declared mass ------------------------------------------------------------


def test_box() -> None:
    found = estimate(collision('<box size="0.1 0.2 0.3"/>'), mass=2.0)
    assert (found.mass, found.com, found.method) == (2.0, (0.0, 0.0, 0.0), "box")
    same(found.tensor, diagonal(2 * 0.13 / 12, 2 * 0.10 / 12, 2 * 0.05 / 12))
    assert found.volume == approx(0.006)


def test_cylinder_along_z() -> None:
    found = estimate(collision('<cylinder radius="0.05" length="0.4"/>'), mass=3.0)
    side = 3.0 * (3 * 0.05**2 + 0.4**2) / 12
    same(found.tensor, diagonal(side, side, 3.0 * 0.05**2 / 2))
    assert found.method == "cylinder"


def test_sphere() -> None:
    found = estimate(collision('<sphere radius="0.1"/>'), mass=5.0)
    same(found.tensor, diagonal(0.02, 0.02, 0.02))


def test_capsule_is_a_cylinder_and_two_hemispheres() -> None:
    r, h, m = 0.05, 0.2, 4.0
    found = estimate(collision(f'<capsule radius="{r}" length="{h}"/>'), mass=m)
    cylinder, ball = math.pi * r * r * h, 4 / 3 * math.pi * r**3
    mc, mh = m * cylinder / (cylinder + ball), m * ball / (cylinder + ball) / 2
    # a hemisphere about its own centre (3r/8 from the flat face), moved out to the capsule's
    hemisphere = (2 / 5 - (3 / 8) ** 2) * mh * r * r + mh * (h / 2 + 3 * r / 8) ** 2
    side = mc * (3 * r * r + h * h) / 12 + 2 * hemisphere
    same(found.tensor, diagonal(side, side, mc * r * r / 2 + 2 * (2 / 5) * mh * r * r))
    assert found.volume == approx(cylinder + ball)


def test_an_offset_and_rotated_origin_moves_the_centre_and_turns_the_axes() -> None:
    origin = '<origin xyz="0.1 0.2 0.3" rpy="1.5707963267948966 0 0"/>'
    found = estimate(collision('<cylinder radius="0.05" length="0.4"/>', origin), mass=3.0)
    assert found.com == approx((0.1, 0.2, 0.3))
    side = 3.0 * (3 * 0.05**2 + 0.4**2) / 12
    same(found.tensor, diagonal(side, 3.0 * 0.05**2 / 2, side))  # roll 90°: the axis is y


def test_a_yawed_box_has_products_of_inertia() -> None:
    origin = '<origin rpy="0 0 0.5"/>'
    found = estimate(collision('<box size="0.1 0.2 0.3"/>', origin), mass=2.0)
    ixx, iyy, izz = 2 * 0.13 / 12, 2 * 0.10 / 12, 2 * 0.05 / 12
    c, s = math.cos(0.5), math.sin(0.5)
    expected = (
        (c * c * ixx + s * s * iyy, c * s * (ixx - iyy), 0.0),
        (c * s * (ixx - iyy), s * s * ixx + c * c * iyy, 0.0),
        (0.0, 0.0, izz),
    )
    same(found.tensor, expected)


def test_two_shapes_combine_with_the_parallel_axis_theorem() -> None:
    box = '<box size="0.1 0.1 0.1"/>'
    body = collision(box, '<origin xyz="0.3 0 0"/>') + collision(box, '<origin xyz="-0.1 0 0"/>')
    found = estimate(body, mass=2.0)
    assert found.com == approx((0.1, 0.0, 0.0))
    own = 1.0 * 0.02 / 12  # each box has half the mass
    same(found.tensor, diagonal(2 * own, 2 * (own + 0.2**2), 2 * (own + 0.2**2)))
    assert found.method == "2 shapes: box + box"


def test_the_mass_is_spread_in_proportion_to_the_volumes() -> None:
    body = collision('<box size="0.1 0.1 0.1"/>') + collision(
        '<box size="0.1 0.1 0.3"/>', '<origin xyz="0 0 0.2"/>'
    )
    found = estimate(body, mass=4.0)  # volumes 1:3, so 1 kg at z = 0 and 3 kg at z = 0.2
    assert found.mass == 4.0
    assert found.com == approx((0.0, 0.0, 0.15))
    izz = 1.0 * 0.02 / 12 + 3.0 * 0.02 / 12
    ixx = 1.0 * 0.02 / 12 + 1.0 * 0.15**2 + 3.0 * 0.10 / 12 + 3.0 * 0.05**2
    same(found.tensor, diagonal(ixx, ixx, izz))


def test_density_gives_the_mass() -> None:
    found = geometry_inertial(
        document(collision('<box size="0.1 0.1 0.1"/>')), "part", density=1000.0
    )
    assert found is not None
    assert found.mass == approx(1.0)
    assert found.density == approx(1000.0)
    same(found.tensor, diagonal(0.02 / 12, 0.02 / 12, 0.02 / 12))


def test_visuals_only_when_asked() -> None:
    body = '<visual><geometry><sphere radius="0.1"/></geometry></visual>'
    assert geometry_inertial(document(body), "part", 1.0) is None
    found = geometry_inertial(document(body), "part", 1.0, use_visual=True)
    assert found is not None and found.tensor[0][0] == approx(0.004)


@pytest.mark.parametrize(
    "body",
    [
        "",  # no collision
        collision('<box size="0.1 0 0.1"/>'),
        collision('<box size="0.1 0.1"/>'),
        collision('<box size="1 1 1"/>') + collision('<cylinder radius="0.1"/>'),
        collision('<box size="1 1 1"/>') + "<collision><geometry/></collision>",
        collision('<box size="1 1 1"/>', '<origin xyz="0 0 a"/>'),
        collision('<mesh filename="missing.stl"/>'),
    ],
)
def test_unusable_geometry_gives_nothing(body: str) -> None:
    assert geometry_inertial(document(body), "part", 1.0) is None


def test_unknown_link_and_bad_arguments() -> None:
    doc = document(collision('<sphere radius="0.1"/>'))
    assert geometry_inertial(doc, "nope", 1.0) is None
    with pytest.raises(ValueError):
        geometry_inertial(doc, "part")
    with pytest.raises(ValueError):
        geometry_inertial(doc, "part", 1.0, 1000.0)
    with pytest.raises(ValueError):
        geometry_inertial(doc, "part", -1.0)


# -- meshes ---------------------------------------------------------------------------------------


def write_box(path: Path, extents: tuple[float, float, float], open_top: bool = False) -> None:
    trimesh = pytest.importorskip("trimesh")
    mesh = trimesh.creation.box(extents=extents)
    mesh.apply_translation((0.0, 0.0, extents[2] / 2))  # standing on z = 0
    if open_top:
        keep = [i for i, n in enumerate(mesh.face_normals) if n[2] < 0.5]
        mesh = trimesh.Trimesh(mesh.vertices, mesh.faces[keep], process=False)
        assert not mesh.is_watertight
    mesh.export(path)


@pytest.mark.parametrize(
    ("open_top", "origin", "method", "com"),
    [
        (False, '<origin xyz="1 0 0"/>', "mesh (solid)", (1.0, 0.0, 0.15)),
        (True, "", "mesh (convex hull)", (0.0, 0.0, 0.15)),
    ],
    ids=["watertight-solid", "open-convex-hull"],
)
def test_a_mesh_is_a_solid_or_its_hull(tmp_path: Path, open_top, origin, method, com) -> None:
    write_box(tmp_path / "box.stl", (0.1, 0.2, 0.3), open_top=open_top)
    body = collision('<mesh filename="box.stl"/>', origin)
    found = geometry_inertial(document(body, tmp_path), "part", 2.0)
    assert found is not None
    assert found.method == method
    assert found.com == approx(com)
    same(found.tensor, diagonal(2 * 0.13 / 12, 2 * 0.10 / 12, 2 * 0.05 / 12), rel=FLOAT32)


def test_a_mesh_scale_applies(tmp_path: Path) -> None:
    write_box(tmp_path / "box.stl", (0.1, 0.2, 0.3))
    body = collision('<mesh filename="box.stl" scale="2 1 1"/>')
    found = geometry_inertial(document(body, tmp_path), "part", density=1000.0)
    assert found is not None
    assert found.mass == approx(12.0)
    same(found.tensor, diagonal(12 * 0.13 / 12, 12 * 0.13 / 12, 12 * 0.08 / 12), rel=FLOAT32)


def test_a_mesh_and_a_primitive_combine(tmp_path: Path) -> None:
    write_box(tmp_path / "box.stl", (0.1, 0.1, 0.1))
    body = collision('<mesh filename="box.stl"/>') + collision(
        '<box size="0.1 0.1 0.1"/>', '<origin xyz="0 0 0.15"/>'
    )
    found = geometry_inertial(document(body, tmp_path), "part", 2.0)
    assert found is not None
    assert found.method == "2 shapes: mesh (solid) + box"
    assert found.com == approx((0.0, 0.0, 0.1))
    own = 0.02 / 12
    same(found.tensor, diagonal(2 * (own + 0.05**2), 2 * (own + 0.05**2), 2 * own), rel=FLOAT32)


def test_a_mesh_in_millimetres_is_not_used(tmp_path: Path) -> None:
    write_box(tmp_path / "big.stl", (100.0, 100.0, 100.0))
    assert (
        geometry_inertial(document(collision('<mesh filename="big.stl"/>'), tmp_path), "part", 1.0)
        is None
    )


# -- balancing ------------------------------------------------------------------------------------


def test_balance_averages_the_moments_like_mujoco() -> None:
    assert balance(diagonal(1.0, 1.0, 3.0)) == diagonal(5 / 3, 5 / 3, 5 / 3)


def test_balance_of_a_rotated_tensor_keeps_the_trace() -> None:
    tensor = rotate(diagonal(0.1, 0.2, 0.5), rpy_matrix((0.3, -0.7, 1.1)))
    found = balance(tensor)
    same(found, diagonal(0.8 / 3, 0.8 / 3, 0.8 / 3))
    a, b, c = eigenvalues(found)
    assert a + b >= c
    assert judge((a, b, c)) == "valid"


def test_balance_averages_a_negative_moment_away() -> None:
    found = balance(diagonal(-0.1, 0.4, 0.6))
    same(found, diagonal(0.3, 0.3, 0.3))
    with pytest.raises(ValueError):
        balance(diagonal(-1.0, 0.1, 0.2))


@pytest.mark.parametrize(
    "tensor",
    [
        diagonal(1.0, 1.0, 2.0),  # A + B = C: a flat plate, physical
        diagonal(0.1, 0.2, 0.25),
        matrix((2.0, 2.0, 3.0, 1.0, 0.0, 0.0)),
        diagonal(1.0, 1.0, 2.0 + 1e-9),  # within the linter's tolerance
    ],
)
def test_balance_leaves_physical_tensors_alone(tensor: Mat) -> None:
    assert balance(tensor) is tensor


# -- writing --------------------------------------------------------------------------------------


def test_inertia_attributes_are_six_significant_digits_in_urdf_order() -> None:
    tensor = ((1 / 120, -0.0, 1e-20), (-0.0, 2 / 3, -1.5e-7), (1e-20, -1.5e-7, 0.6753219))
    assert inertia_attributes(tensor) == {
        "ixx": "0.00833333",
        "ixy": "0",
        "ixz": "0",  # rounding noise
        "iyy": "0.666667",
        "iyz": "-1.5e-07",
        "izz": "0.675322",
    }
    assert inertia_attributes(diagonal(1e-12, 2e-12, 2.5e-12))["ixx"] == "1e-12"
    assert list(inertia_attributes(tensor)) == ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]


def test_inertial_xml_follows_the_file_style() -> None:
    found = Estimate(2.0, (0.1, 1e-17, -0.0), diagonal(1 / 60, 0.02, 0.01), "box", 0.006)
    text = inertial_xml(found, "\t", "\r\n", base="\t")
    assert text == (
        "<inertial>\r\n"
        '\t\t<origin xyz="0.1 0 0" rpy="0 0 0"/>\r\n'
        '\t\t<mass value="2"/>\r\n'
        '\t\t<inertia ixx="0.0166667" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.01"/>\r\n'
        "\t</inertial>"
    )
    assert inertial_xml(found, "  ", "\n").splitlines()[1].startswith('  <origin xyz="0.1 0 0"')
