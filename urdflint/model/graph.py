"""The kinematic graph of a robot: which joint connects which links."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from urdflint.model.document import Joint, Link


@dataclass
class Graph:
    """Links and the joints between them, built only from resolvable references.

    ``parent_joints[link]`` lists every joint whose child is ``link`` (more than
    one is a loop); ``child_joints[link]`` every joint whose parent is ``link``.
    ``roots`` are link names with no parent joint, in document order; ``root``
    is the one that carries the largest subtree (the robot's base).
    """

    links: dict[str, Link]
    parent_joints: dict[str, list[Joint]] = field(default_factory=dict)
    child_joints: dict[str, list[Joint]] = field(default_factory=dict)

    @classmethod
    def build(cls, links: dict[str, Link], joints: list[Joint]) -> Graph:
        graph = cls(links)
        for name in links:
            graph.parent_joints[name] = []
            graph.child_joints[name] = []
        for joint in joints:
            if joint.parent in links and joint.child in links:
                graph.parent_joints[joint.child].append(joint)  # type: ignore[index]
                graph.child_joints[joint.parent].append(joint)  # type: ignore[index]
        return graph

    @property
    def roots(self) -> list[str]:
        return [name for name, parents in self.parent_joints.items() if not parents]

    @property
    def root(self) -> str | None:
        roots = self.roots
        if not roots:
            return None
        return max(roots, key=lambda name: (len(self.subtree(name)), -roots.index(name)))

    def parent_joint(self, link: str) -> Joint | None:
        """The (first) joint whose child is ``link``."""
        parents = self.parent_joints.get(link) or []
        return parents[0] if parents else None

    def parent_link(self, link: str) -> str | None:
        joint = self.parent_joint(link)
        return joint.parent if joint is not None else None

    def children(self, link: str) -> list[str]:
        return [j.child for j in self.child_joints.get(link, []) if j.child is not None]

    def subtree(self, link: str) -> list[str]:
        """``link`` and every link below it (each once, loops tolerated)."""
        seen: list[str] = []
        stack = [link]
        visited: set[str] = set()
        while stack:
            name = stack.pop()
            if name in visited:
                continue
            visited.add(name)
            seen.append(name)
            stack.extend(reversed(self.children(name)))
        return seen

    def ancestors(self, link: str) -> Iterator[str]:
        """Parent, grandparent, ... up to a root (stops on a loop)."""
        visited = {link}
        current = self.parent_link(link)
        while current is not None and current not in visited:
            yield current
            visited.add(current)
            current = self.parent_link(current)

    def cycles(self) -> list[list[Joint]]:
        """Directed cycles of joints (parent -> child), each reported once."""
        state: dict[str, int] = {}
        found: list[list[Joint]] = []
        for start in self.links:
            if state.get(start):
                continue
            path: list[Joint] = []
            stack: list[tuple[str, Iterator[Joint]]] = [(start, iter(self.child_joints[start]))]
            state[start] = 1
            while stack:
                node, edges = stack[-1]
                joint = next(edges, None)
                if joint is None:
                    state[node] = 2
                    stack.pop()
                    if path:
                        path.pop()
                    continue
                child = joint.child or ""
                if state.get(child) == 1:
                    names = [n for n, _ in stack]
                    first = names.index(child)
                    found.append([*path[first:], joint])
                elif not state.get(child):
                    state[child] = 1
                    path.append(joint)
                    stack.append((child, iter(self.child_joints[child])))
        return found
