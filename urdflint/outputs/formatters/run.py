"""What a formatter knows about the run besides the findings, and the one-line summary."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from urdflint.model.finding import Finding, Severity


@dataclass(frozen=True)
class RunInfo:
    """What a formatter may know about the run besides the findings."""

    tool_version: str
    files: tuple[str, ...] = ()
    models: dict[str, Any] = field(default_factory=dict)
    fail_on: str = "error"  # lowest failing severity, or "never" (JUnit failures)
    rules: dict[str, tuple[str, ...]] = field(default_factory=dict)  # path -> rule codes run
    show_info: bool = True  # text: list infos one by one (else one summary line)
    matrix: tuple[dict[str, Any], ...] = ()  # --matrix: one row per (file, target)
    targets: dict[str, Any] = field(default_factory=dict)  # path -> the targets and how chosen
    baselined: int = 0  # findings hidden by --baseline (recorded by --write-baseline)
    # display options of the main output; they never change the findings or the exit code
    output_format: str = "concise"  # text: "concise" groups a rule's findings at one place
    statistics: bool = False  # text, json: one row per rule instead of the findings
    quiet: bool = False  # text, github: the findings only, no summary lines
    # SARIF helpUri of each rule: a URL with {code}, {name} or {path} (the rule's source in
    # the repository), or a base URL that the code is appended to; None: no helpUri
    docs_url: str | None = None
    unread: tuple[str, ...] = ()  # paths whose file is not what was checked (stdin's name)

    def summary(self, findings: Sequence[Finding]) -> dict[str, int]:
        counts = {"files": len(self.files), "error": 0, "warning": 0, "info": 0}
        for finding in findings:
            counts[str(finding.severity)] += 1
        return counts


def summary_line(findings: Sequence[Finding], run: RunInfo) -> str:
    counts = run.summary(findings)
    if not findings and not counts["files"]:
        return "urdflint: no files checked"  # not "no problems": nothing was looked at
    accepted = f" ({_plural(run.baselined, 'finding')} in the baseline)" if run.baselined else ""
    files = _plural(counts["files"], "file")
    if not findings:
        return f"urdflint: no {'new ' if accepted else ''}problems in {files}{accepted}"
    parts = [_plural(counts[str(s)], str(s)) for s in reversed(Severity) if counts[str(s)]]
    return f"urdflint: {', '.join(parts)} in {files}{accepted}"


def targets_lines(run: RunInfo) -> list[str]:
    """``targets: Gazebo Sim, ROS (KDL, MoveIt): assumed, ...`` for the files whose targets
    were inferred or assumed (none when every file's were given), one line per distinct
    choice, with the number of files when several were checked."""
    from urdflint.engine.inference import Evidence, Targets

    groups: dict[str, int] = {}
    for chosen in run.targets.values():
        if not chosen or chosen.get("how") == "given":
            continue
        evidence = tuple(Evidence(**e) for e in chosen.get("evidence", ()))
        sentence = Targets(tuple(chosen["names"]), False, evidence).sentence()
        groups[sentence] = groups.get(sentence, 0) + 1
    several = len(run.targets) > 1
    return [
        f"targets: {sentence}" + (f" [{_plural(count, 'file')}]" if several else "")
        for sentence, count in groups.items()
    ]


def _plural(count: int, word: str) -> str:
    return f"{count} {word}" if count == 1 else f"{count} {word}s"
