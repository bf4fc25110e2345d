"""``urdflint info``: the robot's tree, per-link masses, total mass, centre of mass and DOF.

:func:`render` prints the kinematic tree like ``check_urdf`` does, with each link's
parent joint and its type, then a per-link mass table and the totals Pinocchio
computes (the root link and the links welded to it included, see P002). Without
Pinocchio it still prints the tree and the URDF's masses and their sum, and says
what needs Pinocchio. :func:`summary` is the ``models`` entry of ``check``'s JSON.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from urdflint.model.inertia import read_inertial
from urdflint.model.optional import install_command
from urdflint.model.values import fmt

if TYPE_CHECKING:
    from urdflint.engine.physics import Physics
    from urdflint.model.document import Document


def summary(doc: Document) -> dict[str, Any] | None:
    """``{name, root, links, joints, dof, mass, com}`` (counts for links and joints),
    or ``None`` when the model could not be built."""
    if not doc.ok:
        return None
    physics: Physics = doc.physics
    if not physics.built:
        return None
    return {
        "name": physics.name,
        "root": physics.root,
        "links": len(doc.links),
        "joints": len(doc.joints),
        "dof": physics.dof,
        "mass": physics.mass,
        "com": list(physics.com) if physics.com is not None else None,
    }


def render(doc: Document, fmt_name: str = "text", statics: bool = False) -> tuple[str, bool]:
    """The ``info`` output as text or JSON, and whether the model was built (exit 0);
    ``statics`` adds the gravity loads (``--statics``, :mod:`urdflint.outputs.statics_info`)."""
    data = collect(doc)
    if statics and "links" in data:
        from urdflint.outputs import statics_info

        data["statics"] = statics_info.collect(doc)
    ok = bool(data["built"]) or bool(data.get("pinocchio_missing"))
    ok = ok and not data.get("q_problems")
    if fmt_name == "json":
        return json.dumps(data, indent=2, default=_plain) + "\n", ok
    return text(data), ok


# -- data ----------------------------------------------------------------------------------


def _plain(value: Any) -> Any:
    """A numpy scalar an analysis left in the data, as the Python value it holds."""
    item = getattr(value, "item", None)
    if callable(item):
        return item()
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


def collect(doc: Document) -> dict[str, Any]:
    """Everything ``info`` shows, as plain JSON-able data."""
    if not doc.ok:
        problem = doc.problem
        message = f"{problem.code}: {problem.message} (line {problem.line})" if problem else None
        return {"version": 1, "path": doc.path, "built": False, "problem": message}
    graph = doc.graph
    links: list[dict[str, Any]] = []
    seen: set[str] = set()
    for root in graph.roots or list(doc.link_map)[:1]:
        _walk(doc, root, None, 0, links, seen)
    for name in doc.link_map:  # links only reachable through a loop
        if name not in seen:
            _walk(doc, name, None, 0, links, seen)
    static_sum = sum(item["mass"] or 0.0 for item in links)
    physics: Physics = doc.physics
    data: dict[str, Any] = {
        "version": 1,
        "path": doc.path,
        "name": doc.robot.get("name"),
        "root": graph.root,
        "built": physics.built,
        "problem": None if physics.built else physics.reason,
        "pinocchio_missing": physics.missing,
        "links": links,
        "joints": [
            {
                "name": j.name,
                "type": j.type,
                "parent": j.parent,
                "child": j.child,
                "mimic": (j.find("mimic").get("joint") if j.find("mimic") is not None else None),  # type: ignore[union-attr]
            }
            for j in doc.joints
        ],
        "mass_urdf": static_sum,
        "mass": physics.mass if physics.built else None,
        "dof": physics.dof if physics.built else None,
        "com": list(physics.com) if physics.built and physics.com is not None else None,
        "com_problem": physics.com_problem if physics.built else None,
        "com_frame": graph.root,
        "configuration": dict(physics.q) if physics.built else {},
        "q_problems": [p.message for p in physics.q_problems] if physics.built else [],
    }
    return data


def _walk(
    doc: Document,
    name: str,
    joint: Any,
    depth: int,
    out: list[dict[str, Any]],
    seen: set[str],
) -> None:
    stack: list[tuple[str, Any, int]] = [(name, joint, depth)]
    while stack:
        link, via, level = stack.pop()
        if link in seen:
            continue
        seen.add(link)
        element = doc.link_map[link].element if link in doc.link_map else None
        inertial = read_inertial(element) if element is not None else None
        out.append(
            {
                "name": link,
                "depth": level,
                "parent": via.parent if via is not None else None,
                "joint": via.name if via is not None else None,
                "joint_type": via.type if via is not None else None,
                "mass": inertial.mass if inertial is not None else None,
                "inertial": inertial is not None,
            }
        )
        for child_joint in reversed(doc.graph.child_joints.get(link, [])):
            if child_joint.child is not None:
                stack.append((child_joint.child, child_joint, level + 1))


# -- text ------------------------------------------------------------------------------------


def text(data: dict[str, Any]) -> str:
    lines: list[str] = []
    if "links" not in data:
        lines.append(f"{data['path']}: not a usable URDF: {data['problem']}")
        return "\n".join(lines) + "\n"
    lines.append(f"robot   {data['name']}")
    lines.append(f"root    {data['root']}")
    lines.append("")
    links = data["links"]
    width = max((2 * item["depth"] + len(item["name"]) for item in links), default=4)
    width = max(width, 4) + 2
    lines.append(f"{'link':<{width}}  {'mass (kg)':>10}  joint")
    for item in links:
        label = "  " * item["depth"] + item["name"]
        mass = _mass_cell(item)
        joint = (
            f"{item['joint_type']} '{item['joint']}' from '{item['parent']}'"
            if item["joint"] is not None
            else ("(root)" if item["name"] == data["root"] else "(no parent joint)")
        )
        lines.append(f"{label:<{width}}  {mass:>10}  {joint}")
    lines.append("")
    lines.append(f"links {len(links)}, joints {len(data['joints'])}")
    urdf_sum = f"{fmt(data['mass_urdf'])} kg"
    if data["built"]:
        lines.append(
            f"mass    {fmt(data['mass'])} kg (Pinocchio; sum of <mass> values: {urdf_sum})"
        )
        if data["com"] is not None:
            where = (
                ", ".join(f"{k}={fmt(v)}" for k, v in sorted(data["configuration"].items()))
                if data["configuration"]
                else "neutral configuration"
            )
            xyz = " ".join(fmt(x + 0.0) for x in data["com"])
            lines.append(f"com     {xyz} m (frame of root link '{data['com_frame']}', {where})")
        else:
            lines.append(f"com     not computed: {data['com_problem']}")
        lines.append(f"dof     {data['dof']}")
        for problem in data["q_problems"]:
            lines.append(f"error: {problem}")
    elif data["pinocchio_missing"]:
        lines.append(f"mass    {urdf_sum} (sum of <mass> values)")
        lines.append(f"com, dof: need Pinocchio ({install_command('dynamics')})")
    else:
        lines.append(f"mass    {urdf_sum} (sum of <mass> values)")
        lines.append(f"model not built: {data['problem']}")
    if "statics" in data:
        from urdflint.outputs import statics_info

        lines += statics_info.text(data["statics"])
    return "\n".join(lines) + "\n"


def _mass_cell(item: dict[str, Any]) -> str:
    if not item["inertial"]:
        return "-"
    if item["mass"] is None:
        return "?"
    return fmt(item["mass"])
