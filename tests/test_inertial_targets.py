"""Severities and messages of the I rules per target: welded links, massless links and models.

The fixture runner checks where findings land; these tests check how bad they are and what
they say, target by target (what each engine does was observed with sdformat's sources,
mujoco 4.0, pin 4.1, PyBullet 3.2.7 and Drake 1.51; see the rules' docs).
"""

from __future__ import annotations

from pathlib import Path

from tests.conftest import FIXTURES
from tests.helpers import lint_file, lint_text
from urdflint.engine import config
from urdflint.model.finding import Finding, Severity

RULES = FIXTURES / "rules"


def found(path: Path, code: str, *targets: str) -> list[Finding]:
    settings = config.from_mapping({"targets": list(targets) or ["gazebo-classic"]})
    settings = config.Settings(**{**settings.__dict__, "select": (code,)})
    return [f for f in lint_file(path, settings=settings) if f.code == code]


def severities(path: Path, code: str, *targets: str) -> list[Severity]:
    return [f.severity for f in found(path, code, *targets)]


# -- impossible values on welded links ------------------------------------------------------


def test_impossible_values_on_welded_links_warn_when_gazebo_lumps_them_into_a_valid_body() -> None:
    for code in ("I002", "I003", "I004", "I005"):
        path = RULES / code / "bad_welded.urdf"
        for targets in (("gazebo-classic",), ("gz-sim",), ("gazebo-classic", "gz-sim")):
            (finding,) = found(path, code, *targets)
            assert finding.severity is Severity.WARNING, (code, targets)
            assert "(welded: " in finding.message and "which stays valid" in finding.message
            # the same file feeds other consumers: the clause names those that refuse it
            # (MuJoCo ignores a negative mass on a welded link: I002 names none)
            refusing = finding.message.endswith("; MuJoCo refuses the file)")
            assert refusing is (code != "I002"), finding.message
        # MuJoCo checks every link before fusing static bodies: an error as soon as it is selected
        assert severities(path, code, "mujoco") == [Severity.ERROR]
        assert severities(path, code, "gazebo-classic", "mujoco") == [Severity.ERROR]


def test_impossible_tensor_on_a_welded_link_that_carries_the_body_is_an_error() -> None:
    (finding,) = found(RULES / "I005" / "bad_welded_body.urdf", "I005")
    assert finding.severity is Severity.ERROR and "welded" not in finding.message


def test_impossible_tensor_on_a_moving_link_is_an_error() -> None:
    assert severities(RULES / "I005" / "bad.urdf", "I005") == [Severity.ERROR]


def test_negative_mass_and_zero_moment_are_both_reported() -> None:
    text = (RULES / "I003" / "bad_negative_mass.urdf").read_text()
    codes = sorted(f.code for f in lint_text(text, select=("I002", "I003")))
    assert codes == ["I002", "I003"]
    assert all(f.severity is Severity.ERROR for f in lint_text(text, select=("I002", "I003")))


# -- links without mass -----------------------------------------------------------------------


def test_kinematics_only_model_gets_one_finding_listing_the_links() -> None:
    (finding,) = found(RULES / "I001" / "bad_kinematics_only.urdf", "I001")
    assert finding.severity is Severity.ERROR
    assert finding.message == (
        "no link has an <inertial> (a kinematics-only model?), so Gazebo Classic drops "
        "links 'upper_arm', 'forearm' and 'hand' with their joints"
    )


def test_missing_inertial_is_judged_per_link_when_some_links_have_one() -> None:
    assert len(found(RULES / "I001" / "bad_mujoco.urdf", "I001", "gazebo-classic")) == 2


def test_mujoco_makes_up_a_mass_from_collision_geometry_or_refuses_the_model() -> None:
    upper, fore = found(RULES / "I001" / "bad_mujoco.urdf", "I001", "mujoco")
    assert upper.severity is Severity.WARNING and "Gazebo" not in upper.message
    assert upper.message == (
        "link 'upper_arm' has no <inertial>, so MuJoCo makes up its mass and inertia from its "
        "collision geometry (1000 kg/m³)"
    )
    assert fore.severity is Severity.ERROR
    assert "MuJoCo refuses the model" in fore.message and "mjMINVAL" in fore.message


def test_mujoco_without_inertia_from_geometry_refuses_the_model(tmp_path: Path) -> None:
    text = (RULES / "I001" / "bad_mujoco.urdf").read_text()
    text = text.replace(
        '<robot name="arm">',
        '<robot name="arm"><mujoco><compiler inertiafromgeom="false"/></mujoco>',
    )
    path = tmp_path / "arm.urdf"
    path.write_text(text)
    assert severities(path, "I001", "mujoco") == [Severity.ERROR, Severity.ERROR]


def test_several_targets_name_each_consequence_at_the_highest_severity() -> None:
    upper, _ = found(RULES / "I001" / "bad_mujoco.urdf", "I001", "gazebo-classic", "mujoco")
    assert upper.severity is Severity.ERROR
    assert upper.message == (
        "link 'upper_arm' has no <inertial>, so Gazebo Classic drops it, its joint 'shoulder' "
        "and the 2 links below it; MuJoCo makes up its mass and inertia from its collision "
        "geometry (1000 kg/m³)"
    )


def test_zero_mass_on_a_moving_link_is_refused_by_mujoco() -> None:
    (finding,) = found(RULES / "I002" / "bad_zero.urdf", "I002", "mujoco")
    assert finding.severity is Severity.ERROR and "MuJoCo refuses the model" in finding.message


def test_mujoco_fuses_massless_frames_and_ignores_a_static_root() -> None:
    assert found(RULES / "I001" / "good_mujoco.urdf", "I001", "mujoco") == []
    assert found(RULES / "I001" / "good.urdf", "I001", "mujoco") == []


# -- massless models (I013) -------------------------------------------------------------------


def test_massless_model_severity() -> None:
    (pinned,) = found(RULES / "I013" / "bad.urdf", "I013")
    assert pinned.severity is Severity.ERROR
    assert pinned.message == (
        "root link 'base_link' has mass 0 kg, so Gazebo Classic drops it and with it the whole "
        'model (2 links): sdformat finds no link to load ("A model must have at least one link")'
    )
    (single,) = found(RULES / "I013" / "bad_single.urdf", "I013", "gz-sim")
    assert single.severity is Severity.ERROR
    assert single.message.startswith("the only link, 'table', has mass 0 kg, so Gazebo Sim drops")
    (frame,) = found(RULES / "I013" / "bad_frame.urdf", "I013")
    assert frame.severity is Severity.WARNING


def test_massless_model_is_a_gazebo_rule() -> None:
    assert found(RULES / "I013" / "bad.urdf", "I013", "mujoco") == []


def test_massless_root_is_reported_once() -> None:
    text = (RULES / "I013" / "bad.urdf").read_text()
    assert sorted(f.code for f in lint_text(text, select=("I0",))) == ["I013"]


def test_massless_root_with_a_preserved_fixed_child_is_still_lost() -> None:
    text = (
        (RULES / "I013" / "good.urdf")
        .read_text()
        .replace(
            "</robot>",
            '<gazebo reference="base_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
            "</robot>",
        )
    )
    assert [f.code for f in lint_text(text, select=("I013",))] == ["I013"]
