"""The targets a model is meant for, when nobody said: inferred from the model and its package.

A target changes severities and messages (Gazebo Classic ignores URDF colours, Gazebo Sim
reads them; MuJoCo refuses a mesh Gazebo loads), so a default that fits nobody makes
findings wrong for most users. When neither ``--target``, the configuration nor the
file's folder configuration names targets, each rule of thumb below that matches is
evidence for a target (:func:`infer`):

- a Gazebo plugin (``<plugin filename>`` in a ``<gazebo>`` block, or the hardware plugin of
  a ``<ros2_control>`` block): ``libgazebo_ros_*``, ``gazebo_ros2_control`` and
  ``gazebo_ros_control`` are Gazebo Classic's; ``gz-sim-*``, ``ignition-gazebo-*``,
  ``gz_ros2_control``, ``ign_ros2_control`` (and ``gz::sim``/``ignition::gazebo`` system
  names) are Gazebo Sim's; ``mujoco_ros2_control`` is MuJoCo's;
- the dependencies in the ``package.xml`` of the file's package: ``gazebo_ros``,
  ``gazebo_plugins``, ``gazebo_ros_control``, ``gazebo_ros2_control`` (Classic);
  ``ros_gz_sim``, ``ros_gz``, ``ros_gz_bridge``, ``gz_ros2_control``, ``ros_ign_gazebo``,
  ``ign_ros2_control`` (Sim); ``mujoco_ros2_control``, ``mujoco_ros`` (MuJoCo);
  ``isaac_ros_*`` (Isaac Sim); ``drake``, ``drake_ros`` (Drake);
- a ``<mujoco>`` block (MuJoCo's compiler options) and ``drake:`` elements (Drake);
- PyBullet's ``<contact>`` block in a link (``<lateral_friction>``, ``<rolling_friction>``...);
- a ROS package (a ``package.xml``) or a MoveIt SRDF: ROS (robot_state_publisher, KDL and
  MoveIt read the file).

With no evidence for a simulator, the targets are Gazebo Sim and ROS: Gazebo Classic
reached its end of life in January 2025, and ROS 2 Jazzy and later ship Gazebo Sim.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from urdflint.model.targets import LABELS, ordered

if TYPE_CHECKING:
    from urdflint.model.document import Document

ASSUMED: tuple[str, ...] = ("gz-sim", "ros")  # no evidence for any simulator

CLASSIC_PLUGIN = r"gazebo_ros2?_control|(^|/)(lib)?gazebo_ros_"
SIM_PLUGIN = r"(^|/)(lib)?(gz-sim|ignition-gazebo)|g[zn]_ros2_control|gz::sim|ignition::gazebo"
PLUGINS: tuple[tuple[re.Pattern[str], str], ...] = (
    (re.compile(CLASSIC_PLUGIN, re.I), "gazebo-classic"),
    (re.compile(SIM_PLUGIN, re.I), "gz-sim"),
    (re.compile(r"mujoco_ros2_control", re.I), "mujoco"),
)
DEPENDENCIES: dict[str, str] = {
    "gazebo_ros": "gazebo-classic",
    "gazebo_plugins": "gazebo-classic",
    "gazebo_ros_control": "gazebo-classic",
    "gazebo_ros2_control": "gazebo-classic",
    "gazebo_ros_pkgs": "gazebo-classic",
    "ros_gz_sim": "gz-sim",
    "ros_gz": "gz-sim",
    "ros_gz_bridge": "gz-sim",
    "gz_ros2_control": "gz-sim",
    "ros_ign_gazebo": "gz-sim",
    "ros_ign": "gz-sim",
    "ign_ros2_control": "gz-sim",
    "mujoco_ros2_control": "mujoco",
    "mujoco_ros": "mujoco",
    "drake": "drake",
    "drake_ros": "drake",
}
PYBULLET_CONTACT = frozenset(
    {"lateral_friction", "rolling_friction", "spinning_friction", "contact_cfm", "contact_erp",
     "restitution", "stiffness", "damping", "friction_anchor"}
)  # fmt: skip
SIMULATORS = frozenset({"gazebo-classic", "gz-sim", "mujoco", "drake", "pybullet", "isaac"})


@dataclass(frozen=True, slots=True)
class Evidence:
    """One reason for a target: what was seen, and where (a file and line when known)."""

    target: str
    why: str
    path: str | None = None
    line: int | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"target": self.target, "why": self.why, "path": self.path, "line": self.line}

    def where(self) -> str:
        if self.path is None:
            return self.why
        place = f"{self.path}:{self.line}" if self.line else self.path
        return f"{self.why} ({place})"


@dataclass(frozen=True, slots=True)
class Targets:
    """The targets of one file and how they were chosen: ``given`` (``--target`` or the
    configuration), else ``evidence`` (empty when assumed)."""

    names: tuple[str, ...]
    given: bool = False
    evidence: tuple[Evidence, ...] = ()

    @property
    def assumed(self) -> bool:
        return not self.given and not any(e.target in SIMULATORS for e in self.evidence)

    def to_dict(self) -> dict[str, Any]:
        how = "given" if self.given else "assumed" if self.assumed else "inferred"
        return {
            "names": list(self.names),
            "how": how,
            "evidence": [e.to_dict() for e in self.evidence],
        }

    def sentence(self) -> str:
        """``Gazebo Sim, ROS (KDL, MoveIt): assumed, nothing names a simulator``."""
        labels = ", ".join(LABELS[t] for t in self.names)
        if self.given:
            return f"{labels}: as configured"
        simulators = [e for e in self.evidence if e.target in SIMULATORS]
        if not simulators:
            return (
                f"{labels}: assumed, nothing in the model or its package names a simulator "
                "(--target chooses)"
            )
        shown = "; ".join(e.where() for e in _first_per_target(simulators))
        return f"{labels}: inferred from {shown}"


def _first_per_target(evidence: list[Evidence]) -> list[Evidence]:
    seen: dict[str, Evidence] = {}
    for e in evidence:
        seen.setdefault(e.target, e)
    return list(seen.values())


def infer(doc: Document) -> Targets:
    """The targets of ``doc`` from its evidence (see the module's docstring)."""
    evidence = [*_in_model(doc), *_in_package(doc)]
    simulators = {e.target for e in evidence if e.target in SIMULATORS}
    names = set(simulators) if simulators else set(ASSUMED)
    if any(e.target == "ros" for e in evidence):
        names.add("ros")
    return Targets(ordered(tuple(names)), False, tuple(evidence))


def _where(doc: Document, el: Any) -> tuple[str, int | None]:
    if doc.origin is not None:
        found = doc.origin(el)
        if found is not None:
            return found.path, found.line
    return doc.path, el.sourceline


def _in_model(doc: Document) -> list[Evidence]:
    if doc.root is None:
        return []
    found: list[Evidence] = []
    for el in doc.root.iter():
        tag = el.tag
        if not isinstance(tag, str):
            continue
        if tag.startswith("{"):
            namespace, _, local = tag[1:].partition("}")
            if "drake" in namespace.lower() or namespace.endswith(":drake"):
                found.append(Evidence("drake", f"<drake:{local}>", *_where(doc, el)))
            continue
        if tag == "plugin":
            name = " ".join(
                v for v in (el.get("filename"), el.get("name"), (el.text or "").strip()) if v
            )
            for pattern, target in PLUGINS:
                if name and pattern.search(name):
                    plugin = el.get("filename") or (el.text or "").strip() or el.get("name")
                    found.append(Evidence(target, f"the plugin {plugin}", *_where(doc, el)))
                    break
        elif tag == "mujoco" and el.getparent() is doc.root:
            found.append(Evidence("mujoco", "a <mujoco> block", *_where(doc, el)))
        elif tag == "contact" and _pybullet_contact(el):
            found.append(Evidence("pybullet", "PyBullet's <contact> block", *_where(doc, el)))
    return found


def _pybullet_contact(el: Any) -> bool:
    """A link's ``<contact>`` with PyBullet's keys (``<lateral_friction value>``...)."""
    parent = el.getparent()
    if parent is None or parent.tag != "link":
        return False
    return any(isinstance(c.tag, str) and c.tag in PYBULLET_CONTACT for c in el)


def _in_package(doc: Document) -> list[Evidence]:
    from urdflint.sources import package_xml

    if doc.base_dir is None or doc.path in ("-", "<stdin>"):
        return []
    stop = getattr(doc.context, "root", None)
    folder = package_xml.enclosing(Path(doc.base_dir) / "_", stop)
    found: list[Evidence] = []
    if folder is not None:
        manifest = package_xml.read(folder)
        if manifest.problem is None:
            shown = _shown(doc, folder / "package.xml")
            for dependency in sorted(manifest.runtime):
                target = DEPENDENCIES.get(dependency)
                if target is None and dependency.startswith("isaac_ros_"):
                    target = "isaac"
                if target is not None:
                    why = f"package.xml depends on {dependency}"
                    found.append(Evidence(target, why, shown))
            found.append(Evidence("ros", f"a ROS package ({manifest.name})", shown))
    if not any(e.target == "ros" for e in found) and doc.root is not None:
        from urdflint.sources import srdf

        located = srdf.find(doc)
        if located is not None:
            found.append(Evidence("ros", "a MoveIt SRDF", located[1]))
    return found


def _shown(doc: Document, path: Path) -> str:
    """``path`` as the file is shown (relative when the file is shown relative)."""
    import os

    if os.path.isabs(doc.path) or doc.base_dir is None:
        return str(path)
    try:
        return os.path.relpath(path)
    except ValueError:
        return str(path)
