"""Rule pages (``urdflint explain``) and the README rule table, from the registry.

The short page (the default) fits a terminal: the title, the start of what the rule does,
why and how to fix it, and one bad and one good snippet of its fixtures. The long page
(``--long``, and the service's rule page) has every section in full, what each target
does, and every fixture. Neither shows the comments only the tests read.
"""

from __future__ import annotations

from collections.abc import Iterable

from urdflint.engine import examples, prose, registry, snippets
from urdflint.engine.registry import Rule

FIXABLE = {
    "safe": "Fix: automatic and safe (`urdflint fix`, or `check --fix`).",
    "unsafe": "Fix: automatic, but it changes the model's physics (`urdflint fix --unsafe-fixes`).",
}
HEADINGS = ("What it does", "Why is this bad?", "How to fix")
SHORT_LIMIT = 40  # lines of a short page, at most
CAPS = (4, 6, 4)  # lines of each section on a short page, at most
MORE = "More: `urdflint explain {code} --long`"  # what the short page leaves out follows


def page(rule: Rule) -> str:
    """The full page (``urdflint explain CODE --long``, the service's rule page): every
    section, what each target does, the options, and every fixture of the rule."""
    lines = _title(rule)
    for heading in HEADINGS:
        lines += [f"## {heading}", rule.section(heading), ""]
    if rule.effects:
        lines += ["## What each target does", *effects_section(rule), ""]
    if rule.options:
        lines += ["## Options", *(f"- `{k}` (default {v!r})" for k, v in rule.options.items()), ""]
    if rule.needs:
        lines += ["## Needs", f"Optional modules: {', '.join(rule.needs)}", ""]
    for example in examples.load(rule.code):
        lines += [_example_heading(example), *_fenced(example.lines), ""]
    return "\n".join(lines)


def short_page(rule: Rule) -> str:
    """The short page (``urdflint explain CODE``): at most ``SHORT_LIMIT`` lines with the
    title, the start of each section, and one bad and one good snippet."""
    head = _title(rule, short=True)
    fixtures = examples.load(rule.code)
    for most in (snippets.SPAN_MOST, snippets.SPAN):  # smaller snippets if the text needs room
        shown = _snippets(fixtures, most)
        room = SHORT_LIMIT - len(head) - len(shown) - 1 - 2 * len(HEADINGS)  # 1: "More: ..."
        if room >= prose.FLOOR * len(HEADINGS):
            break
    texts = [rule.section(heading) for heading in HEADINGS]
    cut = prose.fit(texts, room, list(CAPS))
    lines = head
    for heading, text in zip(HEADINGS, cut, strict=True):
        lines += [f"## {heading}", *text, ""]
    whole = [text.splitlines() for text in texts] == cut
    more = [
        part
        for part, missing in (
            ("the whole text", not whole),
            ("what each target does", bool(rule.effects)),
            ("every example", bool(fixtures)),
            ("the modules it needs", bool(rule.needs)),
        )
        if missing
    ]
    if more:
        shown.append(f"{MORE.format(code=rule.code)} ({', '.join(more)}).")
    return "\n".join([*lines, *shown]).rstrip("\n") + "\n"


def _title(rule: Rule, *, short: bool = False) -> list[str]:
    """The code, name, default severity and family, the summary, and the automatic fix
    (on the short page without the blank lines between, and with the rule's options)."""
    family = registry.FAMILIES[rule.family]
    title = f"{rule.code} {rule.name} (default severity: {rule.severity}; family: {family})"
    fix = [FIXABLE[rule.fixable]] if rule.fixable else []
    if short:
        options = ", ".join(f"`{k}` (default {v!r})" for k, v in rule.options.items())
        return [title, rule.summary, *fix, *([f"Options: {options}."] if options else []), ""]
    return [title, "", rule.summary, "", *([*fix, ""] if fix else [])]


def _snippets(fixtures: list[examples.Example], most: int) -> list[str]:
    """The short page's bad and good snippet, each under its heading ([] without both)."""
    found = snippets.pair(fixtures, most)
    if found is None:
        return []
    bad, good = found
    return [
        _example_heading(bad.example),
        *_fenced(bad.lines()),
        "",
        _example_heading(good.example),
        *_fenced(good.lines()),
    ]


def _example_heading(example: examples.Example) -> str:
    kind = "Bad" if example.bad else "Good"
    settings = f", with `{example.settings}`" if example.settings else ""
    return f"## {kind} example ({example.name}{settings})"


def _fenced(lines: Iterable[str]) -> list[str]:
    return ["```xml", *(line.rstrip() for line in lines), "```"]


def effects_section(rule: Rule) -> list[str]:
    """One line per (variant, target): the consequence, its severity and what the consumer
    does, and where that comes from."""
    from urdflint.model import targets

    lines: list[str] = []
    for variant, table in rule.effects.items():
        if variant:
            lines.append(f"{variant}:")
        for target in targets.ordered(tuple(table)):
            effect = table[target]
            basis = targets.BASIS[target]
            detail = f": {effect.detail}" if effect.detail else ""
            lines.append(
                f"- {targets.LABELS[target]} ({basis}): {effect.consequence.key}, "
                f"{effect.level}{detail}"
            )
    return lines


def rule_table() -> str:
    """The Markdown table README carries between its rule-table markers."""
    rows = ["| Code | Name | Severity | Fix | What it catches |", "|---|---|---|---|---|"]
    for rule in sorted(registry.load_rules().values(), key=lambda r: r.code):
        summary = rule.summary.replace("|", "\\|")
        fix = rule.fixable or ""
        rows.append(f"| {rule.code} | {rule.name} | {rule.severity} | {fix} | {summary} |")
    return "\n".join(rows) + "\n"


def update_readme(path: str = "README.md") -> bool:
    """Rewrite the table between README's rule-table markers; True if it changed."""
    import re
    from pathlib import Path

    readme = Path(path)
    text = readme.read_text(encoding="utf-8")
    new = re.sub(
        r"(<!-- rules:start -->\n).*?(<!-- rules:end -->)",
        lambda m: m.group(1) + rule_table() + m.group(2),
        text,
        flags=re.S,
    )
    if new != text:
        readme.write_text(new, encoding="utf-8")
    return new != text


if __name__ == "__main__":  # python -m urdflint.engine.docs  (refreshes README's rule table)
    print("README.md updated" if update_readme() else "README.md already current")
