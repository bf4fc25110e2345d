"""A `package://` mesh or texture names a package the file's own package does not depend on.

## What it does
For a description that lives in a ROS package (a `package.xml` in a folder
above the file), reads the manifest and checks every `package://OTHER/...` of
a `<mesh>` or `<texture>`: `OTHER` must be the package itself or be declared
with a tag a binary install brings along: `<depend>`, `<exec_depend>`,
`<run_depend>` (format 1), `<build_export_depend>` or
`<buildtool_export_depend>`. `<build_depend>` and `<test_depend>` do not count.

Reported once per file and package, on the first reference, naming how many
there are. In a document expanded from xacro, the check uses the package of the
file where the reference is written (an included macro from another package is
checked against that package's manifest), and only references whose package
name is written literally there (`package://${pkg}/...` is the includer's
business). A `package.xml` that cannot be parsed is reported once.

## Why is this bad?
In a source workspace every package is there, so the mesh resolves and nobody
notices. Installed from binaries (`apt install ros-<distro>-my-robot-description`),
in a minimal Docker image, or through rosdep, only declared dependencies come
along: bloom generates the Debian `Depends:` from `exec_depend`,
`build_export_depend` (both implied by `<depend>`), `run_depend` and
`buildtool_export_depend`. resource_retriever then fails with "Package [OTHER]
does not exist", RViz and MoveIt show the link without its geometry, Gazebo
logs that it cannot find the file, and Isaac Sim's importer skips the mesh.

## How to fix
Add `<exec_depend>OTHER</exec_depend>` (or `<depend>OTHER</depend>`) to the
package's `package.xml`, or copy the meshes into the package and refer to them
as `package://THIS_PACKAGE/...`.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from urdflint.engine.registry import Hit, rule
from urdflint.model.document import Document
from urdflint.model.finding import Severity
from urdflint.sources import package_xml
from urdflint.sources.meshes import FileRef, package_of


@dataclass
class Group:
    """References to one undeclared package from one file."""

    manifest: package_xml.Manifest
    refs: list[FileRef] = field(default_factory=list)


@rule("C015", "package-not-a-dependency", Severity.WARNING)
def check(doc: Document) -> Iterator[Hit]:
    groups: dict[tuple[Path, str], Group] = {}
    broken: dict[Path, FileRef] = {}  # unreadable manifests, first reference
    for ref in package_xml.file_references(doc):
        other = package_of(ref.uri)
        if other is None:
            continue
        where = package_xml.written(doc, ref.element, "filename")
        if where.file is None or (where.expanded and f"package://{other}" not in where.text):
            continue
        folder = package_xml.enclosing(where.file, doc.resolver.root)
        if folder is None:
            continue
        manifest = package_xml.read(folder)
        if manifest.problem is not None:
            broken.setdefault(folder, ref)
        elif not manifest.provides(other):
            groups.setdefault((folder, other), Group(manifest)).refs.append(ref)
    for (folder, other), group in groups.items():
        yield _hit(group.refs, group.manifest, other, folder)
    for folder, ref in broken.items():
        problem = package_xml.read(folder).problem
        yield Hit(
            ref.element,
            f"{folder / 'package.xml'}: {problem}, so the package's dependencies are unknown",
            fix="Repair package.xml (see REP 149 for its format).",
            severity=Severity.INFO,
        )


def _hit(refs: list[FileRef], manifest: package_xml.Manifest, other: str, folder: Path) -> Hit:
    first: etree._Element = refs[0].element
    count = f"{len(refs)} references" if len(refs) > 1 else "a reference"
    return Hit(
        first,
        f"{count} to package {other!r} (first: {refs[0].what}), but {manifest.name!r} "
        f"does not declare it in {folder / 'package.xml'}: a binary install will not bring "
        f"{other!r} along",
        fix=f"Add <exec_depend>{other}</exec_depend> to {folder / 'package.xml'}.",
        attribute="filename",
    )
