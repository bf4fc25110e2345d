"""The dataset report page's stylesheet and its one small script (table sorting), inline.

The palette is the web page's (``server/static/app.css``); no font, image or script is
fetched: the page opens offline and prints.
"""

from __future__ import annotations

CSS = """
:root {
  --ink: #1d2939; --muted: #667085; --line: #e4e7ec; --paper: #ffffff; --page: #f6f7f9;
  --accent: #3e4fd8; --accent-ink: #2f3cb3;
  --error: #d92d20; --error-bg: #fef3f2; --error-ink: #b42318;
  --warning: #dc6803; --warning-bg: #fffaeb; --warning-ink: #b54708;
  --info: #1570ef; --info-bg: #eff8ff; --info-ink: #175cd3;
  --pass: #079455; --pass-bg: #ecfdf3; --pass-ink: #067647;
  --radius: 10px;
  --mono: ui-monospace, SFMono-Regular, Menlo, Consolas, "Liberation Mono", monospace;
  color-scheme: light;
}
* { box-sizing: border-box; }
html { font-size: 15px; }
body { margin: 0; background: var(--page); color: var(--ink); line-height: 1.5;
  font-family: system-ui, -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif; }
code, .mono { font-family: var(--mono); font-size: 0.86em; }
.muted { color: var(--muted); }
.wrap { max-width: 1320px; margin: 0 auto; padding: 0 1.5rem 2rem; }
.top { background: #101828; color: #f2f4f7; }
.top .wrap { display: flex; align-items: center; justify-content: space-between;
  height: 3.25rem; padding-bottom: 0; }
.brand { margin: 0; font-weight: 700; font-size: 1.1rem; letter-spacing: 0.01em; }
.logo { color: #8098f9; }
.top .sources { color: #98a2b3; font-family: var(--mono); font-size: 0.82rem;
  overflow: hidden; text-overflow: ellipsis; white-space: nowrap; max-width: 60%; }
h1 { font-size: 1.6rem; margin: 1.6rem 0 0.2rem; letter-spacing: -0.01em; }
h2 { font-size: 1.08rem; margin: 0 0 0.2rem; }
h3 { font-size: 0.95rem; margin: 1rem 0 0.4rem; }
.lead { margin: 0 0 1.25rem; color: #475467; }
.card { background: var(--paper); border: 1px solid var(--line); border-radius: var(--radius);
  padding: 1.15rem 1.35rem; box-shadow: 0 1px 2px rgba(16, 24, 40, 0.04);
  margin-bottom: 1.25rem; min-width: 0; }
.card > .note { margin: 0 0 0.85rem; color: var(--muted); font-size: 0.9rem; }
.stats { display: grid; grid-template-columns: repeat(auto-fit, minmax(7.6rem, 1fr));
  gap: 0.75rem; margin-bottom: 1.25rem; }
.stat { background: var(--paper); border: 1px solid var(--line); border-radius: var(--radius);
  padding: 0.8rem 1rem; box-shadow: 0 1px 2px rgba(16, 24, 40, 0.04);
  border-top: 3px solid #d0d5dd; }
.stat .value { display: block; font-size: 1.7rem; font-weight: 700; line-height: 1.2;
  font-variant-numeric: tabular-nums; }
.stat .label { display: block; font-size: 0.85rem; color: #475467; }
.stat .share { font-size: 0.8rem; color: var(--muted); }
.stat[data-stat="errors"] { border-top-color: var(--error); }
.stat[data-stat="errors"] .value { color: var(--error-ink); }
.stat[data-stat="warnings"] { border-top-color: var(--warning); }
.stat[data-stat="warnings"] .value { color: var(--warning-ink); }
.stat[data-stat="infos"] { border-top-color: var(--info); }
.stat[data-stat="clean"], .stat[data-stat="everywhere"] { border-top-color: var(--pass); }
.stat[data-stat="clean"] .value, .stat[data-stat="everywhere"] .value { color: var(--pass-ink); }
.stat[data-stat="files"] { border-top-color: var(--accent); }
.columns { display: grid; grid-template-columns: minmax(0, 1fr) minmax(0, 2fr); gap: 1.25rem; }
.plots { display: grid; grid-template-columns: repeat(3, minmax(0, 1fr)); gap: 1.25rem;
  margin-bottom: 1.25rem; }
.plots .card { margin: 0; }
.plots svg.plot { width: 100%; height: auto; display: block; margin-top: 0.4rem; }
.figures { display: flex; gap: 1rem; flex-wrap: wrap; font-size: 0.85rem; color: #475467;
  margin: 0.1rem 0 0; }
.figures b { color: var(--ink); font-variant-numeric: tabular-nums; }
.table-wrap { overflow-x: auto; }
table { border-collapse: collapse; width: 100%; font-size: 0.9rem; }
th, td { text-align: left; vertical-align: middle; padding: 0.45rem 0.7rem;
  border-bottom: 1px solid var(--line); }
thead th { font-size: 0.76rem; text-transform: uppercase; letter-spacing: 0.04em;
  color: var(--muted); font-weight: 600; background: #f9fafb; white-space: nowrap; }
tbody tr:hover td { background: #fcfcfd; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
table.sortable thead th { cursor: pointer; user-select: none; }
table.sortable thead th[aria-sort="ascending"]::after { content: " \\25B2"; font-size: 0.7em; }
table.sortable thead th[aria-sort="descending"]::after { content: " \\25BC"; font-size: 0.7em; }
.scroll { max-height: 31rem; overflow-y: auto; scrollbar-width: thin; }
.status-bar { display: flex; height: 0.9rem; border-radius: 999px; overflow: hidden;
  background: #f2f4f7; margin: 0.2rem 0 0.6rem; }
.status-bar .seg { display: block; height: 100%; }
.seg[data-status="errors"], .status-legend [data-status="errors"] i { background: var(--error); }
.seg[data-status="warnings"], .status-legend [data-status="warnings"] i {
  background: var(--warning); }
.seg[data-status="infos"], .status-legend [data-status="infos"] i { background: var(--info); }
.seg[data-status="clean"], .status-legend [data-status="clean"] i { background: var(--pass); }
.seg[data-status="unreadable"], .status-legend [data-status="unreadable"] i {
  background: #98a2b3; }
.status-legend { list-style: none; margin: 0; padding: 0; display: grid;
  grid-template-columns: repeat(2, minmax(0, 1fr)); gap: 0.2rem 1rem; font-size: 0.86rem;
  color: #475467; }
.status-legend i { display: inline-block; width: 0.7rem; height: 0.7rem; border-radius: 2px;
  margin-right: 0.4rem; vertical-align: -0.05rem; }
.status-legend b { color: var(--ink); font-variant-numeric: tabular-nums; }
.scroll thead th { position: sticky; top: 0; z-index: 1; }
.path { font-family: var(--mono); font-size: 0.83rem; overflow-wrap: break-word; }
.sev, .chip, .outcome { display: inline-block; border-radius: 999px; padding: 0 0.55rem;
  font-size: 0.76rem; font-weight: 600; white-space: nowrap; border: 1px solid var(--line);
  color: var(--muted); background: #f9fafb; }
.sev[data-severity="error"], .chip[data-severity="error"] { color: var(--error-ink);
  background: var(--error-bg); border-color: #fecdca; }
.sev[data-severity="warning"], .chip[data-severity="warning"] { color: var(--warning-ink);
  background: var(--warning-bg); border-color: #fedf89; }
.sev[data-severity="info"], .chip[data-severity="info"] { color: var(--info-ink);
  background: var(--info-bg); border-color: #b2ddff; }
.chip { font-family: var(--mono); margin: 0.1rem 0.2rem 0.1rem 0; }
.chip .times { font-weight: 400; opacity: 0.8; }
.outcome[data-outcome="loads"] { color: var(--pass-ink); background: var(--pass-bg);
  border-color: #abefc6; }
.outcome[data-outcome="changes"] { color: var(--warning-ink); background: var(--warning-bg);
  border-color: #fedf89; }
.outcome[data-outcome="refused"], .outcome[data-outcome="crashes"] { color: var(--error-ink);
  background: var(--error-bg); border-color: #fda29b; }
.outcome[data-outcome="crashes"] { border-style: dashed; }
.meter { display: inline-block; width: 5rem; height: 0.45rem; border-radius: 999px;
  background: #f2f4f7; vertical-align: middle; margin-left: 0.5rem; overflow: hidden; }
.meter > span { display: block; height: 100%; background: #8098f9; border-radius: 999px; }
#matrix-table td.cell { text-align: right; font-weight: 600; font-variant-numeric: tabular-nums;
  min-width: 6.5rem; }
#matrix-table td.cell[data-count="0"] { color: #c0c5cf; font-weight: 400; }
#matrix-table td.cell .pct { font-weight: 400; font-size: 0.78rem; color: #475467;
  margin-left: 0.3rem; }
#matrix-table th.target { white-space: nowrap; }
.legend { display: flex; gap: 1rem; flex-wrap: wrap; font-size: 0.82rem; color: #475467;
  margin-top: 0.6rem; }
.legend i { display: inline-block; width: 0.7rem; height: 0.7rem; border-radius: 2px;
  margin-right: 0.3rem; vertical-align: -0.05rem; }
.delta { white-space: nowrap; }
.delta-up { color: var(--error-ink); font-weight: 600; }
.delta-same { color: #475467; font-weight: 600; }
.move { display: inline-block; white-space: nowrap; margin: 0.1rem 0.6rem 0.1rem 0; }
.delta-down { color: var(--pass-ink); font-weight: 600; }
.arrow { color: var(--muted); padding: 0 0.25rem; }
.empty { color: var(--pass-ink); background: var(--pass-bg); border-radius: 8px;
  padding: 0.6rem 0.9rem; margin: 0; }
.more { color: var(--muted); font-size: 0.85rem; margin: 0.5rem 0 0; }
footer { color: var(--muted); font-size: 0.82rem; padding-top: 0.5rem; }
@media (max-width: 980px) {
  .columns, .plots { grid-template-columns: minmax(0, 1fr); }
}
@media print {
  body { background: #ffffff; }
  .card, .stat { box-shadow: none; break-inside: avoid; }
  .scroll { max-height: none; overflow: visible; }
}
"""

# Click a column head of a table.sortable: its rows sorted by that column (numbers as
# numbers, from a cell's data-sort when it has one), again for the other direction.
SCRIPT = """
(function () {
  'use strict';
  function key(cell) {
    var raw = cell.hasAttribute('data-sort') ? cell.getAttribute('data-sort') : cell.textContent;
    var text = raw.trim();
    var number = parseFloat(text.replace(/,/g, ''));
    return isNaN(number) || !/^-?[\\d.,]+/.test(text) ? text.toLowerCase() : number;
  }
  document.querySelectorAll('table.sortable').forEach(function (table) {
    var heads = table.querySelectorAll('thead th');
    heads.forEach(function (th, column) {
      th.addEventListener('click', function () {
        var descending = th.getAttribute('aria-sort') !== 'descending';
        heads.forEach(function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', descending ? 'descending' : 'ascending');
        var body = table.tBodies[0];
        var rows = Array.prototype.slice.call(body.rows);
        rows.sort(function (a, b) {
          var x = key(a.cells[column]), y = key(b.cells[column]);
          var order = typeof x === typeof y ? (x < y ? -1 : x > y ? 1 : 0)
            : (typeof x === 'number' ? -1 : 1);
          return descending ? -order : order;
        });
        rows.forEach(function (row) { body.appendChild(row); });
      });
    });
  });
})();
"""
