"""The editor's requests: code actions (the finding's fix, a suppression comment), hover (the
rule, a link's inertia, the robot's mass and centre of mass) and the link/joint outline, from
what the analyses found (the findings a file shows: :meth:`Analyzer.findings_for`)."""

from __future__ import annotations

import os
from typing import Any

from lsprotocol import types as T

from urdflint.lsp import convert, describe
from urdflint.lsp.analysis import Analyzer


def finding_for(analyzer: Analyzer, path: str, diagnostic: T.Diagnostic) -> Any:
    data = diagnostic.data if isinstance(diagnostic.data, dict) else {}
    for finding in analyzer.findings_for(path):
        if finding.code != diagnostic.code:
            continue
        if (finding.line, finding.column) == (data.get("line"), data.get("column")):
            return finding
        if not data and finding.line - 1 == diagnostic.range.start.line:
            return finding
    return None


def actions(analyzer: Analyzer, params: T.CodeActionParams) -> list[T.CodeAction]:
    path = convert.path_of(params.text_document.uri)
    if path is None:
        return []
    lines = convert.lines_of(analyzer.text(path) or "")
    found: list[T.CodeAction] = []
    for diagnostic in params.context.diagnostics:
        if diagnostic.source != convert.SOURCE:
            continue
        finding = finding_for(analyzer, os.path.abspath(path), diagnostic)
        if finding is None:
            continue
        fix = finding.autofix
        if fix is not None and fix.edits and not fix.unavailable:
            edit = convert.fix_edit(fix, analyzer.text)
            if edit is not None:
                unsafe = " (unsafe: changes the physics)" if fix.applicability == "unsafe" else ""
                found.append(
                    T.CodeAction(
                        f"Fix {finding.code}: {fix.description}{unsafe}",
                        kind=T.CodeActionKind.QuickFix,
                        diagnostics=[diagnostic],
                        edit=edit,
                        is_preferred=fix.applicability == "safe",
                    )
                )
        found.append(
            T.CodeAction(
                f"Suppress {finding.code} ({finding.name}) with a comment",
                kind=T.CodeActionKind.QuickFix,
                diagnostics=[diagnostic],
                edit=convert.suppression(lines, params.text_document.uri, finding),
            )
        )
    return found


def hover(analyzer: Analyzer, params: T.HoverParams) -> T.Hover | None:
    path = convert.path_of(params.text_document.uri)
    text = analyzer.text(path) if path else None
    if path is None or text is None:
        return None
    path = os.path.abspath(path)
    lines = convert.lines_of(text)
    found = describe.tag_at(text, lines, params.position)
    if found is None:
        return None
    tag, start, end = found
    here = [f for f in analyzer.findings_for(path) if start <= (f.line, f.column) <= end]
    covering = analyzer.document_for(path)
    doc = covering[0] if covering else None
    element = describe.element_at(doc, path, *start)
    value = describe.hover(doc, here, element, tag)
    if value is None:
        return None
    return T.Hover(T.MarkupContent(T.MarkupKind.Markdown, value))


def outline(analyzer: Analyzer, params: T.DocumentSymbolParams) -> list[T.DocumentSymbol]:
    path = convert.path_of(params.text_document.uri)
    if path is None:
        return []
    path = os.path.abspath(path)
    covering = analyzer.document_for(path)
    lines = convert.lines_of(analyzer.text(path) or "")
    return describe.symbols(covering[0] if covering else None, path, lines)
