"""Every corpus robot Pinocchio can build: urdflint's total mass is the sum of the URDF's
masses, and its COM is the one an independent free-flyer Pinocchio build computes."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.conftest import corpus_models, needs_corpus
from urdflint.engine.physics import urdf_masses
from urdflint.model.document import Document

pytestmark = needs_corpus
pin = pytest.importorskip("pinocchio")

# Robots urdflint does not hand to Pinocchio, and the static finding that stops it.
NOT_BUILT = {
    # effort="-1" velocity="-1" on every joint: Pinocchio refuses ("min_effort > max_effort").
    "eve_r3": "J010",
}


def independent(xml: str) -> tuple[float, tuple[float, ...]]:
    model = pin.buildModelFromXML(xml, pin.JointModelFreeFlyer())
    data = model.createData()
    com = pin.centerOfMass(model, data, pin.neutral(model))  # free-flyer at identity
    return pin.computeTotalMass(model), tuple(float(c) for c in com)


@pytest.mark.parametrize("path", corpus_models(), ids=lambda p: p.parent.name)
def test_mass_and_com_match_an_independent_free_flyer_build(path: Path) -> None:
    doc = Document(str(path), path.read_bytes())
    result = doc.physics
    robot = path.parent.name
    if robot in NOT_BUILT:
        assert not result.built and result.blocker is not None
        assert result.blocker.code == NOT_BUILT[robot]
        return
    assert result.built, result.reason
    expected = sum(urdf_masses(doc).values())
    assert math.isclose(result.mass, expected, rel_tol=1e-9, abs_tol=1e-12)
    total, com = independent(path.read_text(encoding="utf-8"))
    assert math.isclose(result.mass, total, rel_tol=1e-9, abs_tol=1e-12)
    if total > 0:
        assert result.com is not None
        assert all(
            math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)
            for a, b in zip(result.com, com, strict=True)
        )
    else:
        assert result.com is None
