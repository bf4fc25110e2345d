"""Findings and fixes in the Language Server Protocol's terms.

LSP positions count lines from 0 and characters in UTF-16 code units; urdflint's count lines
from 1 and characters in code points, and edits are byte offsets. Everything here converts
against the text the editor has (the open buffer, else the file on disk).
"""

from __future__ import annotations

import re
from typing import Any

from lsprotocol import types as T
from pygls import uris

from urdflint.model.finding import Finding, Severity

SOURCE = "urdflint"
SEVERITY = {
    Severity.ERROR: T.DiagnosticSeverity.Error,
    Severity.WARNING: T.DiagnosticSeverity.Warning,
    Severity.INFO: T.DiagnosticSeverity.Information,
}
# what a finding's position starts: a start tag (whole when on one line, else its name), an
# attribute and its value, or a word
SPAN_RE = re.compile(
    r"""<[\w.:-]+(?:"[^"]*"|'[^']*'|[^'">])*>|<[\w.:-]+|[\w.:-]+\s*=\s*(?:"[^"]*"|'[^']*')"""
    r"""|[^\s<>"']+"""
)


def uri_of(path: str) -> str:
    return uris.from_fs_path(path) or f"file://{path}"


def path_of(uri: str) -> str | None:
    return uris.to_fs_path(uri)


def lines_of(text: str) -> list[str]:
    """The lines as urdflint numbers them (split on ``\n`` only, as libxml2 counts)."""
    return text.split("\n")


def units(text: str) -> int:
    """Length of ``text`` in UTF-16 code units."""
    return len(text.encode("utf-16-le")) // 2


def position(lines: list[str], line: int, column: int) -> T.Position:
    """1-based line and code-point column -> an LSP position."""
    row = min(max(line - 1, 0), max(len(lines) - 1, 0))
    text = lines[row] if lines else ""
    return T.Position(row, units(text[: max(column - 1, 0)]))


def finding_range(lines: list[str], finding: Finding) -> T.Range:
    """The tag, attribute or word the finding points at."""
    start = position(lines, finding.line, finding.column)
    text = lines[start.line] if lines else ""
    at = min(max(finding.column - 1, 0), len(text))
    match = SPAN_RE.match(text, at)
    end = at + (len(match.group(0)) if match else 0)
    if end == at:  # nothing to underline: the rest of the line, at least one character
        end = max(len(text.rstrip()), at + 1)
    return T.Range(start, T.Position(start.line, units(text[:end])))


def diagnostic(lines: list[str], finding: Finding) -> T.Diagnostic:
    related = [
        T.DiagnosticRelatedInformation(
            T.Location(uri_of(call.path), point(call.line, call.column)),
            f"in macro `{call.macro}`, called here",
        )
        for call in finding.trace
        if call.path.startswith("/")
    ]
    message = finding.message
    if finding.fix:
        message += f"\nFix: {finding.fix}"
    return T.Diagnostic(
        range=finding_range(lines, finding),
        message=message,
        severity=SEVERITY[finding.severity],
        code=finding.code,
        source=SOURCE,
        related_information=related or None,
        data={"name": finding.name, "line": finding.line, "column": finding.column},
    )


def point(line: int, column: int) -> T.Range:
    """A range at a 1-based position in a file not open (columns taken as written)."""
    at = T.Position(max(line - 1, 0), max(column - 1, 0))
    return T.Range(at, at)


def offset_position(data: bytes, offset: int) -> T.Position:
    """A byte offset in ``data`` (UTF-8) -> an LSP position."""
    offset = min(max(offset, 0), len(data))
    row = data.count(b"\n", 0, offset)
    start = data.rfind(b"\n", 0, offset) + 1
    return T.Position(row, units(data[start:offset].decode("utf-8", "replace")))


def fix_edit(autofix: Any, text_of: Any) -> T.WorkspaceEdit | None:
    """The autofix as a workspace edit; ``text_of(path)`` gives the text its offsets index
    (``None`` when the file cannot be read: then no edit is offered)."""
    changes: list[Any] = []
    for path in dict.fromkeys(e.path for e in autofix.edits):
        doc = T.OptionalVersionedTextDocumentIdentifier(uri=uri_of(path), version=None)
        mine = [e for e in autofix.edits if e.path == path]
        if any(e.create for e in mine):
            changes.append(T.CreateFile(uri=uri_of(path), kind="create"))
            start = T.Position(0, 0)
            edits = [T.TextEdit(T.Range(start, start), e.text) for e in mine]
        else:
            text = text_of(path)
            if text is None:
                return None
            data = text.encode("utf-8")
            edits = [
                T.TextEdit(
                    T.Range(offset_position(data, e.start), offset_position(data, e.end)), e.text
                )
                for e in mine
            ]
        changes.append(T.TextDocumentEdit(doc, edits))
    return T.WorkspaceEdit(document_changes=changes) if changes else None


def _tag_start(lines: list[str], row: int, column: int) -> tuple[int, int]:
    """Where the tag holding (row, column) starts: the position itself when it is a ``<``,
    else the last ``<`` before it (an attribute's finding; a start tag may span lines, and
    no ``<`` is written inside one)."""
    for r in range(row, -1, -1):
        text = lines[r] if r < len(lines) else ""
        found = text.rfind("<", 0, column + 1 if r == row else len(text))
        if found >= 0:
            return r, found
    return row, column


def suppression(lines: list[str], uri: str, finding: Finding) -> T.WorkspaceEdit:
    """An ``ignore`` comment on its own line right before the finding's element, indented
    as it; an element that does not start its line is moved to a line of its own first."""
    row = min(max(finding.line - 1, 0), max(len(lines) - 1, 0))
    text = lines[row] if lines else ""
    column = min(max(finding.column - 1, 0), len(text))
    row, column = _tag_start(lines, row, column)  # a finding at an attribute: its element
    text = lines[row] if lines else ""
    comment = f"<!-- urdflint: ignore[{finding.code}] {finding.name} -->"
    indent = text[: len(text) - len(text.lstrip())]
    if text[:column].strip():  # something precedes the element on its line
        at = T.Position(row, units(text[:column]))
        inner = indent + "  "
        edit = T.TextEdit(T.Range(at, at), f"\n{inner}{comment}\n{inner}")
        return T.WorkspaceEdit(changes={uri: [edit]})
    at = T.Position(row, 0)
    return T.WorkspaceEdit(changes={uri: [T.TextEdit(T.Range(at, at), f"{indent}{comment}\n")]})
