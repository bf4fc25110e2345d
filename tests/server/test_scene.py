"""The 3D scene of the check answer (``urdflint/outputs/scene.py``, ``scene=true``): poses
through the joints, the equivalent inertia boxes, centres of mass, joint axes, which link
each finding colours, and meshes read only inside the request's folder, within a budget."""

from __future__ import annotations

import base64
import math
import struct
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import FIXTURES
from tests.server.attacks import MESHES, STL, make_zip, mesh_robot

np = pytest.importorskip("numpy")

from urdflint.engine import config, linter  # noqa: E402
from urdflint.engine.context import Context  # noqa: E402
from urdflint.outputs import scene_meshes  # noqa: E402
from urdflint.outputs.scene import build_scene, equivalent_box, quaternion  # noqa: E402

VIEW = FIXTURES / "models" / "inertia_view.urdf"
BROKEN = FIXTURES / "models" / "broken_arm.urdf"


def scene_of(
    path: Path, context: Context | None = None, **settings: Any
) -> tuple[dict[str, Any], list[Any]]:
    result = linter.lint_path(path, path.name, config.from_mapping(settings), context)
    assert result.document is not None
    found = build_scene(result.document, result.findings)
    assert found is not None
    return found, list(result.findings)


def by_name(items: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    return {item["name"]: item for item in items}


def rotate(vector: list[float], at: list[float]) -> np.ndarray:
    """``vector`` turned by the quaternion of an ``at`` pose."""
    x, y, z, w = at[3:]
    q = np.array([x, y, z])
    v = np.array(vector, dtype=float)
    return v + 2 * np.cross(q, np.cross(q, v) + w * v)


# -- the inertia box ---------------------------------------------------------------------------


def test_equivalent_box_of_a_known_tensor_is_gazebos() -> None:
    # a uniform 0.4 x 0.3 x 0.1 box of 4 kg: m/12 (b^2 + c^2) ...
    tensor = (4 / 12 * (0.09 + 0.01), 4 / 12 * (0.16 + 0.01), 4 / 12 * (0.16 + 0.09), 0, 0, 0)
    box, problem = equivalent_box(4.0, tensor)
    assert box is not None and problem is None
    size, rotation, valid = box
    assert valid and size == pytest.approx([0.4, 0.3, 0.1], abs=1e-12)
    assert np.allclose(rotation, np.eye(3))
    # Gazebo's formula, side by side: sqrt(6/m (Iyy + Izz - Ixx)) ...
    ixx, iyy, izz = tensor[:3]
    assert size[0] == pytest.approx(math.sqrt(6 / 4 * (iyy + izz - ixx)))


def test_a_rotated_tensor_gives_the_same_box_along_its_principal_axes() -> None:
    turn = math.radians(30)  # about z
    r = np.array(
        [[math.cos(turn), -math.sin(turn), 0], [math.sin(turn), math.cos(turn), 0], [0, 0, 1]]
    )
    moments = np.diag([2 / 12 * (0.04 + 0.01), 2 / 12 * (0.25 + 0.01), 2 / 12 * (0.25 + 0.04)])
    tensor = r @ moments @ r.T  # a 0.5 x 0.2 x 0.1 box of 2 kg, turned 30 degrees
    flat = (tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[0, 2], tensor[1, 2])
    box, _ = equivalent_box(2.0, flat)
    assert box is not None
    size, rotation, valid = box
    assert valid and size == pytest.approx([0.5, 0.2, 0.1], abs=1e-9)
    assert np.allclose(rotation, r, atol=1e-9)  # each side along its own axis, right-handed
    assert np.linalg.det(rotation) == pytest.approx(1.0)


def test_impossible_and_massless_tensors() -> None:
    box, problem = equivalent_box(1.0, (0.01, 0.01, 0.03, 0, 0, 0))  # 0.01 + 0.01 < 0.03
    assert box is not None and not box[2] and box[0][2] == 0.0 and "no rigid body" in str(problem)
    assert equivalent_box(-1.0, (0.01, 0.01, 0.01, 0, 0, 0)) == (None, "the mass is not positive")
    assert equivalent_box(1.0, None)[0] is None
    assert equivalent_box(1.0, (0, 0, 0, 0, 0, 0))[1] == "the inertia tensor is zero"


def test_quaternions_of_rotations() -> None:
    assert quaternion(np.eye(3)) == pytest.approx((0, 0, 0, 1))
    half = math.sqrt(0.5)
    about_z = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    assert quaternion(about_z) == pytest.approx((0, 0, half, half))
    flip_x = np.diag([1.0, -1, -1])  # trace -1: the other branch
    assert quaternion(flip_x) == pytest.approx((1, 0, 0, 0))


# -- the fixture robot -----------------------------------------------------------------------


def test_inertia_view_boxes_coms_and_colours() -> None:
    scene, findings = scene_of(VIEW)
    codes = sorted(f.code for f in findings)
    assert codes == ["I007", "I008"]  # the fixture's two deliberate mistakes, nothing else
    links = by_name(scene["links"])
    assert list(links) == [
        "base_footprint",
        "base_link",
        "column",
        "upper_arm",
        "forearm",
        "gripper",
    ]

    base = links["base_link"]["inertial"]
    assert base["box"]["size"] == pytest.approx([0.4, 0.3, 0.1], abs=1e-4)  # hugs the visual box
    assert base["com"] == [0.0, 0.0, 0.05] and links["base_link"]["severity"] is None

    gripper = links["gripper"]
    side = math.sqrt(6 / 0.3 * 0.18)  # the tensor 1000x too large: a 1.9 m cube around 6 cm
    assert gripper["inertial"]["box"]["size"] == pytest.approx([side] * 3, abs=1e-5)
    assert gripper["inertial"]["box"]["valid"] is True
    assert gripper["severity"] == gripper["inertia_severity"] == "warning"
    assert [findings[i].code for i in gripper["findings"]] == ["I007"]
    assert gripper["at"][:3] == pytest.approx([0.68, 0, 0.5])  # base 0.1 + 0.4 up; 0.35 + 0.33 out

    arm = links["upper_arm"]
    assert arm["at"][:3] == pytest.approx([0, 0, 0.5])
    assert arm["inertial"]["com"] == pytest.approx([0.175, 0, 0.8])  # 0.3 m above the bar
    top = arm["visual"][0]["at"][2] + arm["visual"][0]["size"][2] / 2
    assert arm["inertial"]["com"][2] > top + 0.25
    assert [findings[i].code for i in arm["findings"]] == ["I008"]
    assert arm["inertia_severity"] == "warning" and arm["parent"] == "shoulder"

    joints = by_name(scene["joints"])
    assert joints["shoulder"]["axis"] == {"origin": [0, 0, 0.5], "direction": [0, 1, 0]}
    assert joints["wrist"]["axis"] is None  # fixed
    assert scene["meshes"] == [] and scene["notes"] == [] and scene["q"] == {}


def test_a_joint_position_moves_the_links_below_it() -> None:
    scene, _ = scene_of(VIEW, expect={"q": {"shoulder": math.pi / 2}})
    links = by_name(scene["links"])
    assert scene["q"] == {"shoulder": pytest.approx(math.pi / 2)}
    # the arm turns down about y: the forearm's frame, 0.35 m along x, ends 0.35 m below
    assert links["forearm"]["at"][:3] == pytest.approx([0, 0, 0.15], abs=1e-6)
    assert links["gripper"]["at"][:3] == pytest.approx([0, 0, 0.5 - 0.68], abs=1e-6)
    assert links["column"]["at"][:3] == pytest.approx([0, 0, 0.1])  # above it: unmoved
    assert rotate([1, 0, 0], links["forearm"]["at"]) == pytest.approx([0, 0, -1], abs=1e-6)
    com = links["upper_arm"]["inertial"]["com"]  # (0.175, 0, 0.3) in the turned frame
    assert com == pytest.approx([0.3, 0, 0.5 - 0.175], abs=1e-6)
    assert by_name(scene["joints"])["elbow"]["axis"]["origin"] == pytest.approx([0, 0, 0.15])


def test_broken_arm_colours_links_by_their_own_and_their_joints_findings() -> None:
    scene, findings = scene_of(BROKEN)
    links = by_name(scene["links"])
    codes = {name: {findings[i].code for i in link["findings"]} for name, link in links.items()}
    assert {"J001", "J007", "I002", "I005"} <= codes["upper_arm"]  # its joint's count too
    assert links["upper_arm"]["severity"] == "error"
    assert links["upper_arm"]["inertial"]["box"] is None  # mass -1: no box...
    assert links["upper_arm"]["inertial"]["problem"] == "the mass is not positive"
    assert links["upper_arm"]["inertial"]["com"] == pytest.approx([0, 0, 0.3])  # ...its COM
    assert links["base_link"]["severity"] == "warning" and "X007" in codes["base_link"]
    assert links["base_footprint"]["severity"] is None
    assert links["forearm"]["collision"] == []  # a negative radius is not drawn (C003)
    assert links["forearm"]["parent"] == "elbow"  # the first parent joint; the brace is extra
    joints = by_name(scene["joints"])
    assert joints["shoulder"]["axis"] is None  # the zero axis (J007)
    assert joints["wrist"]["child"] == "hand" and joints["wrist"]["severity"] == "error"
    assert "hand" not in links  # undefined: the outline shows it from the joint


# -- meshes -----------------------------------------------------------------------------------


def decoded(mesh: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    positions = np.frombuffer(base64.b64decode(mesh["positions"]), dtype="<f4").reshape(-1, 3)
    kind = "<u2" if mesh["index"] == "u16" else "<u4"
    return positions, np.frombuffer(base64.b64decode(mesh["indices"]), dtype=kind).reshape(-1, 3)


def test_meshes_are_read_inside_the_root_only(tmp_path: Path) -> None:
    pytest.importorskip("trimesh")
    root = tmp_path / "files"
    (root / "pkg" / "meshes").mkdir(parents=True)
    (root / "pkg" / "meshes" / "box.stl").write_bytes(STL)
    (tmp_path / "secret.stl").write_bytes(STL)  # beside the root: must never be read
    urdf = root / "r.urdf"
    body = mesh_robot("package://pkg/meshes/box.stl")
    body = body.replace("</robot>", _extra_links("../secret.stl", "package://pkg/meshes/no.stl"))
    urdf.write_text(body)
    context = Context(package_paths={"pkg": root / "pkg"}, root=root, environ={})
    scene, _ = scene_of(urdf, context)
    shapes = [s for link in scene["links"] for s in link["visual"] + link["collision"]]
    meshes = {s["file"]: s for s in shapes if s["kind"] == "mesh"}
    assert meshes["package://pkg/meshes/box.stl"]["mesh"] == 0
    assert meshes["../secret.stl"]["mesh"] is None and meshes["../secret.stl"]["missing"]
    assert "no file" in meshes["package://pkg/meshes/no.stl"]["missing"]
    [mesh] = scene["meshes"]
    positions, faces = decoded(mesh)
    assert (mesh["vertices"], mesh["triangles"], mesh["simplified"]) == (4, 4, None)
    assert positions.shape == (4, 3) and faces.max() == 3
    assert positions.max() == pytest.approx(0.1)  # the tetrahedron's 10 cm, in metres


def _extra_links(*uris: str) -> str:
    parts = []
    for index, uri in enumerate(uris):
        parts.append(
            f'<link name="extra{index}"><visual><geometry><mesh filename="{uri}"/></geometry>'
            "</visual></link>"
            f'<joint name="e{index}" type="fixed"><parent link="base_link"/>'
            f'<child link="extra{index}"/></joint>'
        )
    return "".join(parts) + "</robot>"


def test_big_meshes_are_simplified_within_the_budget() -> None:
    trimesh = pytest.importorskip("trimesh")
    ball = trimesh.creation.icosphere(subdivisions=4, radius=0.1)  # 5120 triangles
    entry = scene_meshes.Entry("ball.stl", ball.vertices, ball.faces)
    whole = scene_meshes.encode(entry, 10_000)
    assert whole["simplified"] is None and whole["triangles"] == 5120
    cut = scene_meshes.encode(entry, 800)
    assert cut["simplified"] == "clustered" and 200 < cut["triangles"] <= 800
    positions, faces = decoded(cut)
    assert cut["original_triangles"] == 5120 and faces.max() < len(positions)
    assert np.linalg.norm(positions, axis=1) == pytest.approx(0.1, abs=0.02)  # still a ball
    tiny = scene_meshes.encode(entry, 12)
    assert tiny["simplified"] == "bounding box" and tiny["triangles"] == 12
    assert decoded(tiny)[0].max(axis=0) == pytest.approx([0.1, 0.1, 0.1], abs=1e-6)


def test_the_budget_is_shared_fairly() -> None:
    assert scene_meshes.allot([100, 200, 300], 10_000) == [100, 200, 300]
    assert scene_meshes.allot([100, 5000, 5000], 3100) == [100, 1500, 1500]
    assert scene_meshes.allot([1, 50_000], 1000) == [12, 988]  # never below a box's 12


# -- the API ----------------------------------------------------------------------------------


def test_scene_option_adds_the_scene(client: Any) -> None:
    files = {"urdf": ("view.urdf", VIEW.read_bytes(), "application/xml")}
    answer = client.post("/v1/check", files=files, data={"scene": "true", "q": "shoulder=0.5"})
    assert answer.status_code == 200
    data = answer.json()
    scene = data["scene"]["view.urdf"]
    assert scene["q"] == {"shoulder": 0.5}
    gripper = by_name(scene["links"])["gripper"]
    assert [data["findings"][i]["code"] for i in gripper["findings"]] == ["I007"]
    plain = client.post("/v1/check", files=files).json()
    assert "scene" not in plain
    refused = client.post("/v1/check", files=files, data={"scene": "perhaps"})
    assert refused.status_code == 422 and "scene" in refused.json()["detail"]
    parameters = client.get("/openapi.json").json()["paths"]["/v1/check"]["post"]["parameters"]
    assert "scene" in {p["name"] for p in parameters}


def test_scene_meshes_come_from_the_zip_and_never_name_the_servers_folders(client: Any) -> None:
    pytest.importorskip("trimesh")
    urdf = mesh_robot("package://pkg/meshes/box.stl").replace(
        "</robot>", _extra_links("package://pkg/meshes/gone.stl", "file:///etc/passwd")
    )
    answer = client.post(
        "/v1/check",
        files={"urdf": ("r.urdf", urdf.encode(), "application/xml"), "meshes": ("m.zip", MESHES)},
        data={"scene": "true"},
    )
    assert answer.status_code == 200
    scene = answer.json()["scene"]["r.urdf"]
    [mesh] = scene["meshes"]
    assert mesh["triangles"] == 4 and mesh["file"] == "package://pkg/meshes/box.stl"
    missing = [s for link in scene["links"] for s in link["visual"] if s.get("missing")]
    assert len(missing) == 2
    text = str(scene["links"])
    assert "urdflint-" not in text and "/tmp" not in text  # the request folder stays hidden


def test_a_binary_mesh_from_the_zip_arrives_whole_under_the_budget(client: Any) -> None:
    trimesh = pytest.importorskip("trimesh")
    ball = trimesh.creation.icosphere(subdivisions=5, radius=0.1)  # 20480 triangles
    data = ball.export(file_type="stl")
    assert isinstance(data, bytes) and struct.unpack("<I", data[80:84])[0] == 20480
    answer = client.post(
        "/v1/check",
        files={
            "urdf": ("r.urdf", mesh_robot("package://pkg/meshes/ball.stl").encode()),
            "meshes": ("m.zip", make_zip([("pkg/meshes/ball.stl", data)])),
        },
        data={"scene": "true", "select": "C004"},
    )
    assert answer.status_code == 200
    [mesh] = answer.json()["scene"]["r.urdf"]["meshes"]
    assert mesh["original_triangles"] == 20480 and mesh["simplified"] is None  # under budget
    positions, faces = decoded(mesh)
    assert mesh["index"] == "u16" and len(faces) == 20480 and len(positions) == mesh["vertices"]
