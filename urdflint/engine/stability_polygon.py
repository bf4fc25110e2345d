"""The support polygon in the ground plane: the convex hull of the contact points, whether it
is a polygon, a line or a point, and the signed distance of a point to its edge (pure
Python: a few dozen points)."""

from __future__ import annotations

import math

Point2 = tuple[float, float]
NARROW = 0.001  # m: a support narrower than this is a line; all points this close, a point
WORDS = ("+x (front)", "+x+y (front left)", "+y (left)", "-x+y (back left)", "-x (back)",
         "-x-y (back right)", "-y (right)", "+x-y (front right)")  # fmt: skip


def hull(points: list[Point2]) -> list[Point2]:
    """The convex hull, counter-clockwise (Andrew's monotone chain); collinear points dropped."""
    unique = sorted(set(points))
    if len(unique) < 3:
        return unique

    def cross(o: Point2, a: Point2, b: Point2) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Point2] = []
    for p in unique:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-15:
            lower.pop()
        lower.append(p)
    upper: list[Point2] = []
    for p in reversed(unique):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-15:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def shape_kind(polygon: list[Point2]) -> str:
    """``polygon``, ``line`` (narrower than :data:`NARROW`) or ``point``."""
    if not polygon:
        return "none"
    span = max(math.dist(a, b) for a in polygon for b in polygon)
    if span < NARROW:
        return "point"
    if len(polygon) < 3:
        return "line"
    width = min(
        max(_line_distance(p, a, b) for p in polygon)
        for a, b in zip(polygon, polygon[1:] + polygon[:1], strict=True)
    )
    return "line" if width < NARROW else "polygon"


def _line_distance(p: Point2, a: Point2, b: Point2) -> float:
    length = math.dist(a, b)
    if length == 0:
        return math.dist(p, a)
    return abs((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / length


def _nearest_on_segment(p: Point2, a: Point2, b: Point2) -> Point2:
    dx, dy = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2
    t = min(1.0, max(0.0, t))
    return (a[0] + t * dx, a[1] + t * dy)


def margin(polygon: list[Point2], p: Point2) -> tuple[float, Point2]:
    """The signed distance from ``p`` to the edge of the counter-clockwise ``polygon``
    (positive inside, negative outside), and the nearest point of the edge."""
    edges = list(zip(polygon, polygon[1:] + polygon[:1], strict=True))
    nearest = min((_nearest_on_segment(p, a, b) for a, b in edges), key=lambda n: math.dist(p, n))
    distance = math.dist(p, nearest)
    inside = all(
        (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) >= 0 for a, b in edges
    )
    return (distance if inside else -distance), nearest


def direction(v: Point2) -> str:
    """``+x (front)``, ``-x+y (back left)``... for a horizontal vector (REP 103 axes)."""
    if v == (0.0, 0.0):
        return "nowhere"
    sector = round(math.degrees(math.atan2(v[1], v[0])) / 45.0) % 8
    return WORDS[sector]
