"""The dataset report as one self-contained HTML page (``urdflint report --html FILE``).

Inline CSS, inline SVG plots and one small inline script (table sorting): the page opens
offline, references nothing outside itself and prints. Every string that comes from the
records (paths, codes, names, messages) is escaped. Elements carry stable ids and
``data-*`` attributes (``#matrix-table td.cell[data-target][data-outcome][data-count]``,
``svg.plot[data-plot]``, ``.stat[data-stat]``) for scripts and tests.
"""

from __future__ import annotations

from html import escape
from typing import Any

from urdflint.outputs.dataset import plots
from urdflint.outputs.dataset.html_diff import diff_section
from urdflint.outputs.dataset.style import CSS, SCRIPT
from urdflint.outputs.dataset.summary import OUTCOMES

HEADS = {
    "loads": "Loads",
    "changes": "Loads with changes",
    "refused": "Refused",
    "crashes": "Crashes",
    "not-installed": "Not installed",
}
RGB = {
    "loads": (18, 183, 106),
    "changes": (247, 144, 9),
    "refused": (240, 68, 56),
    "crashes": (145, 32, 24),
    "not-installed": (152, 162, 179),
}
SHOWN_RULES = 200
RANK = {"error": 3, "warning": 2, "info": 1}


def e(value: Any) -> str:
    """Text from the records, escaped for an element's content or an attribute."""
    return escape(str(value), quote=True)


def path(value: Any) -> str:
    """A path, escaped, that may wrap after each ``/``."""
    return e(value).replace("/", "/<wbr>")


def percent(part: int, whole: int) -> str:
    if not whole:
        return ""
    share = 100 * part / whole
    return f"{share:.0f} %" if share >= 10 or share == 0 else f"{share:.1f} %"


def render(summary: dict[str, Any]) -> str:
    """The whole page."""
    sources = ", ".join(summary.get("results") or [])
    body = [
        _headline(summary),
        '<div class="columns">',
        _severities(summary),
        _rules(summary),
        "</div>",
        _matrix(summary),
        _worst(summary),
        _distributions(summary),
    ]
    if summary.get("diff"):
        body.append(diff_section(summary["diff"], summary.get("against") or []))
    tools = ", ".join(summary.get("tools") or []) or "urdflint"
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>urdflint dataset report: {summary['files']} files</title>\n"
        f"<style>{CSS}</style>\n</head>\n<body>\n"
        '<header class="top"><div class="wrap"><p class="brand"><span class="logo">&#9670;</span>'
        f' urdflint</p><span class="sources" title="{e(sources)}">{e(sources)}</span></div>'
        '</header>\n<main class="wrap" id="report">\n'
        + "\n".join(body)
        + f"\n<footer>Written by urdflint report from records of {e(tools)}.</footer>\n"
        f"</main>\n<script>{SCRIPT}</script>\n</body>\n</html>\n"
    )


def _stat(key: str, value: int, label: str, whole: int | None = None) -> str:
    share = f'<span class="share">{percent(value, whole)} of files</span>' if whole else ""
    return (
        f'<div class="stat" data-stat="{key}" data-value="{value}">'
        f'<span class="value">{value:,}</span><span class="label">{e(label)}</span>'
        f"{share}</div>"
    )


def _headline(summary: dict[str, Any]) -> str:
    total, status, found = summary["files"], summary["status"], summary["matrix"]
    findings = sum(s["findings"] for s in summary["severities"])
    stats = [
        _stat("files", total, "files checked"),
        _stat("errors", status["errors"], "with errors", total),
        _stat("warnings", status["warnings"], "with warnings, no errors", total),
        _stat("infos", status["infos"], "with infos only", total),
        _stat("clean", status["clean"], "clean", total),
        _stat("everywhere", found["everywhere"], "load on every target", found["modelled"]),
        _stat("findings", findings, "findings"),
        _stat("unreadable", status["unreadable"], "unreadable"),
        _stat("crashed", status["crashed"], "a rule crashed on"),
    ]
    return (
        f'<h1>Dataset report</h1><p class="lead">{total:,} files, '
        f"{findings:,} findings from {len(summary['rules'])} rules; "
        f"{found['modelled']:,} models in the load matrix.</p>"
        f'<section id="headline" class="stats" aria-label="Headline numbers">{"".join(stats)}'
        "</section>" + _problems(summary)
    )


def _problems(summary: dict[str, Any]) -> str:
    """The unreadable files and those a rule crashed on, listed (a few)."""
    rows = [
        f'<tr data-kind="unreadable"><td><span class="outcome" data-outcome="refused">'
        f'unreadable</span></td><td class="path">{path(u["path"])}</td>'
        f"<td>{e(u['error'] or '')}</td></tr>"
        for u in summary["unreadable"][:50]
    ]
    rows += [
        f'<tr data-kind="crashed"><td><span class="outcome" data-outcome="crashes">'
        f'rule crashed</span></td><td class="path">{path(p)}</td><td></td></tr>'
        for p in summary["crashed"][:50]
    ]
    if not rows:
        return ""
    return (
        '<section class="card" id="problems"><h2>Files not fully checked</h2>'
        '<div class="table-wrap"><table><tbody>'
        + "".join(rows)
        + "</tbody></table></div></section>"
    )


def _severities(summary: dict[str, Any]) -> str:
    total = summary["files"]
    rows = "".join(
        f'<tr data-severity="{e(s["severity"])}"><td><span class="sev" '
        f'data-severity="{e(s["severity"])}">{e(s["severity"])}</span></td>'
        f'<td class="num">{s["findings"]:,}</td><td class="num">{s["files"]:,}</td>'
        f'<td class="num">{percent(s["files"], total)}</td></tr>'
        for s in summary["severities"]
    )
    return (
        '<section class="card" id="severities"><h2>Findings by severity</h2>'
        '<p class="note">Each file counts once per severity it has.</p>'
        '<div class="table-wrap"><table id="severity-table"><thead><tr><th>Severity</th>'
        '<th class="num">Findings</th><th class="num">Files</th><th class="num">Share</th>'
        f"</tr></thead><tbody>{rows}</tbody></table></div>{_status(summary)}</section>"
    )


STATUS = (
    ("errors", "with errors"),
    ("warnings", "warnings, no errors"),
    ("infos", "infos only"),
    ("clean", "clean"),
    ("unreadable", "unreadable"),
)


def _status(summary: dict[str, Any]) -> str:
    """The files by their worst finding, as one bar and its legend."""
    total, status = summary["files"], summary["status"]
    parts = "".join(
        f'<span class="seg" data-status="{key}" style="width: {100 * status[key] / total:.2f}%"'
        f' title="{label}: {status[key]}"></span>'
        for key, label in STATUS
        if total and status[key]
    )
    legend = "".join(
        f'<li data-status="{key}"><i></i>{label} <b>{status[key]:,}</b></li>'
        for key, label in STATUS
    )
    return (
        f'<h3>Files by their worst finding</h3><div class="status-bar" id="status-bar">'
        f'{parts}</div><ul class="status-legend">{legend}</ul>'
    )


def _rules(summary: dict[str, Any]) -> str:
    total = max(summary["files"], 1)
    rows = []
    for r in summary["rules"][:SHOWN_RULES]:
        width = 100 * r["files"] / total
        rank = RANK.get(r["severity"], 0)  # sorted descending: errors first
        rows.append(
            f'<tr data-code="{e(r["code"])}" data-findings="{r["findings"]}">'
            f"<td><code>{e(r['code'])}</code></td><td>{e(r['name'])}</td>"
            f'<td data-sort="{rank}">'
            f'<span class="sev" data-severity="{e(r["severity"])}">{e(r["severity"])}</span></td>'
            f'<td class="num">{r["findings"]:,}</td><td class="num" data-sort="{r["files"]}">'
            f'{r["files"]:,}<span class="meter"><span style="width:{width:.1f}%"></span>'
            "</span></td></tr>"
        )
    if not rows:
        body = '<p class="empty">No findings in these records.</p>'
    else:
        body = (
            '<div class="table-wrap scroll"><table id="rule-table" class="sortable"><thead><tr>'
            '<th>Code</th><th>Rule</th><th>Severity</th><th class="num">Findings</th>'
            f'<th class="num">Files</th></tr></thead><tbody>{"".join(rows)}</tbody></table></div>'
        )
    return (
        '<section class="card" id="rules"><h2>Rules</h2><p class="note">Most frequent first; '
        f"click a column to sort.</p>{body}</section>"
    )


def _cell(target: str, outcome: str, count: int, whole: int) -> str:
    share = count / whole if whole else 0
    style = ""
    if count:
        r, g, b = RGB[outcome]
        style = f' style="background: rgba({r}, {g}, {b}, {0.1 + 0.55 * share:.2f})"'
    pct = f'<span class="pct">{percent(count, whole)}</span>' if count else ""
    return (
        f'<td class="cell num" data-target="{e(target)}" data-outcome="{outcome}" '
        f'data-count="{count}"{style}>{count:,}{pct}</td>'
    )


def _matrix(summary: dict[str, Any]) -> str:
    found = summary["matrix"]
    if not found["targets"]:
        return (
            '<section class="card" id="matrix"><h2>Load matrix</h2><p class="note">These '
            "records have no load matrix: check with <code>--matrix</code>.</p></section>"
        )
    rows = []
    for t in found["targets"]:
        cells = "".join(_cell(t["target"], o, t[o], t["files"]) for o in OUTCOMES)
        bar = plots.stacked({o: t[o] for o in OUTCOMES}, key=t["target"])
        rows.append(
            f'<tr data-target="{e(t["target"])}"><th class="target" scope="row">'
            f'{e(t["label"])} <span class="muted mono">{e(t["target"])}</span></th>'
            f'{cells}<td class="num">{t["files"]:,}</td><td>{bar}</td></tr>'
        )
    heads = "".join(f'<th class="num">{HEADS[o]}</th>' for o in OUTCOMES)
    legend = "".join(
        f'<span><i style="background: {plots.OUTCOME_COLOURS[o]}"></i>{HEADS[o]}</span>'
        for o in OUTCOMES
    )
    return (
        '<section class="card" id="matrix"><h2>Load matrix</h2><p class="note">What each '
        "target is predicted to do with each model: files per outcome (a model with several "
        "problems counts under its worst).</p>"
        '<div class="table-wrap"><table id="matrix-table"><thead><tr><th>Target</th>'
        f'{heads}<th class="num">Files</th><th>Share</th></tr></thead><tbody>'
        f'{"".join(rows)}</tbody></table></div><div class="legend">{legend}</div>'
        + _engines(found)
        + "</section>"
    )


def _engines(found: dict[str, Any]) -> str:
    if not found["engines"]:
        return ""
    kinds = (*OUTCOMES, "not-installed")
    rows = "".join(
        f'<tr data-engine="{e(x["engine"])}"><th scope="row" class="mono">{e(x["engine"])}</th>'
        + "".join(_cell(x["engine"], o, x[o], x["files"]) for o in kinds)
        + f'<td class="num">{x["files"]:,}</td></tr>'
        for x in found["engines"]
    )
    heads = "".join(f'<th class="num">{HEADS[o]}</th>' for o in kinds)
    agree = "".join(
        f'<tr data-target="{e(a["target"])}"><th scope="row">{e(a["label"])}</th>'
        f'<td class="mono">{e(a["engine"])}</td><td class="num">{a["agree"]:,} of '
        f'{a["compared"]:,}</td><td class="num">{percent(a["agree"], a["compared"])}</td><td>'
        + ", ".join(
            f'predicted <span class="outcome" data-outcome="{e(d["predicted"])}">'
            f'{e(d["predicted"])}</span>, engine <span class="outcome" '
            f'data-outcome="{e(d["confirmed"])}">{e(d["confirmed"])}</span>: {d["files"]}'
            for d in a["disagreements"]
        )
        + "</td></tr>"
        for a in found["agreement"]
    )
    table = (
        '<h3>Agreement: predicted and confirmed</h3><div class="table-wrap">'
        '<table id="agreement-table"><thead><tr><th>Target</th><th>Engine</th>'
        '<th class="num">Agree</th><th class="num">Share</th><th>Disagreements</th></tr>'
        f"</thead><tbody>{agree}</tbody></table></div>"
    )
    return (
        '<h3 id="engines">Confirmed by the engines (<code>--confirm</code>)</h3>'
        '<div class="table-wrap"><table id="engine-table"><thead><tr><th>Engine</th>'
        f'{heads}<th class="num">Files</th></tr></thead><tbody>{rows}</tbody></table></div>'
        + (table if found["agreement"] else "")
    )


def _worst(summary: dict[str, Any]) -> str:
    labels = {t["target"]: t["label"] for t in summary["matrix"]["targets"]}
    rows = []
    for n, w in enumerate(summary["worst"], 1):
        blocked = "".join(
            f'<span class="outcome" data-outcome="{kind}" data-target="{e(t)}" '
            f'title="{e(labels.get(t, t))} {"refuses it" if kind == "refused" else "crashes"}">'
            f"{e(labels.get(t, t))}</span> "
            for kind in ("refused", "crashes")
            for t in w[kind]
        )
        codes = "".join(
            f'<span class="chip" data-severity="{e(c["severity"])}">{e(c["code"])}'
            f'<span class="times">&#215;{c["count"]}</span></span>'
            for c in w["codes"]
        )
        rows.append(
            f'<tr data-path="{e(w["path"])}" data-rank="{n}"><td class="num">{n}</td>'
            f'<td class="path">{path(w["path"])}</td><td data-sort="{w["blocked"]}">'
            f"{blocked or '<span class=muted>none</span>'}</td>"
            f'<td class="num">{w["errors"]:,}</td><td class="num">{w["warnings"]:,}</td>'
            f"<td>{codes}</td></tr>"
        )
    if not rows:
        body = '<p class="empty">No file has errors, warnings or a refusing target.</p>'
    else:
        body = (
            '<div class="table-wrap"><table id="worst-table" class="sortable"><thead><tr>'
            '<th class="num">#</th><th>Asset</th><th>Refused by / crashes</th>'
            '<th class="num">Errors</th><th class="num">Warnings</th><th>Top codes</th></tr>'
            f"</thead><tbody>{''.join(rows)}</tbody></table></div>"
        )
    return (
        f'<section class="card" id="worst"><h2>Worst assets</h2><p class="note">The '
        f"{len(summary['worst'])} files with the most targets refusing them (or crashing), "
        f"then the most errors, then warnings.</p>{body}</section>"
    )


def _figures(d: dict[str, Any]) -> str:
    def show(value: Any) -> str:
        return "&#8211;" if value is None else f"{value:,.4g}"

    return (
        f'<p class="figures"><span>n <b>{d["count"]:,}</b></span><span>min '
        f"<b>{show(d['min'])}</b></span><span>median <b>{show(d['median'])}</b></span>"
        f"<span>max <b>{show(d['max'])}</b></span></p>"
    )


def _distributions(summary: dict[str, Any]) -> str:
    d = summary["distributions"]
    cards = [
        ("mass", "Total mass", "kg", "Each model's mass; files without a model are left out."),
        ("links", "Links per model", "links", "How big the models are."),
        ("findings", "Findings per file", "findings", "All severities."),
    ]
    body = "".join(
        f'<div class="card" data-distribution="{key}" data-scale="{d[key]["scale"]}">'
        f'<h2>{title}</h2><p class="note">{note}'
        f"{' Logarithmic bins.' if d[key]['scale'] == 'log' else ''}</p>{_figures(d[key])}"
        + plots.histogram(d[key], key=key, title=title, unit=unit)
        + "</div>"
        for key, title, unit, note in cards
    )
    return f'<section id="distributions" class="plots" aria-label="Distributions">{body}</section>'
