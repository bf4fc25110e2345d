"""The summary of a dataset run as text (``urdflint report``'s default output)."""

from __future__ import annotations

from typing import Any

from urdflint.outputs.dataset.summary import NOT_INSTALLED, OUTCOMES

HEADS = {
    "loads": "LOADS",
    "changes": "CHANGES",
    "refused": "REFUSED",
    "crashes": "CRASHES",
    NOT_INSTALLED: "NOT INSTALLED",
}
BAR = 30  # the widest histogram bar, in characters
SHOWN = 20  # entries of a diff list shown (the JSON has them all)


def render(summary: dict[str, Any]) -> str:
    """The whole text report."""
    parts = [
        _files(summary),
        _severities(summary),
        _rules(summary),
        _matrix(summary),
        _worst(summary),
        _distributions(summary),
    ]
    if summary.get("diff"):
        parts.append(_diff(summary["diff"]))
    return "\n\n".join(p for p in parts if p) + "\n"


def plural(count: int, word: str) -> str:
    return f"{count} {word}{'' if count == 1 else 's'}"


def _percent(part: int, whole: int) -> str:
    return f"{100 * part / whole:5.1f} %" if whole else "      "


def table(rows: list[list[str]], right: set[int] | None = None) -> list[str]:
    """Rows as aligned columns (``right``: the columns aligned right), two spaces apart."""
    right = right or set()
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return [
        "  "
        + "  ".join(
            cell.rjust(widths[i]) if i in right else cell.ljust(widths[i])
            for i, cell in enumerate(row)
        ).rstrip()
        for row in rows
    ]


def _files(summary: dict[str, Any]) -> str:
    total, status = summary["files"], summary["status"]
    lines = [f"urdflint report: {plural(total, 'file')}"]
    names = [
        ("errors", "with errors"),
        ("warnings", "with warnings (no errors)"),
        ("infos", "with infos only"),
        ("clean", "clean"),
        ("unreadable", "unreadable"),
        ("crashed", "a rule crashed on"),
    ]
    rows = [[label, str(status[key]), _percent(status[key], total)] for key, label in names]
    lines += table(rows, {1, 2})
    for item in summary.get("unreadable", [])[:SHOWN]:
        lines.append(f"    unreadable: {item['error'] or item['path']}")
    for path in summary.get("crashed", [])[:SHOWN]:
        lines.append(f"    crashed: {path}")
    return "\n".join(lines)


def _severities(summary: dict[str, Any]) -> str:
    rows = [["SEVERITY", "FINDINGS", "FILES"]]
    rows += [[s["severity"], str(s["findings"]), str(s["files"])] for s in summary["severities"]]
    return "\n".join(["Findings by severity", *table(rows, {1, 2})])


def _rules(summary: dict[str, Any]) -> str:
    if not summary["rules"]:
        return "Rules: no findings"
    rows = [["CODE", "NAME", "SEVERITY", "FINDINGS", "FILES"]]
    rows += [
        [r["code"], r["name"], r["severity"], str(r["findings"]), str(r["files"])]
        for r in summary["rules"]
    ]
    return "\n".join(["Rules, most frequent first", *table(rows, {3, 4})])


def _matrix(summary: dict[str, Any]) -> str:
    found = summary["matrix"]
    if not found["targets"]:
        return "Load matrix: none in these records (check with --matrix)"
    rows = [["TARGET", *(HEADS[o] for o in OUTCOMES), "FILES"]]
    rows += [
        [t["label"], *(str(t[o]) for o in OUTCOMES), str(t["files"])] for t in found["targets"]
    ]
    lines = ["Load matrix (predicted: files per outcome)", *table(rows, {1, 2, 3, 4, 5})]
    lines.append(f"  {found['everywhere']} of {found['modelled']} models load on every target")
    if found["engines"]:
        heads = [*OUTCOMES, NOT_INSTALLED]
        rows = [["ENGINE", *(HEADS[o] for o in heads), "FILES"]]
        rows += [
            [e["engine"], *(str(e[o]) for o in heads), str(e["files"])] for e in found["engines"]
        ]
        lines += ["", "Confirmed by the engines (--confirm)", *table(rows, {1, 2, 3, 4, 5, 6})]
    for a in found["agreement"]:
        lines.append(
            f"  {a['label']} ({a['engine']}): predicted = confirmed for "
            f"{a['agree']} of {a['compared']}"
        )
        for d in a["disagreements"]:
            lines.append(
                f"    predicted {d['predicted']}, {a['engine']} {d['confirmed']}: "
                f"{plural(d['files'], 'file')}"
            )
    return "\n".join(lines)


def _worst(summary: dict[str, Any]) -> str:
    if not summary["worst"]:
        return "Worst assets: none (no errors, warnings or refusals)"
    lines = [f"Worst assets (top {len(summary['worst'])})"]
    for n, w in enumerate(summary["worst"], 1):
        blocked = ", ".join([*w["refused"], *(f"{t} (crashes)" for t in w["crashes"])])
        codes = " ".join(f"{c['code']}×{c['count']}" for c in w["codes"])
        lines.append(f"  {n:>3}. {w['path']}")
        lines.append(
            f"       {plural(w['errors'], 'error')}, {plural(w['warnings'], 'warning')}"
            + (f"; refused by {blocked}" if blocked else "")
            + (f"; top codes {codes}" if codes else "")
        )
    return "\n".join(lines)


def _number(value: Any) -> str:
    """A figure as read: whole numbers whole, others to four significant digits."""
    if value is None:
        return "-"
    if isinstance(value, int) or abs(value) >= 1e4:
        return f"{value:.0f}"
    return f"{value:.4g}"


def _distributions(summary: dict[str, Any]) -> str:
    lines = ["Distributions"]
    names = {"mass": "mass (kg)", "links": "links per model", "findings": "findings per file"}
    for key, title in names.items():
        d = summary["distributions"][key]
        scale = ", log bins" if d["scale"] == "log" else ""
        lines.append(
            f"  {title}: {d['count']} files, min {_number(d['min'])}, median "
            f"{_number(d['median'])}, max {_number(d['max'])}{scale}"
        )
        peak = max((b["count"] for b in d["bins"]), default=0)
        width = max((len(b["label"]) for b in d["bins"]), default=0)
        for b in d["bins"]:
            bar = "#" * (round(BAR * b["count"] / peak) if peak else 0)
            if b["count"] and not bar:
                bar = "."
            lines.append(f"    {b['label']:>{width}} | {bar} {b['count']}")
    return "\n".join(lines)


def _diff(diff: dict[str, Any]) -> str:
    f = diff["files"]
    lines = [
        f"Changes against the earlier run ({f['old']} -> {f['new']} files)",
        f"  added {f['added']}, removed {f['removed']}, worse {f['worse']}, "
        f"better {f['better']}, changed both ways {f['changed']}, same {f['same']}",
        f"  findings: {diff['new_findings']['count']} new, {diff['fixed_findings']['count']} fixed",
    ]
    for key in ("worse", "better", "changed"):
        if diff[key]:
            lines += ["", f"  {key}:"]
            lines += [f"    {_change(c)}" for c in diff[key][:SHOWN]]
            lines += _more(diff["files"][key])
    for key, title in (("up", "rules up"), ("down", "rules down")):
        if diff["rules"][key]:
            lines += ["", f"  {title}:"]
            lines += [
                f"    {r['code']} {r['name']}: {r['old']} -> {r['new']} ({r['delta']:+d})"
                for r in diff["rules"][key][:SHOWN]
            ]
    for key, title in (("new_findings", "new findings"), ("fixed_findings", "fixed findings")):
        items = diff[key]["items"]
        if items:
            lines += ["", f"  {title}:"]
            lines += [
                f"    {x['path']}:{x['line']}: {x['code']} {x['message']}" for x in items[:SHOWN]
            ]
            lines += _more(diff[key]["count"])
    return "\n".join(lines)


def _more(count: int) -> list[str]:
    return [f"    ... and {count - SHOWN} more (--format json lists them)"] if count > SHOWN else []


def _change(c: dict[str, Any]) -> str:
    parts = [
        f"errors {c['errors'][0]} -> {c['errors'][1]}",
        f"warnings {c['warnings'][0]} -> {c['warnings'][1]}",
    ]
    parts += [f"{t} {a} -> {b}" for t, (a, b) in c["targets"].items()]
    if c["unreadable"][0] != c["unreadable"][1]:
        parts.append("now unreadable" if c["unreadable"][1] else "readable again")
    if c["crashed"][0] != c["crashed"][1]:
        parts.append("a rule now crashes" if c["crashed"][1] else "no crash any more")
    return f"{c['path']}: " + ", ".join(parts)
