"""``urdflint check --add-noqa``: a suppression comment for every finding reported now.

Each error and warning (infos too with ``--show-info`` or ``--fail-on info``) gets an
``ignore`` directive on its own line before its element, in the file and at the line where
the finding is reported (for xacro, the macro file); robot-level findings get the file's
``ignore-file`` directive, and an SRDF's findings (M rules) the checked URDF's, since
suppressions of M findings live there. Directives already in place are extended, never
written twice (:mod:`urdflint.cli.noqa_text`).

Nothing is written until it is known to work: the files are checked again with the new
text in memory (the editor overlay the language server uses), and a comment that leaves its
finding reported (xacro dropped it, the element is computed) is not written. What a comment
cannot suppress is listed with why: a syntax error (X001: the file takes no comment), the
run's own notes (U rules), a file whose encoding cannot be kept. Running it again changes
nothing. Exit code: 1 when such findings at or above ``--fail-on`` remain, else 0 (2 when a
path cannot be read).
"""

from __future__ import annotations

import argparse
import os
import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from urdflint.cli import fragments, parallel
from urdflint.cli.common import EXIT_ERROR, EXIT_FINDINGS, EXIT_OK, UsageError
from urdflint.cli.noqa_text import Edited, Key, write
from urdflint.engine import config
from urdflint.model.finding import Finding, Severity
from urdflint.outputs.report import FAIL_LEVEL

SRDF_SUFFIXES = (".srdf", ".srdf.xacro", ".srdf.xml.xacro")
X001 = "a file that is not well-formed XML takes no comment: fix the syntax error first"
X010 = "xacro could not expand the file, so no comment in it is read: fix the expansion first"
RUN_NOTE = "a note about the run, not about the model"
NO_EFFECT = "a comment before its element does not suppress it (xacro drops or moves it)"


@dataclass
class Plan:
    """The comments to write: per file (absolute), the codes per spot, and the findings
    each spot is for; the findings no comment can suppress, with why."""

    spots: dict[str, dict[Key, set[str]]] = field(default_factory=dict)
    owners: dict[tuple[str, Key, str], list[Finding]] = field(default_factory=dict)
    refused: list[tuple[Finding, str]] = field(default_factory=list)

    def add(self, finding: Finding, file: str, key: Key) -> None:
        self.spots.setdefault(file, {}).setdefault(key, set()).add(finding.code)
        owned = self.owners.setdefault((file, key, finding.code), [])
        if not any(_same(finding, other) for other in owned):
            owned.append(finding)  # a macro's finding seen by several entries: counted once

    def drop(self, file: str, key: Key, code: str, why: str) -> None:
        """No comment for ``code`` at this spot: its findings are refused with ``why``."""
        codes = self.spots.get(file, {}).get(key)
        if codes is not None:
            codes.discard(code)
            if not codes:
                del self.spots[file][key]
        self.refused.extend((f, why) for f in self.owners.pop((file, key, code), []))


def run(
    args: argparse.Namespace, files: list[str], errors: list[str], finder: Any, context: Any
) -> int:
    """Add the comments, print what was done; the exit code (see the module docstring)."""
    if args.fix or args.diff or args.command == "fix":
        raise UsageError("--add-noqa writes comments, not fixes: run it without --fix/--diff")
    if "-" in files:
        raise UsageError("--add-noqa needs files, not standard input")
    if args.baseline or args.write_baseline:
        raise UsageError("--add-noqa writes a comment for every finding: drop the baseline")
    robots, _ = fragments.split(files)  # a fragment's X011 note is an info about the run
    tasks = [_task(name, finder) for name in robots]
    errors = list(errors)
    plan = Plan()
    roots = _roots(args.paths)
    for task, found in zip(tasks, _lint(args, tasks, context, errors), strict=True):
        _take(plan, task, found, _least(args, task), roots)
    edited = _trial(args, tasks, context, plan)
    _write(edited)
    _report(plan, edited)
    return _exit_code(args, files, errors, tasks, plan)


def _exit_code(
    args: argparse.Namespace,
    files: list[str],
    errors: list[str],
    tasks: Sequence[parallel.Task],
    plan: Plan,
) -> int:
    """2 for an unusable path (or none found), 1 when a finding that no comment suppresses
    is at or above ``--fail-on``, else 0."""
    for message in errors:
        print(f"urdflint: error: {message}", file=sys.stderr)
    if not files and not errors:
        since = f" changed since {args.changed_since}" if args.changed_since else " found"
        print(f"urdflint: no *.urdf or *.xacro files{since}", file=sys.stderr)
        return EXIT_OK if args.changed_since else EXIT_ERROR
    if errors:
        return EXIT_ERROR
    fail = [FAIL_LEVEL.get(task.settings.fail_on) for task in tasks]
    left = [f for f, _ in plan.refused if any(t is not None and f.severity >= t for t in fail)]
    return EXIT_FINDINGS if left else EXIT_OK


def _task(name: str, finder: Any) -> parallel.Task:
    try:
        settings = finder.for_folder(Path(name).parent)
    except config.ConfigError as exc:
        raise UsageError(str(exc)) from None
    return parallel.Task(name, name, settings)


def _least(args: argparse.Namespace, task: parallel.Task) -> Severity:
    """The least severity to suppress: what the text output lists."""
    shown = args.show_info or task.settings.fail_on == "info"
    return Severity.INFO if shown else Severity.WARNING


def _lint(
    args: argparse.Namespace, tasks: Sequence[parallel.Task], context: Any, errors: list[str]
) -> list[list[Finding]]:
    """Each task's findings (a file that cannot be read: an error, and none)."""
    jobs = parallel.jobs_for(args.jobs, len(tasks))
    found: list[list[Finding]] = []
    for done in parallel.run(tasks, context, parallel.Flags(), jobs):
        if done.error is not None and done.error not in errors:
            errors.append(done.error)
        found.append(list(done.findings))
    return found


def _take(
    plan: Plan,
    task: parallel.Task,
    findings: list[Finding],
    least: Severity,
    roots: tuple[str, ...],
) -> None:
    """Where each finding's comment goes, or why it has none."""
    for finding in findings:
        if finding.severity < least:
            continue
        if finding.code in ("X001", "X010"):
            plan.refused.append((finding, X001 if finding.code == "X001" else X010))
            continue
        if finding.code.startswith("U"):
            plan.refused.append((finding, RUN_NOTE))
            continue
        file = os.path.abspath(finding.path)
        key: Key = (finding.line, finding.column)
        if finding.path.lower().endswith(SRDF_SUFFIXES):  # M findings: the URDF's ignore-file
            file, key = os.path.abspath(task.name), None
        elif finding.element.count("/") <= 1:  # the robot itself: the whole file
            key = None
        why = _not_editable(file, roots)
        if why:
            plan.refused.append((finding, why))
            continue
        plan.add(finding, file, key)


def _roots(paths: Sequence[str]) -> tuple[str, ...]:
    """The folders whose files may be edited: the working folder and the paths given."""
    found = [os.getcwd(), *(p if os.path.isdir(p) else os.path.dirname(p) or "." for p in paths)]
    return tuple(os.path.join(os.path.abspath(folder), "") for folder in found)


def _not_editable(file: str, roots: tuple[str, ...]) -> str | None:
    """Why no comment is written into ``file``, or None."""
    if not os.path.isfile(file):
        return "not in a file urdflint can edit"
    if not file.startswith(roots):
        return "in a file outside the working folder and the paths checked (another package)"
    if not os.access(file, os.W_OK):
        return "in a file that is not writable"
    return None


def _edit(plan: Plan) -> dict[str, Edited]:
    """Each planned file's new bytes; the spots that refuse a comment leave the plan."""
    edited: dict[str, Edited] = {}
    for file, spots in sorted(plan.spots.items()):
        if not spots:
            continue
        with open(file, "rb") as handle:
            data = handle.read()
        done = write(data, {key: sorted(codes) for key, codes in spots.items()})
        for key, why in done.refused.items():
            for code in sorted(spots.get(key, ())):
                plan.drop(file, key, code, why)
        edited[file] = done
    return edited


def _trial(
    args: argparse.Namespace, tasks: Sequence[parallel.Task], context: Any, plan: Plan
) -> dict[str, Edited]:
    """The edits, checked in memory first: a comment that leaves its finding reported is
    dropped (and the files are edited again without it)."""
    edited = _edit(plan)
    changed = {file: done.data for file, done in edited.items() if done.added or done.extended}
    if not changed:
        return edited
    trial = replace(context, overlay={**context.overlay, **changed})
    left: set[tuple[str, str, str]] = set()
    for found in _lint(args, tasks, trial, []):
        left.update(_key(f) for f in found)
    failed = []
    for owner, findings in list(plan.owners.items()):
        stuck = [f for f in findings if _key(f) in left]
        if len(stuck) == len(findings):
            failed.append(owner)
        elif stuck:  # the comment works for some of its findings: kept, the others listed
            plan.owners[owner] = [f for f in findings if f not in stuck]
            plan.refused.extend((f, NO_EFFECT) for f in stuck)
    for file, key, code in failed:
        plan.drop(file, key, code, NO_EFFECT)
    return _edit(plan) if failed else edited


def _key(finding: Finding) -> tuple[str, str, str]:
    """What identifies a finding across edits above it (lines move, elements do not)."""
    return os.path.abspath(finding.path), finding.code, finding.element


def _same(a: Finding, b: Finding) -> bool:
    return _key(a) == _key(b) and (a.line, a.column, a.message) == (b.line, b.column, b.message)


def _write(edited: dict[str, Edited]) -> None:
    for file, done in edited.items():
        if done.added or done.extended:
            with open(file, "wb") as out:  # in place: the file keeps its mode and owner
                out.write(done.data)


def _report(plan: Plan, edited: dict[str, Edited]) -> None:
    """What was added where, and the findings left to fix."""
    out = sys.stdout
    total = Counter[str]()
    for file, done in sorted(edited.items()):
        if not (done.added or done.extended):
            continue
        codes = sorted({code for codes in plan.spots.get(file, {}).values() for code in codes})
        what = _count(done.added, "comment") + " added"
        if done.extended:
            what += f", {_count(done.extended, 'comment')} extended"
        out.write(f"{_shown(file)}: {what} ({', '.join(codes)})\n")
        total["added"] += done.added
        total["extended"] += done.extended
        total["files"] += 1
    suppressed = sum(len(findings) for findings in plan.owners.values())
    summary = f"urdflint: added {_count(total['added'], 'suppression comment')}"
    if total["extended"]:
        summary += f" and extended {total['extended']}"
    summary += f" in {_count(total['files'], 'file')} for {_count(suppressed, 'finding')}"
    if not total["files"]:
        summary = "urdflint: no comment to add"
    refused = _unique(plan.refused)
    if refused:
        out.write(f"{_count(len(refused), 'finding')} cannot be suppressed by a comment:\n")
        for finding, why in refused:
            out.write(f"{finding.path}:{finding.line}:{finding.column}: {finding.severity} ")
            out.write(f"{finding.code} {finding.name}: {finding.message}\n    {why}\n")
        summary += f"; {_count(len(refused), 'finding')} left to fix"
    out.write(summary + "\n")
    out.flush()


def _unique(refused: list[tuple[Finding, str]]) -> list[tuple[Finding, str]]:
    """Each refused finding once (a macro file's, seen by several entries), in file order."""
    found: dict[tuple[Any, ...], tuple[Finding, str]] = {}
    for finding, why in refused:
        found.setdefault((*_key(finding), finding.line, finding.column, finding.message),
                         (finding, why))  # fmt: skip
    return sorted(found.values(), key=lambda pair: pair[0].sort_key())


def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _shown(file: str) -> str:
    here = os.getcwd()
    return os.path.relpath(file, here) if file.startswith(here + os.sep) else file
