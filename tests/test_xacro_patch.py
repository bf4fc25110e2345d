"""Incremental re-expansion (urdflint.sources.xacro.patch): a value typed into a plain element.

The decisive check: for real edits of the real packages of fixtures/packages/, the patched
document equals a full expansion of the edited files (given as the editor's buffers, as the
language server does): the same expanded text, the same origin of every element and
attribute, and the same findings. Edits the patch cannot prove give ``None``.
"""

from __future__ import annotations

import dataclasses
import json
import re
import textwrap
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest
from lxml import etree

from tests.conftest import FIXTURES
from urdflint.engine import config, linter
from urdflint.engine.context import Context
from urdflint.model.document import Document
from urdflint.model.positions import TAG_END_RE
from urdflint.sources.xacro import patch
from urdflint.sources.xacro.sourcemap import SourceMap, nodes

pytest.importorskip("xacro")

PACKAGES = FIXTURES / "packages"
ENTRIES: dict[str, dict[str, str]] = {
    item["entry"]: item["args"]
    for item in json.loads((PACKAGES / "entries.json").read_text(encoding="utf-8"))
}
# the plain elements and numeric attributes edited
EDITED = {
    b"mass": (b"value",),
    b"inertia": (b"ixx", b"ixy", b"ixz", b"iyy", b"iyz", b"izz"),
    b"origin": (b"xyz", b"rpy"),
    b"limit": (b"lower", b"upper", b"effort", b"velocity"),
    b"axis": (b"xyz",),
}
START_RE = re.compile(rb"<(" + b"|".join(EDITED) + rb")[\s/>]")
VALUE_RE = re.compile(rb"""\s([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")
BLANK_RE = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>", re.S)
PER_FILE = 4  # edits per file read, spread over the file
SINGLE = 1  # edits per entry compared one by one with a full expansion


def mutate(value: bytes, n: int) -> bytes:
    """The ``n``-th kind of edit a user makes to a number (or a vector of numbers)."""
    kind = n % 5
    if kind == 0:
        return value[1:] if value.startswith(b"-") else b"-" + value
    if kind == 1:
        return value + b"25"
    if kind == 2:
        return b"0 0 0" if len(value.split()) == 3 else b"0"
    if kind == 3:
        return b"1.5."  # not a number
    return value[: len(value) // 2]  # half deleted (maybe empty)


@dataclass(frozen=True)
class Edit:
    """``old`` → ``new`` at ``begin:end`` of ``path`` (a value between quotes)."""

    path: str
    begin: int
    end: int
    new: bytes

    def applied(self, data: bytes, shift: int = 0) -> bytes:
        return data[: self.begin + shift] + self.new + data[self.end + shift :]


@cache
def package_paths() -> dict[str, Path]:
    return {
        etree.parse(str(xml)).findtext("name").strip(): xml.parent.resolve()  # type: ignore[union-attr]
        for xml in PACKAGES.glob("*/package.xml")
    }


def settings_for(entry: str) -> config.Settings:
    return config.Settings(xacro_args=ENTRIES[entry])


def context(overlay: dict[str, bytes] | None = None) -> Context:
    return Context(package_paths=package_paths(), environ={}, overlay=overlay or {})


def full(entry: str, overlay: dict[str, bytes] | None = None) -> linter.Result:
    path = (PACKAGES / entry).resolve()
    return linter.lint_path(path, entry, settings_for(entry), context(overlay))


@cache
def expanded(entry: str) -> Document:
    """The entry's expansion before any edit (shared: never linted, never changed)."""
    return linter.load((PACKAGES / entry).resolve(), entry, settings_for(entry), context())


def candidates(data: bytes) -> list[tuple[int, int, bytes]]:
    """(begin, end, value) of every literal, ``$``-free value of the edited attributes."""
    blanked = BLANK_RE.sub(lambda m: b" " * len(m.group()), data)
    found = []
    for start in START_RE.finditer(blanked):
        end = TAG_END_RE.match(blanked, start.start() + 1)
        if end is None:
            continue
        wanted = EDITED[start.group(1)]
        for attr in VALUE_RE.finditer(blanked, start.start() + 1, end.end()):
            group = 2 if attr.group(2) is not None else 3
            value = attr.group(group)
            if attr.group(1) in wanted and b"$" not in value and b"\n" not in value:
                found.append((*attr.span(group), value))
    return found


def edits_of(entry: str) -> list[Edit]:
    """Up to PER_FILE edits in every file the entry reads (entry and macro files), in file
    order, each with the next kind of mutation."""
    sources = expanded(entry).origin
    assert isinstance(sources, SourceMap)
    edits: list[Edit] = []
    for file in sorted(sources.files, key=lambda f: f.path):
        found = candidates(file.data)
        step = max(1, -(-len(found) // PER_FILE))
        for begin, end, value in found[::step]:
            new = mutate(value, len(edits))
            if new != value:
                edits.append(Edit(file.path, begin, end, new))
    return edits


def attributes(el: etree._Element) -> list[str | None]:
    return [None, *(str(k) for k in el.attrib)] if isinstance(el.tag, str) else [None]


def assert_same(patched: Document, result: linter.Result, settings: config.Settings) -> None:
    """``patched`` is the document of the full expansion ``result``: same text, origins,
    findings (including their fixes: edits at exact source offsets)."""
    whole = result.document
    assert whole is not None and whole.root is not None and patched.root is not None
    assert patched.source == whole.source
    assert patched.library == whole.library
    assert patched.origin is not None and whole.origin is not None
    for a, b in zip(nodes(patched.root), nodes(whole.root), strict=True):
        for name in attributes(b):
            assert patched.origin(a, name) == whole.origin(b, name), (b, name)
    mine = [f.to_dict() for f in linter.lint_document(patched, settings).findings]
    assert mine == [f.to_dict() for f in result.findings]


@pytest.mark.slow  # real packages end to end
@pytest.mark.parametrize("entry", sorted(ENTRIES))
def test_value_edits_in_real_packages_give_what_a_full_expansion_gives(entry: str) -> None:
    edits = edits_of(entry)
    assert edits, "no literal value to edit"
    settings = settings_for(entry)
    base = expanded(entry)
    texts = {f.path: f.data for f in base.origin.files}  # type: ignore[union-attr]

    # one by one: the first SINGLE edits of the files with the most copies of their element
    def copies(edit: Edit) -> int:
        index = next(i for i, f in enumerate(base.origin.files) if f.path == edit.path)  # type: ignore[union-attr]
        tag = texts[edit.path].rfind(b"<", 0, edit.begin)
        return len(base.origin.written_at(base.root, index, tag))  # type: ignore[union-attr,arg-type]

    for edit in sorted(edits, key=lambda e: -copies(e))[:SINGLE]:
        new = edit.applied(texts[edit.path])
        overlay = {edit.path: new}
        patched = patch.apply(base, edit.path, texts[edit.path], new, context(overlay))
        assert patched is not None, edit
        assert_same(patched, full(entry, overlay), settings)

    # all of them, one after the other (as typed): each patches the previous patched document
    current, shift, doc = dict(texts), dict.fromkeys(texts, 0), base
    for edit in edits:
        new = edit.applied(current[edit.path], shift[edit.path])
        overlay = {**{p: t for p, t in current.items() if t != texts[p]}, edit.path: new}
        step = patch.apply(doc, edit.path, current[edit.path], new, context(overlay))
        assert step is not None, edit
        doc, current[edit.path] = step, new
        shift[edit.path] += len(edit.new) - (edit.end - edit.begin)
    overlay = {p: t for p, t in current.items() if t != texts[p]}
    assert_same(doc, full(entry, overlay), settings)


# -- a small package: the cases that patch and those that must not ------------------------

LEG = """
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="scale" value="0.5"/>
  <xacro:macro name="leg" params="side *origin reflect:=1">
    <link name="${side}_leg">
      <inertial>
        <mass value="1.5"/> <origin xyz="0 0 ${reflect*0.1}" rpy="0 0 0"/>
        <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
      </inertial>
      <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    </link>
    <joint name="${side}_joint" type="revolute">
      <parent link="base"/><child link="${side}_leg"/>
      <xacro:insert_block name="origin"/>
      <axis xyz="0 0 1"/> <limit lower="-1" upper="1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <!-- <mass value="3"/> -->
  <xacro:macro name="unused"><link name="unused"><inertial><mass value="7"/></inertial></link>
  </xacro:macro>
</robot>
"""

ROBOT = """
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="leg.xacro"/>
  <link name="base">
    <inertial><mass value="${scale*4}"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <visual><material name='plain'/><geometry><box size="1 1 1"/></geometry></visual>
  </link>
  <xacro:leg side="left"><origin xyz="0 0.1 0" rpy="0 0 0"/></xacro:leg>
  <xacro:leg side="right" reflect="-1"><origin xyz="0 -0.1 0" rpy="0 0 0"/></xacro:leg>
  <link name="named"><xacro:attribute name="name" value="renamed"/></link>
</robot>
"""


@pytest.fixture
def small(tmp_path: Path) -> tuple[Path, Path]:
    robot, leg = tmp_path / "robot.urdf.xacro", tmp_path / "leg.xacro"
    robot.write_text(textwrap.dedent(ROBOT).lstrip(), encoding="utf-8")
    leg.write_text(textwrap.dedent(LEG).lstrip(), encoding="utf-8")
    return robot, leg


def expand(robot: Path, overlay: dict[str, bytes] | None = None) -> linter.Result:
    return linter.lint_path(robot, str(robot), config.Settings(), Context(overlay=overlay or {}))


def replaced(data: bytes, needle: str, new: str, nth: int = 0) -> bytes:
    at = -1
    for _ in range(nth + 1):
        at = data.index(needle.encode(), at + 1)
    return data[:at] + new.encode() + data[at + len(needle) :]


def attempt(robot: Path, path: Path, needle: str, new: str, nth: int = 0) -> Document | None:
    doc = expand(robot).document
    assert doc is not None and doc.ok
    old = path.read_bytes()
    edited = replaced(old, needle, new, nth)
    patched = patch.apply(doc, str(path), old, edited)
    if patched is not None:
        assert_same(patched, expand(robot, {str(path): edited}), config.Settings())
    return patched


@pytest.mark.parametrize(
    ("where", "needle", "new"),
    [
        ("leg", '<mass value="1.5"', '<mass value="-1.5"'),  # a macro called twice
        ("leg", 'ixx="0.1"', 'ixx="0.1e-3"'),
        ("leg", 'rpy="0 0 0"/>\n', 'rpy="0 0 0.0001"/>\n'),  # after an expression in the tag
        ("leg", 'lower="-1"', 'lower=""'),  # emptied
        ("leg", 'velocity="1"', 'velocity="1 &amp; &lt;2&gt; &quot;"'),  # escaped as minidom
        ("leg", '<mass value="7"', '<mass value="8"'),  # in a macro never called: no copy
        ("robot", 'xyz="0 0.1 0"', 'xyz="0 0.12345 0"'),  # a block parameter, inserted
        ("robot", "name='plain'", "name='a \"b\" &amp; c'"),  # single quotes
        ("robot", 'ixx="1" ixy', 'ixx="1.5" ixy'),  # attributes after it on the same line
    ],
)
def test_plain_values_patch(small: tuple[Path, Path], where: str, needle: str, new: str) -> None:
    robot, leg = small
    path = robot if where == "robot" else leg
    assert attempt(robot, path, needle, new) is not None


def test_both_copies_of_a_macro_element_change(small: tuple[Path, Path]) -> None:
    robot, leg = small
    patched = attempt(robot, leg, '<mass value="1.5"', '<mass value="-2.5"')
    assert patched is not None
    assert [el.get("value") for el in patched.robot.iter("mass")][1:] == ["-2.5", "-2.5"]


@pytest.mark.parametrize(
    ("where", "needle", "new"),
    [
        ("leg", '"0.5"', '"0.25"'),  # a property value
        ("leg", "${reflect*0.1}", "${reflect*0.2}"),  # inside an expression
        ("leg", 'ixx="0.1"', 'ixx="${scale}"'),  # becomes an expression
        ("leg", 'ixx="0.1"', 'ixx="$"'),
        ("leg", 'reflect:=1"', 'reflect:=2"'),  # a macro parameter's default
        ("leg", '1"/> <limit lower="-1"', '2"/> <limit lower="-2"'),  # across two tags
        ("leg", 'ixx="0.1" ixy="0"', 'ixx="0.2" ixy="1"'),  # across two values
        ("leg", 'lower="-1"', 'lower="-1\n"'),  # a line break
        ("leg", 'lower="-1"', 'lower="-1&#10;"'),  # a line break, as a reference
        ("leg", 'lower="-1"', 'lower="-"1"'),  # not well-formed
        ("leg", 'lower="-1"', 'lower="<1"'),  # not well-formed
        ("leg", 'lower="-1"', 'lower="&nbsp;1"'),  # an undefined entity
        ("leg", '<mass value="3"/>', '<mass value="4"/>'),  # in a comment
        ("leg", '<mass value="1.5"', '<masss value="1.5"'),  # the tag name
        ("leg", 'ixx="0.1"', 'ixy="0.1"'),  # an attribute name
        ("robot", 'side="left"', 'side="lefty"'),  # a macro call's parameter
        ("robot", '"named"', '"other"'),  # the element has a xacro:attribute
        ("robot", 'filename="leg.xacro"', 'filename="leg2.xacro"'),
    ],
)
def test_edits_that_are_not_plain_values_expand_in_full(
    small: tuple[Path, Path], where: str, needle: str, new: str
) -> None:
    robot, leg = small
    path = robot if where == "robot" else leg
    assert attempt(robot, path, needle, new) is None


def test_a_stale_or_unread_file_expands_in_full(small: tuple[Path, Path], tmp_path: Path) -> None:
    robot, leg = small
    doc = expand(robot).document
    assert doc is not None
    old = leg.read_bytes()
    new = replaced(old, '"1.5"', '"2.5"')
    stale = replaced(old, '"0.1"', '"0.3"')
    assert patch.apply(doc, str(leg), stale, replaced(stale, '"1.5"', '"2.5"')) is None
    assert patch.apply(doc, str(tmp_path / "other.xacro"), old, new) is None
    assert patch.apply(doc, str(leg), old, old) is None
    urdf = Document("plain.urdf", b"<robot name='r'><link name='a'/></robot>")
    assert patch.apply(urdf, str(leg), old, new) is None


def test_the_default_context_reads_the_edited_buffer(small: tuple[Path, Path]) -> None:
    robot, leg = small
    doc = expand(robot).document
    assert doc is not None
    old = leg.read_bytes()
    new = replaced(old, '"1.5"', '"2.5"')
    patched = patch.apply(doc, str(leg), old, new)
    assert patched is not None
    assert patched.context.overlay == {str(leg): new}
    assert dataclasses.replace(patched.context, overlay={}) == dataclasses.replace(
        doc.context, overlay={}
    )
