"""The real robots in ../shared/corpus: no crash, valid JSON, only reviewed errors.

``REVIEWED_ERRORS`` is the set of error-level codes each robot is allowed to
produce: every one was read and judged a real defect (see the comments). A new
error code on a real robot fails this test until someone reviews it.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.conftest import CORPUS, corpus_models, needs_corpus

pytestmark = needs_corpus

REVIEWED_ERRORS: dict[str, set[str]] = {
    # Moving links without <inertial>: Gazebo drops each link, its joint and its subtree.
    "abb_irb2400": {"I001"},
    "allegro_hand_right": {"I001"},
    "spot": {"I001"},
    "robotiq_2f_85": {"I001"},
    # (anymal_c: its depth-camera links break A + B >= C (8.7e-6 + 6.7e-4 < 1.4e-3), but they
    # are welded to 'base', which Gazebo lumps them into and which stays valid: I005 warnings.)
    # <gazebo reference> to links that do not exist (rear camera, ee_link, depth cameras):
    # Gazebo drops those blocks without a message.
    "atlas_v5": {"G001"},
    "ur10_gazebo": {"G001"},
    "unitree_a1": {"G001"},
    "unitree_go1": {"G001"},
    # effort="-1" velocity="-1" (SDF's "unlimited", not URDF's): Pinocchio refuses the model
    # ("min_effort > max_effort"); P001 says so and cites the J010 finding.
    "eve_r3": {"J010"},  # P001 (Pinocchio refuses the effort) is J010's consequence
    # pybullet_data's iiwa pins its base with <mass value="0"/> (PyBullet's fixed-base
    # convention): Gazebo's converter drops the massless root and with it every link.
    "kuka_iiwa": {"I013"},
    # Gripper fingers with iyy = izz = 0 but ixx > 0: no rigid body has that tensor.
    "fetch": {"I003"},
    # Ten moving links with an all-zero (or -5e-20) tensor; r_ankle_1's moments are ~1e-20.
    "icub": {"I003", "I004"},
    # Missing gazebo references (6), massless finger-tip frames on the prismatic gripper
    # joints (Gazebo drops r/l_gripper_joint). (Its sensor mounts with 0.001 + 0.001 < 0.01 are
    # welded to a valid head body: I005 warnings.)
    "pr2": {"G001", "I001"},
    # All nine finger links: 0.0018 + 0.0024 < 0.0128.
    "robotiq_3f": {"I005"},
    # arm_1_link violates A + B >= C by 2 %. (The antennas' negative principal moments are
    # welded to a valid base body: I004 warnings.)
    "tiago": {"I005"},
    # Meshes referenced by relative path (meshes/*.STL) that this copy does not ship
    # (MANIFEST: "meshes not kept"): in this tree the files really are missing.
    "unitree_g1_29dof": {"C004"},
    # An unexpanded macro call <xacro:v1_pelvis_sensors_usb>: the pelvis IMU links are missing.
    "valkyrie": {"X008"},
}


@pytest.fixture(scope="module")
def report() -> dict:
    proc = subprocess.run(
        [sys.executable, "-m", "urdflint", "check", "--format", "json", str(CORPUS)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode in (0, 1), proc.stderr
    assert proc.stderr == ""
    return json.loads(proc.stdout)


def test_every_robot_is_checked_without_internal_errors(report: dict) -> None:
    assert report["summary"]["files"] == len(corpus_models()) == 36
    assert not [
        f for f in report["findings"] if f["code"].startswith("U00") and f["code"] != "U002"
    ]


def test_findings_are_well_formed(report: dict) -> None:
    for f in report["findings"]:
        assert f["line"] >= 1 and f["column"] >= 1
        assert f["element"].startswith("/robot")
        assert f["message"] and not f["message"].endswith(".")


@pytest.mark.parametrize("model", corpus_models(), ids=lambda p: p.parent.name)
def test_only_reviewed_errors(report: dict, model) -> None:
    robot = model.parent.name
    errors = {
        f["code"]
        for f in report["findings"]
        if f["path"] == str(model) and f["severity"] == "error"
    }
    assert errors == REVIEWED_ERRORS.get(robot, set()), f"{robot}: review these error codes"
