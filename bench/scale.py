#!/usr/bin/env python3
"""How ``urdflint check`` grows with the robot: synthetic chains and trees of 1k to 8k links.

    .venv/bin/python bench/scale.py [--sizes 1000,2000,4000,8000]

Each model has, per link, an inertial, a coloured box visual, a box collision, a revolute
joint and a ``<gazebo reference>`` block; links sit on a grid (no two collisions overlap), a
chain hangs each link on the previous one, a tree on link ``(i - 1) // 2``. The time of a
whole ``urdflint check --isolated`` (every rule, the default target) is printed beside the
ratio to the previous size (goal: at most 2.2 per doubling) and beside the floor measured in
the same run: ``lxml.etree.parse`` of the same file in this process.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
URDFLINT = [sys.executable, "-m", "urdflint"]
SPACING = 0.3  # m between grid points; the boxes are 0.1 m


def position(i: int) -> tuple[float, float, float]:
    return ((i % 50) * SPACING, (i // 50 % 50) * SPACING, (i // 2500) * SPACING)


def model(n: int, tree: bool) -> str:
    lines = ['<?xml version="1.0"?>', '<robot name="synthetic">']
    for i in range(n):
        lines += [
            f'  <link name="l{i}">',
            '    <inertial><mass value="1"/><inertia ixx="0.00167" ixy="0" ixz="0" '
            'iyy="0.00167" iyz="0" izz="0.00167"/></inertial>',
            '    <visual><geometry><box size="0.1 0.1 0.1"/></geometry>'
            '<material name="red"><color rgba="1 0 0 1"/></material></visual>',
            '    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>',
            "  </link>",
        ]
        if i:
            parent = (i - 1) // 2 if tree else i - 1
            offset = [c - p for c, p in zip(position(i), position(parent), strict=True)]
            lines += [
                f'  <joint name="j{i}" type="revolute">',
                f'    <parent link="l{parent}"/><child link="l{i}"/>',
                f'    <origin xyz="{offset[0]:.3f} {offset[1]:.3f} {offset[2]:.3f}"/>',
                '    <axis xyz="0 0 1"/>',
                '    <limit lower="-1" upper="1" effort="10" velocity="1"/>',
                "  </joint>",
                f'  <gazebo reference="l{i}"><mu1>0.5</mu1></gazebo>',
            ]
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def timed(argv: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(argv, cwd=ROOT, capture_output=True, check=False)
    return time.perf_counter() - start


def parse_floor(path: Path) -> float:
    from lxml import etree

    start = time.perf_counter()
    etree.parse(str(path))
    return time.perf_counter() - start


def main() -> int:
    sizes = [1000, 2000, 4000, 8000]
    if "--sizes" in sys.argv:
        sizes = [int(v) for v in sys.argv[sys.argv.index("--sizes") + 1].split(",")]
    print("| model | links | urdflint check (s) | × previous | lxml parse (s) | × parse |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for kind in ("chain", "tree"):
            previous = None
            for n in sizes:
                path = Path(tmp) / f"{kind}{n}.urdf"
                path.write_text(model(n, kind == "tree"))
                took = timed([*URDFLINT, "check", "--isolated", "--exit-zero", str(path)])
                ratio = f"{took / previous:.2f}" if previous else "–"
                floor = parse_floor(path)
                print(f"| {kind} | {n} | {took:.2f} | {ratio} | {floor:.3f} | {took / floor:.0f} |")
                previous = took
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
