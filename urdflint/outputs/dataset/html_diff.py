"""The dataset report page's comparison with an earlier run (``--against``), as HTML.

Escapes every string from the records, as :mod:`.html` does.
"""

from __future__ import annotations

from html import escape
from typing import Any

from urdflint.outputs.dataset.summary import OUTCOMES

HEADS = {
    "loads": "Loads",
    "changes": "Loads with changes",
    "refused": "Refused",
    "crashes": "Crashes",
}
BETTER_UP = {"loads": True, "changes": None, "refused": False, "crashes": False}  # more is...
SHOWN = 100  # rows of a list shown (the JSON summary has up to its limit)


def e(value: Any) -> str:
    return escape(str(value), quote=True)


def path(value: Any) -> str:
    """A path, escaped, that may wrap after each ``/``."""
    return e(value).replace("/", "/<wbr>")


def _delta(old: int, new: int, up_is_better: bool | None = False) -> str:
    """``old → new`` with the change coloured: red when worse, green when better (grey:
    neither, as more files loading with changes can be either)."""
    change = new - old
    if not change:
        return f"{new:,}"
    css = (
        "delta-same"
        if up_is_better is None
        else ("delta-down" if (change > 0) == up_is_better else "delta-up")
    )
    return (
        f'<span class="delta"><span class="muted">{old:,}</span><span class="arrow">'
        f'&#8594;</span>{new:,} <span class="{css}">({change:+,})</span></span>'
    )


def _stat(key: str, value: int, label: str) -> str:
    return (
        f'<div class="stat" data-stat="{key}" data-value="{value}"><span class="value">'
        f'{value:,}</span><span class="label">{label}</span></div>'
    )


def diff_section(diff: dict[str, Any], against: list[str]) -> str:
    f = diff["files"]
    stats = "".join(
        [
            _stat("worse", f["worse"], "files worse"),
            _stat("better", f["better"], "files better"),
            _stat("changed", f["changed"], "changed both ways"),
            _stat("added", f["added"], "files added"),
            _stat("removed", f["removed"], "files removed"),
            _stat("new", diff["new_findings"]["count"], "new findings"),
            _stat("fixed", diff["fixed_findings"]["count"], "fixed findings"),
        ]
    )
    source = f' (<span class="mono">{e(", ".join(against))}</span>)' if against else ""
    parts = [
        f'<section class="card" id="diff"><h2>Changes against the earlier run{source}</h2>',
        f'<p class="note">{f["old"]:,} files then, {f["new"]:,} now; {f["same"]:,} unchanged. '
        "New and fixed findings are matched by path, rule and element (not by line).</p>",
        f'<div class="stats" id="diff-stats">{stats}</div>',
        _matrix(diff["matrix"]),
        _files("worse", "Files that got worse", diff["worse"], f["worse"]),
        _files("better", "Files that got better", diff["better"], f["better"]),
        _files(
            "changed",
            "Files better on some targets, worse on others",
            diff["changed"],
            f["changed"],
        ),
        _rules(diff["rules"]),
        _findings("new", "New findings", diff["new_findings"]),
        _findings("fixed", "Fixed findings", diff["fixed_findings"]),
        _paths("added", "Files added", diff["added"], f["added"]),
        _paths("removed", "Files removed", diff["removed"], f["removed"]),
        "</section>",
    ]
    return "".join(parts)


def _matrix(rows: list[dict[str, Any]]) -> str:
    if not rows:
        return ""
    body = "".join(
        f'<tr data-target="{e(r["target"])}"><th scope="row">{e(r["label"])}</th>'
        + "".join(
            f'<td class="num" data-outcome="{o}" data-old="{r[o][0]}" data-new="{r[o][1]}">'
            f"{_delta(r[o][0], r[o][1], BETTER_UP[o])}</td>"
            for o in OUTCOMES
        )
        + "</tr>"
        for r in rows
    )
    heads = "".join(f'<th class="num">{HEADS[o]}</th>' for o in OUTCOMES)
    return (
        '<h3>Load matrix, then and now</h3><div class="table-wrap">'
        f'<table id="diff-matrix"><thead><tr><th>Target</th>{heads}</tr></thead>'
        f"<tbody>{body}</tbody></table></div>"
    )


def _more(shown: int, total: int) -> str:
    if total <= shown:
        return ""
    return f'<p class="more">and {total - shown:,} more (<code>--format json</code> lists them)</p>'


def _moves(targets: dict[str, list[str]]) -> str:
    from urdflint.model.targets import LABELS

    return "".join(
        f'<span class="move" data-target="{e(t)}">{e(LABELS.get(t, t))} '
        f'<span class="outcome" data-outcome="{e(a)}">{e(a)}</span><span class="arrow">&#8594;'
        f'</span><span class="outcome" data-outcome="{e(b)}">{e(b)}</span></span>'
        for t, (a, b) in targets.items()
    )


def _files(key: str, title: str, changes: list[dict[str, Any]], total: int) -> str:
    if not changes:
        return ""
    rows = []
    for c in changes[:SHOWN]:
        notes = []
        if c["unreadable"][0] != c["unreadable"][1]:
            notes.append("now unreadable" if c["unreadable"][1] else "readable again")
        if c["crashed"][0] != c["crashed"][1]:
            notes.append("a rule crashes" if c["crashed"][1] else "no crash")
        note = f' <span class="muted">({e(", ".join(notes))})</span>' if notes else ""
        rows.append(
            f'<tr data-path="{e(c["path"])}" data-verdict="{e(c["verdict"])}">'
            f'<td class="path">{path(c["path"])}{note}</td>'
            f'<td class="num">{_delta(*c["errors"])}</td>'
            f'<td class="num">{_delta(*c["warnings"])}</td><td>{_moves(c["targets"])}</td></tr>'
        )
    return (
        f'<h3>{title}</h3><div class="table-wrap"><table id="diff-{key}"><thead><tr>'
        '<th>Asset</th><th class="num">Errors</th><th class="num">Warnings</th>'
        f"<th>Targets</th></tr></thead><tbody>{''.join(rows)}</tbody></table></div>"
        + _more(len(rows), total)
    )


def _rules(moved: dict[str, list[dict[str, Any]]]) -> str:
    rows = [
        f'<tr data-code="{e(r["code"])}" data-delta="{r["delta"]}"><td><code>{e(r["code"])}'
        f'</code></td><td>{e(r["name"])}</td><td><span class="sev" '
        f'data-severity="{e(r["severity"])}">{e(r["severity"])}</span></td>'
        f'<td class="num">{_delta(r["old"], r["new"])}</td></tr>'
        for key in ("up", "down")
        for r in moved[key][:SHOWN]
    ]
    if not rows:
        return ""
    return (
        '<h3>Rules whose counts changed</h3><div class="table-wrap scroll">'
        '<table id="diff-rules" class="sortable"><thead><tr><th>Code</th><th>Rule</th>'
        f'<th>Severity</th><th class="num">Findings</th></tr></thead><tbody>{"".join(rows)}'
        "</tbody></table></div>"
    )


def _findings(key: str, title: str, found: dict[str, Any]) -> str:
    items = found["items"][:SHOWN]
    if not items:
        return ""
    rows = "".join(
        f'<tr data-code="{e(x["code"])}" data-fingerprint="{e(x["fingerprint"])}">'
        f'<td class="path">{path(x["path"])}:{e(x["line"])}</td><td><span class="chip" '
        f'data-severity="{e(x["severity"])}">{e(x["code"])}</span></td>'
        f"<td>{e(x['message'])}</td></tr>"
        for x in items
    )
    return (
        f'<h3>{title}</h3><div class="table-wrap scroll"><table id="diff-{key}-findings">'
        "<thead><tr><th>Where</th><th>Rule</th><th>Message</th></tr></thead>"
        f"<tbody>{rows}</tbody></table></div>" + _more(len(items), found["count"])
    )


def _paths(key: str, title: str, paths: list[str], total: int) -> str:
    if not paths:
        return ""
    items = "".join(f'<li class="path">{path(p)}</li>' for p in paths[:SHOWN])
    return f'<h3>{title}</h3><ul id="diff-{key}">{items}</ul>' + _more(
        min(len(paths), SHOWN), total
    )
