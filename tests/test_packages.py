"""Real description packages: defects planted in macro bodies are reported where they are written.

fixtures/packages/ is a cut-down ROS workspace (see its README.md): real description
packages of several vendors, ROS 1 and ROS 2, with only the files their entry files
expand. Each test copies the whole workspace (packages include each other), plants
defects inside ``<xacro:macro>`` bodies of the package's macro files by text edits
that keep every line where it was, lints the entry file, and checks that each defect
is reported exactly once, at the macro file and the line where it was planted, with
the macro call chain leading back into the package.
"""

from __future__ import annotations

import functools
import json
import re
import shutil
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import FIXTURES
from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.model.finding import Finding

pytest.importorskip("xacro")

PACKAGES = FIXTURES / "packages"
ENTRIES: dict[str, dict[str, str]] = {
    item["entry"]: item["args"]
    for item in json.loads((PACKAGES / "entries.json").read_text(encoding="utf-8"))
}
PLANTED = ("I002", "I005", "J007", "J009", "X007", "G001")
MISSPELT = {"collision": "colision", "inertial": "inertail", "visual": "visaul"}
TAG = {"I002": "mass", "I005": "inertia", "J007": "axis", "J009": "limit"}
COMMENT_RE = re.compile(r"<!--.*?-->", re.S)


@dataclass(frozen=True)
class Plant:
    """One defect, planted in the body of ``macro`` in ``file`` (relative to the workspace).

    ``nth`` picks the element among the body's elements of that kind (``tag`` names the
    element X007 misspells); G001 adds ``<gazebo reference="{ref}"/>`` right after the
    macro's start tag. ``instances``: how often the expansion writes the planted line.
    """

    file: str
    macro: str
    code: str
    nth: int = 0
    tag: str = ""
    ref: str = "no_such_link"
    instances: int = 1


# entry file -> the defects planted for it (each kind in several packages, each defect in
# a macro file of the package or of a package it includes, never in the entry file)
PLANTS: dict[str, list[Plant]] = {
    "ur_description/urdf/ur.urdf.xacro": [
        Plant("ur_description/urdf/ur_macro.xacro", "ur_robot", "J009"),
        Plant("ur_description/urdf/ur_macro.xacro", "ur_robot", "I005"),
        Plant(
            "ur_description/urdf/ur_macro.xacro", "ur_robot", "G001", ref="${tf_prefix}no_such_link"
        ),
        Plant("ur_description/urdf/inc/ur_common.xacro", "cylinder_inertial", "I002"),
    ],
    "franka_description/robots/fr3/fr3.urdf.xacro": [
        Plant(
            "franka_description/robots/common/utils.xacro", "franka-inertials", "I005", instances=8
        ),
        Plant(
            "franka_description/robots/common/utils.xacro",
            "link_with_sc",
            "X007",
            tag="visual",
            instances=8,
        ),
        Plant("franka_description/robots/common/franka_arm.xacro", "franka_arm", "J007"),
    ],
    "franka_description/robots/multi_arm/multi_arm.urdf.xacro": [
        # two arms (7 joints, a hand with two fingers each) from a recursive xacro:loop macro
        Plant(
            "franka_description/robots/common/utils.xacro", "franka-limits", "J009", instances=14
        ),
        Plant(
            "franka_description/end_effectors/common/franka_hand.xacro",
            "franka_hand",
            "G001",
            ref="${arm_prefix}no_such_link",
            instances=2,
        ),
        Plant(
            "franka_description/end_effectors/common/utils.xacro",
            "ee-inertials",
            "I002",
            instances=6,
        ),
    ],
    "kortex_description/robots/gen3.xacro": [
        # the first joint's axis sits in an xacro:if of use_external_cable (false)
        Plant("kortex_description/arms/gen3/7dof/urdf/gen3_macro.xacro", "load_arm", "J007", nth=1),
        Plant("kortex_description/arms/gen3/7dof/urdf/gen3_macro.xacro", "load_arm", "I002"),
        Plant(
            "kortex_description/arms/gen3/7dof/urdf/gen3_macro.xacro",
            "load_arm",
            "X007",
            tag="visual",
        ),
    ],
    "robotiq_description/urdf/robotiq_2f_85_gripper.urdf.xacro": [
        Plant("robotiq_description/urdf/robotiq_2f_85_macro.urdf.xacro", "robotiq_gripper", "J009"),
        Plant("robotiq_description/urdf/robotiq_2f_85_macro.urdf.xacro", "robotiq_gripper", "I005"),
        Plant(
            "robotiq_description/urdf/robotiq_2f_85_macro.urdf.xacro",
            "robotiq_gripper",
            "G001",
            ref="${prefix}no_such_link",
        ),
    ],
    "ros2_control_demo_example_1/urdf/rrbot.urdf.xacro": [
        Plant(
            "ros2_control_demo_description/rrbot/urdf/rrbot_description.urdf.xacro",
            "rrbot",
            "J007",
            nth=1,
        ),
        Plant(
            "ros2_control_demo_description/rrbot/urdf/rrbot_description.urdf.xacro",
            "rrbot",
            "X007",
            tag="collision",
        ),
        Plant(
            "ros2_control_demo_description/rrbot/urdf/rrbot_description.urdf.xacro",
            "rrbot",
            "I002",
            nth=2,
        ),
    ],
    "pmb2_description/robots/pmb2.urdf.xacro": [
        Plant("pmb2_description/urdf/wheels/caster.urdf.xacro", "caster", "J007", instances=4),
        Plant("pmb2_description/urdf/wheels/caster.urdf.xacro", "caster", "I005", instances=4),
        Plant("pmb2_description/urdf/wheels/wheel.urdf.xacro", "wheel", "J009", instances=2),
        Plant(
            "pmb2_description/urdf/sensors/range.urdf.xacro",
            "range_sensor",
            "G001",
            ref="${name}_no_such_link",
            instances=3,
        ),
    ],
    "xarm_description/urdf/dual_xarm_device.urdf.xacro": [
        Plant(
            "xarm_description/urdf/xarm7/xarm7.urdf.xacro", "xarm7_urdf", "I002", nth=3, instances=2
        ),
        Plant(
            "xarm_description/urdf/xarm7/xarm7.urdf.xacro", "xarm7_urdf", "J009", nth=2, instances=2
        ),
        Plant(
            "xarm_description/urdf/xarm7/xarm7.urdf.xacro",
            "xarm7_urdf",
            "X007",
            tag="visual",
            instances=2,
        ),
    ],
    "abb_irb2400_support/urdf/irb2400.xacro": [
        Plant("abb_irb2400_support/urdf/irb2400_macro.xacro", "abb_irb2400", "J007"),
        Plant("abb_irb2400_support/urdf/irb2400_macro.xacro", "abb_irb2400", "J009", nth=1),
        Plant(
            "abb_irb2400_support/urdf/irb2400_macro.xacro",
            "abb_irb2400",
            "X007",
            tag="visual",
            nth=2,
        ),
        Plant(
            "abb_irb2400_support/urdf/irb2400_macro.xacro",
            "abb_irb2400",
            "G001",
            ref="${prefix}no_such_link",
        ),
    ],
    "fanuc_m10ia_support/urdf/m10ia.xacro": [
        Plant("fanuc_m10ia_support/urdf/m10ia_macro.xacro", "fanuc_m10ia", "J009", nth=3),
        Plant("fanuc_m10ia_support/urdf/m10ia_macro.xacro", "fanuc_m10ia", "X007", tag="collision"),
        Plant(
            "fanuc_m10ia_support/urdf/m10ia_macro.xacro",
            "fanuc_m10ia",
            "G001",
            ref="${prefix}no_such_link",
        ),
    ],
    "kuka_kr210_support/urdf/kr210l150.xacro": [
        Plant("kuka_kr210_support/urdf/kr210l150_macro.xacro", "kuka_kr210l150", "I002"),
        Plant("kuka_kr210_support/urdf/kr210l150_macro.xacro", "kuka_kr210l150", "I005", nth=1),
        Plant("kuka_kr210_support/urdf/kr210l150_macro.xacro", "kuka_kr210l150", "J007", nth=4),
    ],
    "motoman_sda10f_support/urdf/sda10f.xacro": [
        # one arm macro, called for the left and the right arm
        Plant(
            "motoman_sda10f_support/urdf/arm_macro.xacro", "motoman_arm", "J007", nth=2, instances=2
        ),
        Plant("motoman_sda10f_support/urdf/arm_macro.xacro", "motoman_arm", "J009", instances=2),
        Plant(
            "motoman_sda10f_support/urdf/arm_macro.xacro",
            "motoman_arm",
            "G001",
            ref="${prefix}no_such_link",
            instances=2,
        ),
        Plant(
            "motoman_sda10f_support/urdf/common_torso_macro.xacro", "torso", "X007", tag="visual"
        ),
    ],
    "pr2_description/robots/pr2.urdf.xacro": [
        Plant("pr2_description/urdf/base_v0/base.urdf.xacro", "pr2_wheel_v0", "I005", instances=8),
        Plant(
            "pr2_description/urdf/base_v0/base.urdf.xacro",
            "pr2_wheel_v0",
            "G001",
            ref="${parent}_${suffix}_no_such_link",
            instances=8,
        ),
        Plant(
            "pr2_description/urdf/base_v0/base.urdf.xacro", "pr2_caster_hub_v0", "I002", instances=4
        ),
        Plant(
            "pr2_description/urdf/gripper_v0/gripper.urdf.xacro",
            "pr2_finger_limits_v0",
            "J009",
            instances=8,
        ),
        Plant(
            "pr2_description/urdf/gripper_v0/gripper.urdf.xacro",
            "pr2_finger_v0",
            "X007",
            tag="visual",
            instances=2,
        ),
        Plant(
            "pr2_description/urdf/forearm_v0/forearm.urdf.xacro",
            "pr2_forearm_v0",
            "J007",
            instances=2,
        ),
    ],
    "husky_description/urdf/husky.urdf.xacro": [
        Plant("husky_description/urdf/wheel.urdf.xacro", "husky_wheel", "I002", instances=4),
        Plant("husky_description/urdf/wheel.urdf.xacro", "husky_wheel", "J007", instances=4),
        Plant(
            "husky_description/urdf/wheel.urdf.xacro",
            "husky_wheel",
            "G001",
            ref="${wheel_prefix}_no_such_link",
            instances=4,
        ),
        Plant(
            "husky_description/urdf/decorations.urdf.xacro", "husky_decorate", "X007", tag="visual"
        ),
    ],
    "a1_description/xacro/robot.xacro": [
        # four legs from one macro; the hip limits sit in an xacro:if of the mirror side
        Plant("a1_description/xacro/leg.xacro", "leg", "I005", instances=4),
        Plant("a1_description/xacro/leg.xacro", "leg", "J009", instances=2),
        Plant("a1_description/xacro/leg.xacro", "leg", "X007", tag="visual", nth=1, instances=4),
        Plant(
            "a1_description/xacro/transmission.xacro",
            "leg_transmission",
            "G001",
            ref="${name}_no_such_link",
            instances=4,
        ),
    ],
    "robotiq_2f_85_gripper_visualization/urdf/robotiq_arg2f_85_model.xacro": [
        # left and right finger macros
        Plant(
            "robotiq_2f_85_gripper_visualization/urdf/robotiq_arg2f_85_model_macro.xacro",
            "outer_knuckle",
            "X007",
            tag="visual",
            instances=2,
        ),
        Plant(
            "robotiq_2f_85_gripper_visualization/urdf/robotiq_arg2f_85_model_macro.xacro",
            "inner_knuckle_joint",
            "J007",
            instances=2,
        ),
        Plant(
            "robotiq_2f_85_gripper_visualization/urdf/robotiq_arg2f_85_model_macro.xacro",
            "inner_finger_joint",
            "J009",
            instances=2,
        ),
        Plant(
            "robotiq_2f_85_gripper_visualization/urdf/robotiq_arg2f.xacro",
            "robotiq_arg2f_base_link",
            "I002",
        ),
    ],
    "iiwa_description/urdf/iiwa14.urdf.xacro": [
        Plant("iiwa_description/urdf/iiwa14.xacro", "iiwa14", "I005", nth=2),
        Plant("iiwa_description/urdf/iiwa14.xacro", "iiwa14", "J009", nth=3),
        Plant(
            "iiwa_description/urdf/iiwa14.xacro", "iiwa14", "G001", ref="${robot_name}_no_such_link"
        ),
    ],
    "baxter_description/urdf/baxter.urdf.xacro": [
        # the electric gripper on both arms, two fingers each
        Plant(
            "rethink_ee_description/urdf/electric_gripper/rethink_electric_gripper.xacro",
            "rethink_electric_gripper",
            "J007",
            instances=2,
        ),
        Plant(
            "rethink_ee_description/urdf/electric_gripper/rethink_electric_gripper.xacro",
            "rethink_electric_gripper",
            "I002",
            instances=2,
        ),
        Plant(
            "rethink_ee_description/urdf/electric_gripper/fingers/extended_narrow.xacro",
            "finger_xacro",
            "I005",
            instances=4,
        ),
        Plant(
            "rethink_ee_description/urdf/electric_gripper/fingers/extended_narrow.xacro",
            "finger_xacro",
            "G001",
            ref="${gripper_side}_${finger_side}_no_such_link",
            instances=4,
        ),
    ],
}


# -- planting by text edits that keep every line in place ------------------------------


def tag_end(text: str, start: int) -> int:
    """Index past the ``>`` closing the tag that starts at ``start`` (quotes respected)."""
    quote = None
    for i in range(start + 1, len(text)):
        if quote:
            quote = None if text[i] == quote else quote
        elif text[i] in "\"'":
            quote = text[i]
        elif text[i] == ">":
            return i + 1
    raise ValueError(f"unterminated tag at {start}")


def macro_body(text: str, name: str) -> tuple[int, int]:
    """(start, end) offsets of the body of ``<xacro:macro name="name">``."""
    for m in re.finditer(r"<xacro:macro\s", text):
        body = tag_end(text, m.start())
        if re.search(rf"\sname\s*=\s*([\"']){re.escape(name)}\1", text[m.start() : body]):
            depth = 1
            for t in re.finditer(r"<(/?)xacro:macro(?=[\s>])", text[body:]):
                depth += -1 if t.group(1) else 1
                if depth == 0:
                    return body, body + t.start()
    raise AssertionError(f"no macro {name!r}")


def set_attr(tag: str, name: str, value: str) -> str:
    attr = re.compile(rf"(\s{re.escape(name)}\s*=\s*)([\"'])(.*?)\2", re.S)
    if attr.search(tag):
        return attr.sub(lambda m: f"{m.group(1)}{m.group(2)}{value}{m.group(2)}", tag, count=1)
    cut = len(tag) - (2 if tag.endswith("/>") else 1)
    return f'{tag[:cut].rstrip()} {name}="{value}"{tag[cut:]}'


POINTED_AT = {"I002": "value", "J007": "xyz", "J009": "lower"}


def plant(workspace: Path, p: Plant) -> int:
    """Plant ``p`` in the workspace copy; the 1-based line of the planted element."""
    path = workspace / p.file
    text = path.read_text(encoding="utf-8")
    start, end = macro_body(text, p.macro)
    if p.code == "G001":
        at, new = start, text[:start] + f'<gazebo reference="{p.ref}"/>' + text[start:]
    else:
        tag = p.tag or TAG[p.code]
        body = COMMENT_RE.sub(lambda m: " " * len(m.group()), text[start:end])
        found = [start + m.start() for m in re.finditer(rf"<{tag}(?=[\s/>])", body)]
        at = found[p.nth]
        close = tag_end(text, at)
        element = text[at:close]
        if p.code == "I002":
            element = set_attr(element, "value", "-1")
        elif p.code == "I005":
            triangle = {"ixx": "1", "iyy": "1", "izz": "5", "ixy": "0", "ixz": "0", "iyz": "0"}
            for attr, value in triangle.items():
                element = set_attr(element, attr, value)
        elif p.code == "J007":
            element = set_attr(element, "xyz", "0 0 0")
        elif p.code == "J009":
            element = set_attr(set_attr(element, "lower", "1"), "upper", "-1")
        elif p.code == "X007":
            element = "<" + MISSPELT[tag] + element[1 + len(tag) :]
            if not element.endswith("/>"):
                end_tag = text.index(f"</{tag}>", close)
                rest = text[close:end_tag] + f"</{MISSPELT[tag]}>" + text[end_tag + len(tag) + 3 :]
                path.write_text(text[:at] + element + rest, encoding="utf-8")
                return text.count("\n", 0, at) + 1
        new = text[:at] + element + text[close:]
        attribute = POINTED_AT.get(p.code)  # the finding points at the attribute at fault
        if attribute is not None:
            at += re.search(rf"\s{attribute}\s*=", element).start() + 1  # type: ignore[union-attr]
    assert new.count("\n") == text.count("\n")  # every line stays where it was
    path.write_text(new, encoding="utf-8")
    return text.count("\n", 0, at) + 1


# -- linting ----------------------------------------------------------------------------


def package_paths(workspace: Path) -> dict[str, Path]:
    return {
        etree.parse(str(xml)).findtext("name").strip(): xml.parent  # type: ignore[union-attr]
        for xml in workspace.glob("*/package.xml")
    }


def lint(workspace: Path, entry: str, select: tuple[str, ...]) -> linter.Result:
    """Lint ``entry`` as ``pkg/path/in/package.xacro``, with the workspace's packages."""
    settings = config.Settings(select=select, xacro_args=ENTRIES[entry])
    context = Context(package_paths=package_paths(workspace), environ={})
    return linter.lint_path(workspace / entry, entry, settings, context)


@functools.cache
def unplanted(entry: str) -> tuple[Finding, ...]:
    """The entry's findings of the planted kinds (and X010/X011) before any planting."""
    return tuple(lint(PACKAGES, entry, (*PLANTED, "X010", "X011")).findings)


def key(f: Finding) -> tuple[str, str, int, str]:
    return (f.code, f.path, f.line, f.message)


def merged(message: str) -> int:
    """How many instances of a macro line a finding stands for, from its message."""
    named = re.search(r" \(for (?:\w+ )?(.*?)(?: and (\d+) more)?\)$", message)
    if named:
        return len(named.group(1).split(", ")) + int(named.group(2) or 0)
    counted = re.search(r" \((\d+) instances of this macro line\)$", message)
    return int(counted.group(1)) if counted else 1


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """A private copy of the whole workspace (packages include files of each other)."""
    copy = tmp_path / "src"
    shutil.copytree(PACKAGES, copy)
    return copy


# -- the tests ----------------------------------------------------------------------------


def test_every_entry_has_plants_and_every_kind_is_planted_several_times() -> None:
    assert set(PLANTS) == set(ENTRIES)
    kinds = Counter(p.code for plants in PLANTS.values() for p in plants)
    assert set(kinds) == set(PLANTED) and min(kinds.values()) >= 3, kinds
    for entry, plants in PLANTS.items():
        assert all(p.file != entry for p in plants)


@pytest.mark.parametrize("entry", sorted(ENTRIES))
def test_entry_expands(entry: str) -> None:
    result = lint(PACKAGES, entry, ("X010", "X011"))
    assert result.findings == [], result.findings
    doc = result.document
    assert doc is not None and doc.ok and not doc.library and doc.links


@pytest.mark.parametrize("entry", sorted(PLANTS))
def test_planted_defects_are_reported_once_where_written(workspace: Path, entry: str) -> None:
    package = entry.split("/")[0]
    plants = PLANTS[entry]
    lines = {p: plant(workspace, p) for p in plants}
    codes = tuple(sorted({p.code for p in plants}))
    after = lint(workspace, entry, codes).findings

    for p, line in lines.items():
        hits = [f for f in after if (f.code, f.path, f.line) == (p.code, p.file, line)]
        assert len(hits) == 1, (p, line, [str((f.code, f.path, f.line, f.message)) for f in after])
        found = hits[0]
        assert "expanded document" not in found.message
        assert found.trace, found
        assert found.trace[0].macro == p.macro  # innermost call: the macro planted in
        outermost = found.trace[-1]
        assert outermost.path.split("/")[0] == package, found.trace  # called from the package
        assert (workspace / outermost.path).is_file()
        assert merged(found.message) == p.instances, found.message

    # and nothing else changed: the findings are the unplanted ones plus one per defect
    before = Counter(key(f) for f in unplanted(entry) if f.code in codes)
    new = Counter(key(f) for f in after) - before
    assert sorted((c, path, line) for c, path, line, _ in new) == sorted(
        (p.code, p.file, line) for p, line in lines.items()
    )
    assert not before - Counter(key(f) for f in after)


def test_fixture_is_small_and_holds_no_meshes() -> None:
    files = [p for p in PACKAGES.rglob("*") if p.is_file()]
    assert sum(p.stat().st_size for p in files) < 1_500_000
    suffixes = {p.suffix for p in files if p.parent != PACKAGES and "LICENSES" not in p.parts}
    assert suffixes <= {".xacro", ".yaml", ".xml", ".urdf"}, suffixes
    readme = (PACKAGES / "README.md").read_text(encoding="utf-8")
    for xml in PACKAGES.glob("*/package.xml"):
        assert f"`{xml.parent.name}`" in readme
