"""What the rules share to stay fast (issue 14): the per-element tables of urdflint.model.memo,
cached link parts, the bounded edit distance, cached principal moments and C013's vectorised
broad phase, each checked against the plain computation it replaces."""

from __future__ import annotations

import itertools
import random

import numpy as np
import pytest
from lxml import etree

from urdflint.engine import linter
from urdflint.model import memo
from urdflint.model.document import Document, children
from urdflint.model.inertia import eigenvalues, matrix, principal_moments
from urdflint.model.spelling import bounded_distance, distance
from urdflint.sources import self_collision as S
from urdflint.sources.self_collision_depth import Placed

ROBOT = b"""<robot name="r">
  <link name="a"><!-- note --><visual/><inertial/><collision/><visual/><inertial/></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="1 0 0"/>
    <origin xyz="2 0 0"/></joint>
  <link name="b"/>
</robot>"""


def test_children_is_a_new_list_each_time() -> None:
    robot = etree.fromstring(ROBOT)
    first = children(robot, "link")
    first.append(robot)  # a caller's list is its own
    assert [el.get("name") for el in children(robot, "link")] == ["a", "b"]


def test_link_parts_and_joint_children_are_what_lxml_finds() -> None:
    doc = Document("r.urdf", ROBOT)
    link = doc.links[0]
    assert link.visuals == link.element.findall("visual")
    assert link.collisions == link.element.findall("collision")
    assert link.inertial is link.element.find("inertial")
    joint = doc.joints[0]
    assert joint.find("origin") is joint.element.find("origin")
    assert joint.find("origin").get("xyz") == "1 0 0"  # type: ignore[union-attr]
    assert joint.find("limit") is None
    assert (joint.parent, joint.child) == ("a", "b")


def test_tables_are_dropped_after_a_lint_and_bounded_between() -> None:
    memo.forget()
    trees = [etree.fromstring(ROBOT) for _ in range(memo.MAX_TREES + 2)]
    for tree in trees:
        memo.table(tree, "t")[tree] = 1
    assert len(memo._TREES) == memo.MAX_TREES  # the oldest trees went
    assert memo.table(trees[-1], "t") == {trees[-1]: 1}
    assert memo.table(trees[0], "t") == {}  # evicted: computed again, never stale
    linter.lint_bytes(ROBOT, "r.urdf")
    assert not memo._TREES


@pytest.mark.parametrize("limit", [0, 1, 2, 3])
def test_bounded_distance_is_exact_within_its_limit(limit: int) -> None:
    rng = random.Random(7)
    words = ["".join(rng.choice("ab_c") for _ in range(rng.randint(0, 7))) for _ in range(150)]
    for a, b in itertools.product(words[:40], words):
        d, bounded = distance(a, b), bounded_distance(a, b, limit)
        assert bounded == d if d <= limit else bounded > limit, (a, b)


def test_principal_moments_keep_the_sign_of_a_zero() -> None:
    plus, minus = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (-0.0, -0.0, -0.0, 0.0, 0.0, 0.0)
    assert principal_moments(plus) == eigenvalues(matrix(plus))
    got = principal_moments(minus)
    assert [str(v) for v in got] == [str(v) for v in eigenvalues(matrix(minus))]


def _brute(shapes: list[Placed], margin: float) -> list[tuple[int, int]]:
    boxes = [s.world_box() for s in shapes]
    return [
        (i, j)
        for i, j in itertools.combinations(range(len(shapes)), 2)
        if (np.minimum(boxes[i][1] - boxes[j][0], boxes[j][1] - boxes[i][0]) >= margin).all()
    ]


@pytest.mark.parametrize("chunk", [1, 5, 1 << 20])
def test_broad_phase_finds_every_overlapping_pair(
    chunk: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(S, "CHUNK", chunk)
    rng = np.random.default_rng(3)
    for _ in range(30):
        shapes = [
            Placed("l", None, "box", np.eye(3), np.round(rng.random(3), 1), rng.random(3) * 0.2)
            for _ in range(int(rng.integers(0, 60)))
        ]
        for margin in (1e-9, 0.01, 0.1):
            assert S.candidates(shapes, margin) == _brute(shapes, margin)
