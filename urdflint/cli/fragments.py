"""The ``*.urdf`` fragments a run was given that no file includes: one X011 note each.

A fragment (:func:`urdflint.sources.discovery.fragment`: a ``<gazebo>`` block, a nameless
``<robot>`` of xacro macro calls meant for an include) is no robot, so the robot rules
would only report what its includer provides. Its note goes through the engine like any
finding: selected, ignored, re-levelled and suppressed (``ignore-file[X011]``) as usual.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from urdflint.engine import linter
from urdflint.model.document import Document
from urdflint.model.parsing import XmlProblem
from urdflint.sources.discovery import fragment


def split(files: Sequence[str]) -> tuple[list[str], list[tuple[str, str]]]:
    """The robot files among ``files``, and each fragment with why it is one."""
    robots: list[str] = []
    found: list[tuple[str, str]] = []
    for name in files:
        why = fragment(Path(name)) if name != "-" else None
        if why is None:
            robots.append(name)
        else:
            found.append((name, why))
    return robots, found


def add(found: Sequence[tuple[str, str]], finder: Any, outcome: Any, context: Any) -> None:
    """Each fragment's note into ``outcome`` (a ``check`` run), as a checked file."""
    for name, why in found:
        result = lint(name, why, finder.for_folder(Path(name).parent), context)
        outcome.checked.append(name)
        outcome.ran[name] = result.ran
        outcome.findings.extend(result.findings)


def lint(name: str, why: str, settings: Any, context: Any) -> linter.Result:
    """The fragment's result: its X011 note, and nothing a robot rule would say."""
    path = Path(name)
    message = (
        f"a fragment of a robot, not checked on its own: {why}, and no file found includes it"
        " (its findings appear where the file that includes it is checked)"
    )
    doc = Document(
        name,
        path.read_bytes(),
        targets=frozenset(settings.targets),
        settings=settings,
        context=context,
        base_dir=path.parent,
        problem=XmlProblem("X011", message),
        library=True,
    )
    return linter.lint_document(doc, settings)
