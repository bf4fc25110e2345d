"""urdflint.model.joints: reading a joint's axis and limit the way urdfdom does."""

from __future__ import annotations

import math

import pytest

from tests.helpers import lint_text
from urdflint.model import joints as J
from urdflint.model.document import Document, Joint


def joint(body: str, jtype: str = "revolute") -> Joint:
    doc = Document(
        "t.urdf",
        f'<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="{jtype}">'
        f'<parent link="a"/><child link="b"/>{body}</joint></robot>'.encode(),
    )
    return doc.joints[0]


def test_axis_defaults_like_urdfdom() -> None:
    assert J.axis(joint("")) == (1.0, 0.0, 0.0)
    assert J.axis(joint("<axis/>")) == (0.0, 0.0, 0.0)
    assert J.axis(joint('<axis xyz="0 1 0"/>')) == (0.0, 1.0, 0.0)
    assert J.axis(joint('<axis xyz="0 1"/>')) is None
    assert J.axis(joint('<axis xyz="0 ${a} 0"/>')) is None


def test_limit_distinguishes_absent_from_malformed() -> None:
    assert J.limit(joint("")) is None
    lim = J.limit(joint('<limit lower="-1" upper="oops" effort="2"/>'))
    assert lim is not None
    assert (lim.lower, lim.upper, lim.effort, lim.velocity) == (-1.0, None, 2.0, None)
    assert lim.has("upper") and not lim.has("velocity")


def test_norm_and_normalised() -> None:
    assert J.norm((3.0, 4.0, 0.0)) == 5.0
    assert J.normalised((0.0, 0.0, 2.0)) == (0.0, 0.0, 1.0)
    x, y, _ = J.normalised((1.0, 1.0, 0.0))
    assert math.isclose(x, math.sqrt(0.5)) and math.isclose(y, math.sqrt(0.5))
    assert J.fmt_vector((-0.0, 0.70710678, 1.0)) == "0 0.707107 1"


def test_units_per_type() -> None:
    assert J.units("prismatic") == ("m", "N", "m/s")
    assert J.units("revolute") == ("rad", "N·m", "rad/s")


def test_type_tables_are_consistent() -> None:
    assert J.BOUNDED <= J.ACTUATED <= J.TYPES
    assert J.AXIS_USED | J.AXIS_IGNORED == J.TYPES
    assert not J.AXIS_USED & J.AXIS_IGNORED


ROBOT = """<robot name="r"><link name="a"/>
<joint name="j" type="revolute"><origin xyz="0 0 0"/><parent link="a"/><child link="b"/>
<axis xyz="{axis}"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<link name="b"><inertial><mass value="1"/>
<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
</robot>"""


@pytest.mark.parametrize(
    ("axis", "options", "found"),
    [
        ("0.707107 0.707107 0", {}, False),
        ("0.577 0.577 0.577", {}, False),  # three decimals: |n - 1| = 6.1e-4
        ("0.577 0.577 0.577", {"tolerance": 1e-4}, True),
        ("0 0 1.01", {}, True),
        ("0 0 0", {}, False),  # J007's
    ],
)
def test_non_unit_axis_tolerance(axis: str, options: dict, found: bool) -> None:
    kwargs = {"rules": {"J008": options}} if options else {}
    hits = [
        f
        for f in lint_text(ROBOT.format(axis=axis), select=("J008",), **kwargs)
        if f.code == "J008"
    ]
    assert bool(hits) is found


def mimic_robot(follower: str, leader: str) -> str:
    def joint(name: str, kind: str, child: str, extra: str = "") -> str:
        return (
            f'<joint name="{name}" type="{kind}"><parent link="base"/><child link="{child}"/>'
            f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>{extra}'
            "</joint>"
        )

    return (
        '<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
        + joint("leader", leader, "a")
        + joint("follower", follower, "b", '<mimic joint="leader"/>')
        + "</robot>"
    )


@pytest.mark.parametrize(
    ("follower", "leader", "expected"),
    [
        # what Drake 1.51 does with each pair, observed: refuses (error) or ignores the mimic
        ("revolute", "continuous", None),
        ("prismatic", "revolute", None),
        ("revolute", "fixed", "error"),  # "which has 1 DOF cannot mimic ... which has 0 DOF"
        ("revolute", "planar", "error"),  # "... which has 3 DOF"
        (
            "revolute",
            "floating",
            "error",
        ),  # "mimic element specifies joint ... which does not exist"
        # a welded follower cannot move anyway: a warning until a Drake target exists
        ("fixed", "revolute", "warning"),  # "which has 0 DOF cannot mimic ... which has 1 DOF"
        ("fixed", "planar", "warning"),  # "which has 0 DOF cannot mimic ... which has 3 DOF"
        ("planar", "planar", "warning"),  # "The mimic element will be ignored."
        ("fixed", "fixed", None),  # ignored with a warning; nothing moves on either side
        ("revolute", "hinge", None),  # S006's
    ],
)
def test_j014_judges_each_pair_of_joint_types(
    follower: str, leader: str, expected: str | None
) -> None:
    found = lint_text(mimic_robot(follower, leader), select=("J014",))
    assert [f.severity.name.lower() for f in found] == ([expected] if expected else [])
    if found:
        assert found[0].element == "/robot/joint[@name='follower']/mimic"


def test_j014_leaves_undefined_and_self_mimics_to_s008() -> None:
    text = mimic_robot("revolute", "fixed")
    assert (
        lint_text(text.replace('<mimic joint="leader"/>', '<mimic joint="x"/>'), select=("J014",))
        == []
    )
    assert lint_text(text.replace('<mimic joint="leader"/>', "<mimic/>"), select=("J014",)) == []
