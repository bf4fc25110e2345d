"""Rule pages (``urdflint explain``) and the README rule table, from the registry."""

from __future__ import annotations

from importlib import resources

from urdflint.engine import registry
from urdflint.engine.registry import Rule

FIXABLE = {
    "safe": "Fix: automatic and safe (`urdflint fix`, or `check --fix`).",
    "unsafe": "Fix: automatic, but it changes the model's physics (`urdflint fix --unsafe-fixes`).",
}


def examples(code: str) -> list[tuple[str, str]]:
    """``(file name, text)`` of the rule's fixtures, bad ones first."""
    try:
        folder = resources.files("urdflint.fixtures") / "rules" / code
        names = sorted(p.name for p in folder.iterdir() if p.name.endswith((".urdf", ".xacro")))
    except (FileNotFoundError, ModuleNotFoundError, NotADirectoryError):
        return []
    ordered = [n for n in names if n.startswith("bad")] + [n for n in names if n.startswith("good")]
    return [(name, (folder / name).read_text(encoding="utf-8")) for name in ordered]


def page(rule: Rule) -> str:
    lines = [f"{rule.code} {rule.name} (default severity: {rule.severity})", "", rule.summary, ""]
    if rule.fixable:
        lines += [FIXABLE[rule.fixable], ""]
    for heading in ("What it does", "Why is this bad?", "How to fix"):
        lines += [f"## {heading}", rule.section(heading), ""]
    if rule.effects:
        lines += ["## What each target does", *effects_section(rule), ""]
    if rule.options:
        lines += ["## Options", *(f"- `{k}` (default {v!r})" for k, v in rule.options.items()), ""]
    if rule.needs:
        lines += ["## Needs", f"Optional modules: {', '.join(rule.needs)}", ""]
    for name, text in examples(rule.code):
        kind = "Bad" if name.startswith("bad") else "Good"
        lines += [f"## {kind} example ({name})", "```xml", text.rstrip(), "```", ""]
    return "\n".join(lines)


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
