#!/usr/bin/env python3
"""How often a defect planted in a xacro macro is reported at the file:line that wrote it.

    .venv/bin/python bench/xacro_accuracy.py [--workspace DIR] [--jobs N] [--json FILE] [-v]

For every entry file of a workspace of ROS packages (default: fixtures/packages), the
script finds the macro files the entry expands, and in them every ``<xacro:macro>``
whose body writes a ``<link>``, ``<joint>``, ``<inertial>``, ``<axis>`` or ``<limit>``.
In each such macro it plants one defect at a time, in a private copy of the workspace,
lints the entry with only the rule under test, and sorts the outcome:

- ``right``: the one new finding is at the macro file and the line of the planted element;
- ``dup``: found at the right file:line, but more than once (per-instance findings
  that were not merged into one);
- ``elsewhere``: new findings of that code, none at the right file:line;
- ``missed``: no new finding;
- ``broken``: the planted copy no longer expands (X010).

``trace_ok`` counts findings whose outermost macro call is in the entry's package,
``count_ok`` those that name as many instances ("(for links a, b)") as the probe saw.

Defects (one site per macro and kind: the first element of the body that the expansion
keeps, in a place where the rule applies):

- I002 ``<mass value="-1">``; I005 ``<inertia>`` 1, 1, 5 (triangle inequality);
- J007 ``<axis xyz="0 0 0">`` on a moving joint; J009 ``<limit lower="1" upper="-1">``;
- X007 ``<collision>``/``<inertial>``/``<visual>`` misspelt (``<colision>``...);
- G001 ``<gazebo reference="${prefix}no_such_link"/>`` added at the start of the body.

Which sites the expansion keeps (a macro may never be called, an element may sit in a
false ``xacro:if``) is learnt from one probe expansion per entry in which every
candidate carries a marker attribute; the probe reads the expanded document only, not
urdflint's source map, so it does not depend on what is measured. Sites whose element
is not expanded, or not where the rule applies, are counted as ``n/a`` and not planted.

Each (file, macro, kind) is planted once, with the first entry that expands it
(``--all-entries``: with every such entry). Runs in a few minutes on the 72 xacro entries
of /work/realpkgs/ws/src with two processes.

Entries: ``entries.json`` in the workspace or up to two folders above it (a list of
``{"entry": "pkg/path/in/package.xacro", "args": {...}}``, paths relative to the
workspace; /work/realpkgs/entries.json has that shape); without one, every ``*.xacro``
that expands to a robot with links without arguments.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import sys
import tempfile
import time
from collections import Counter, defaultdict
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from lxml import etree  # noqa: E402

from urdflint.engine import config, linter  # noqa: E402
from urdflint.engine.context import Context  # noqa: E402

DEFAULT_WORKSPACE = ROOT / "fixtures" / "packages"
KINDS = ("I002", "I005", "J007", "J009", "X007", "G001")
WHAT = {
    "I002": "negative mass",
    "I005": "inertia 1/1/5",
    "J007": "zero axis",
    "J009": "lower > upper",
    "X007": "misspelt element",
    "G001": "dangling gazebo ref",
}
MARK = "urdflint_plant"
MOVING = {"revolute", "continuous", "prismatic", "planar"}
BOUNDED = {"revolute", "prismatic"}
MISSPELT = {"collision": "colision", "inertial": "inertail", "visual": "visaul"}
TARGETS = {
    "I002": ("mass",),
    "I005": ("inertia",),
    "J007": ("axis",),
    "J009": ("limit",),
    "X007": ("collision", "inertial", "visual"),
}
BODY_RE = re.compile(r"<(?:link|joint|inertial|axis|limit)[\s/>]")
MACRO_TAG_RE = re.compile(r"<(/?)xacro:macro(?=[\s/>])")
COMMENT_RE = re.compile(r"<!--.*?-->|<!\[CDATA\[.*?\]\]>", re.S)
QUOTED_RE = re.compile(r"'[^']*'|\"[^\"]*\"")
PARAM_RE = re.compile(r"(?:^|\s)(\*{0,2})([A-Za-z_][\w]*)")


# -- finding sites in the text ------------------------------------------------------------


def tag_end(text: str, start: int) -> int:
    """Index just past the ``>`` that ends the tag starting at ``start`` (quotes respected)."""
    quote = None
    for i in range(start + 1, len(text)):
        c = text[i]
        if quote:
            if c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == ">":
            return i + 1
    raise ValueError("unterminated tag")


@dataclass
class Macro:
    name: str
    start: int  # the '<' of <xacro:macro
    body: int  # just past the start tag
    end: int  # the '<' of </xacro:macro>
    params: str


@dataclass(frozen=True)
class Site:
    """One planting place: ``kind`` at the element (or insertion point) ``offset`` of ``file``."""

    file: str  # relative to the workspace
    macro: str
    kind: str
    offset: int
    line: int
    tag: str  # the element planted on ('' for the G001 insertion)
    ident: int = 0  # the probe marker

    def label(self) -> str:
        return f"{self.file}:{self.line} <{self.tag or 'gazebo'}> in macro {self.macro}"


def comment_spans(text: str) -> list[tuple[int, int]]:
    return [m.span() for m in COMMENT_RE.finditer(text)]


def in_spans(spans: list[tuple[int, int]], i: int) -> bool:
    return any(a <= i < b for a, b in spans)


def macros(text: str) -> list[Macro]:
    """The ``<xacro:macro>`` definitions of a file, nested ones included."""
    spans = comment_spans(text)
    stack: list[Macro] = []
    found: list[Macro] = []
    for m in MACRO_TAG_RE.finditer(text):
        if in_spans(spans, m.start()):
            continue
        if m.group(1):  # </xacro:macro>
            if stack:
                macro = stack.pop()
                macro.end = m.start()
                found.append(macro)
            continue
        end = tag_end(text, m.start())
        tag = text[m.start() : end]
        name = re.search(r"\sname\s*=\s*([\"'])(.*?)\1", tag, re.S)
        params = re.search(r"\sparams\s*=\s*([\"'])(.*?)\1", tag, re.S)
        macro = Macro(
            name.group(2) if name else "?", m.start(), end, -1, params.group(2) if params else ""
        )
        if tag.rstrip(">").rstrip().endswith("/"):
            continue  # an empty macro
        stack.append(macro)
    return sorted(found, key=lambda m: m.start)


def prefix_param(params: str) -> str | None:
    """The macro parameter a link name is built from, for a ``${prefix}no_such_link``."""
    names = [n for star, n in PARAM_RE.findall(QUOTED_RE.sub("", params)) if not star]
    for want in ("prefix", "name", "side", "suffix", "parent"):
        for name in names:
            if want in name.lower():
                return name
    return None


def candidate_sites(rel: str, text: str) -> list[Site]:
    """Every place a defect can be planted in the macros of one file, in text order."""
    spans = comment_spans(text)
    defined = macros(text)
    sites: list[Site] = []

    def owner(i: int) -> Macro | None:
        inside = [m for m in defined if m.body <= i < m.end]
        return max(inside, key=lambda m: m.body) if inside else None

    def line(i: int) -> int:
        return text.count("\n", 0, i) + 1

    for macro in defined:
        body = text[macro.body : macro.end]
        if not BODY_RE.search(COMMENT_RE.sub("", body)):
            continue
        sites.append(Site(rel, macro.name, "G001", macro.body, line(macro.body), ""))
        for kind, tags in TARGETS.items():
            pattern = re.compile(r"<({})(?=[\s/>])".format("|".join(tags)))
            for m in pattern.finditer(text, macro.body, macro.end):
                if in_spans(spans, m.start()) or owner(m.start()) is not macro:
                    continue
                sites.append(Site(rel, macro.name, kind, m.start(), line(m.start()), m.group(1)))
    return sites


# -- edits ---------------------------------------------------------------------------------


def set_attr(tag: str, name: str, value: str) -> str:
    """``tag`` (a start tag's text) with attribute ``name`` set to ``value``, lines kept."""
    pattern = re.compile(rf"(\s{re.escape(name)}\s*=\s*)([\"'])(.*?)\2", re.S)
    if pattern.search(tag):
        return pattern.sub(lambda m: m.group(1) + m.group(2) + value + m.group(2), tag, count=1)
    cut = len(tag) - (2 if tag.endswith("/>") else 1)
    return f'{tag[:cut].rstrip()} {name}="{value}"{tag[cut:]}'


def plant(text: str, site: Site, params: str = "", marker: bool = False) -> str:
    """``text`` with the defect of ``site`` planted (or, with ``marker``, only marked)."""
    mark = f' {MARK}="{site.ident}"' if marker else ""
    if site.kind == "G001":
        prefix = prefix_param(params)
        ref = (f"${{{prefix}}}" if prefix else "") + "no_such_link"
        return text[: site.offset] + f'<gazebo reference="{ref}"{mark}/>' + text[site.offset :]
    end = tag_end(text, site.offset)
    tag = text[site.offset : end]
    if marker:
        new = set_attr(tag, MARK, str(site.ident))
        return text[: site.offset] + new + text[end:]
    if site.kind == "I002":
        new = set_attr(tag, "value", "-1")
    elif site.kind == "I005":
        new = tag
        for attr, value in (
            ("ixx", "1"),
            ("iyy", "1"),
            ("izz", "5"),
            ("ixy", "0"),
            ("ixz", "0"),
            ("iyz", "0"),
        ):
            new = set_attr(new, attr, value)
    elif site.kind == "J007":
        new = set_attr(tag, "xyz", "0 0 0")
    elif site.kind == "J009":
        new = set_attr(set_attr(tag, "lower", "1"), "upper", "-1")
    elif site.kind == "X007":
        wrong = MISSPELT[site.tag]
        new = "<" + wrong + tag[1 + len(site.tag) :]
        if not tag.endswith("/>"):
            close = text.find(f"</{site.tag}>", end)
            after = text[end:close] + f"</{wrong}>" + text[close + len(site.tag) + 3 :]
            return text[: site.offset] + new + after
    else:
        raise ValueError(site.kind)
    return text[: site.offset] + new + text[end:]


def plant_all(text: str, sites: list[Site], params: dict[int, str]) -> str:
    """Every site of one file marked (from the end, so offsets stay valid)."""
    for site in sorted(sites, key=lambda s: (s.offset, s.kind != "G001"), reverse=True):
        text = plant(text, site, params.get(site.ident, ""), marker=True)
    return text


def applicable(el: etree._Element, kind: str, root: etree._Element) -> bool:
    """Whether the rule of ``kind`` looks at the expanded element ``el``."""
    parent = el.getparent()
    if kind == "G001":
        return parent is root
    if kind == "X007":
        return parent is not None and parent.tag == "link" and parent.getparent() is root
    if kind in ("I002", "I005"):
        link = parent.getparent() if parent is not None else None
        return (
            parent.tag == "inertial"
            and link is not None
            and link.tag == "link"
            and link.getparent() is root
        )
    if kind in ("J007", "J009"):
        if parent is None or parent.tag != "joint" or parent.getparent() is not root:
            return False
        return parent.get("type") in (MOVING if kind == "J007" else BOUNDED)
    return False


# -- linting -------------------------------------------------------------------------------


def package_paths(workspace: Path) -> dict[str, Path]:
    found: dict[str, Path] = {}
    for xml in sorted(workspace.rglob("package.xml")):
        try:
            name = (etree.parse(str(xml)).findtext("name") or "").strip()
        except etree.XMLSyntaxError:
            continue
        if name and name not in found:
            found[name] = xml.parent
    return found


def lint(workspace: Path, entry: str, args: dict[str, str], select: tuple[str, ...] | None):
    settings = config.Settings(select=select, xacro_args=dict(args))
    context = Context(package_paths=package_paths_cached(workspace), environ={})
    return linter.lint_path(workspace / entry, entry, settings, context)


_PATHS: dict[Path, dict[str, Path]] = {}


def package_paths_cached(workspace: Path) -> dict[str, Path]:
    if workspace not in _PATHS:
        _PATHS[workspace] = package_paths(workspace)
    return _PATHS[workspace]


def merged(message: str) -> int:
    """How many instances of a macro line a finding stands for, from its message."""
    named = re.search(r" \(for (?:\w+ )?(.*?)(?: and (\d+) more)?\)$", message)
    if named:
        return len(named.group(1).split(", ")) + int(named.group(2) or 0)
    counted = re.search(r" \((\d+) instances of this macro line\)$", message)
    return int(counted.group(1)) if counted else 1


def key(f) -> tuple:
    return (f.code, f.path, f.line, f.column, f.message)


# -- the worker ----------------------------------------------------------------------------

WORK: Path | None = None


def init_worker(workspace: str) -> None:
    """Each worker plants in its own copy of the workspace."""
    global WORK
    tmp = Path(tempfile.mkdtemp(prefix="xacro_accuracy_"))
    WORK = tmp / "ws"
    shutil.copytree(workspace, WORK, symlinks=True)
    import atexit

    atexit.register(shutil.rmtree, tmp, ignore_errors=True)


@dataclass
class EntryReport:
    entry: str
    args: dict[str, str]
    error: str | None = None
    findings: int = 0  # every rule, before planting
    baseline: list[tuple] = field(default_factory=list)  # findings of the planted kinds
    files: list[str] = field(default_factory=list)
    # site, G001 macro params, instances, instances one merged finding stands for
    sites: list[tuple[Site, str, int, int]] = field(default_factory=list)
    candidates: list[tuple[str, str, str]] = field(default_factory=list)  # (file, macro, kind)
    shared: int = 0  # live sites already planted with an earlier entry
    seconds: float = 0.0


def survey(entry: str, args: dict[str, str]) -> EntryReport:
    """Baseline lint, the macro files reached, and which candidate sites are live."""
    assert WORK is not None
    started = time.perf_counter()
    report = EntryReport(entry, args)
    result = lint(WORK, entry, args, None)
    bad = [f for f in result.findings if f.code in ("X010", "X011")]
    doc = result.document
    if bad or doc is None or not doc.ok or doc.origin is None:
        report.error = bad[0].message if bad else "not expanded"
        return report
    report.findings = len(result.findings)
    report.baseline = [key(f) for f in result.findings if f.code in KINDS]
    files = [Path(f.path) for f in doc.origin.files]
    rels = []
    for full in files:
        try:
            rels.append(full.resolve().relative_to(WORK.resolve()).as_posix())
        except ValueError:
            continue
    report.files = rels
    # candidates in every file, then one probe expansion with all of them marked
    candidates: dict[str, list[Site]] = {}
    params: dict[int, str] = {}
    ident = 0
    texts: dict[str, str] = {}
    for rel in rels:
        text = (WORK / rel).read_text(encoding="utf-8")
        texts[rel] = text
        found = []
        defined = {m.body: m for m in macros(text)}
        for site in candidate_sites(rel, text):
            ident += 1
            site = Site(**{**asdict(site), "ident": ident})
            found.append(site)
            if site.kind == "G001":
                params[ident] = defined[site.offset].params
        candidates[rel] = found
    live = probe(entry, args, texts, candidates, params)
    if live is None:  # the probe broke the expansion: try the kinds one at a time
        live = {}
        for kind in KINDS:
            only = {r: [s for s in c if s.kind == kind] for r, c in candidates.items()}
            live.update(probe(entry, args, texts, only, params) or {})
    chosen: dict[tuple[str, str, str], Site] = {}
    for rel, sites in candidates.items():
        for site in sites:
            macro_key = (rel, site.macro, site.kind)
            state = live.get(site.ident)
            if state is None or not state[1]:
                continue
            if macro_key not in chosen:
                chosen[macro_key] = site
    report.candidates = sorted({(s.file, s.macro, s.kind) for c in candidates.values() for s in c})
    for site in sorted(chosen.values(), key=lambda s: (s.file, s.offset, s.kind)):
        count, _, expected = live[site.ident]
        report.sites.append((site, params.get(site.ident, ""), count, expected))
    report.seconds = time.perf_counter() - started
    return report


def instance_name(el: etree._Element) -> str | None:
    """The name a merged finding gives this instance: the nearest named element's name."""
    node: etree._Element | None = el
    while node is not None:
        name = node.get("reference") if node.tag == "gazebo" else node.get("name")
        if name is not None and node.tag in ("link", "joint", "gazebo"):
            return name
        node = node.getparent()
    return None


def probe(entry, args, texts, candidates, params) -> dict[int, tuple[int, bool, int]] | None:
    """ident -> (instances in the expanded document, all of them where the rule applies,
    how many instances one merged finding should stand for)."""
    assert WORK is not None
    try:
        for rel, sites in candidates.items():
            if sites:
                (WORK / rel).write_text(plant_all(texts[rel], sites, params), encoding="utf-8")
        result = lint(WORK, entry, args, ("X010",))
    finally:
        for rel in candidates:
            (WORK / rel).write_text(texts[rel], encoding="utf-8")
    doc = result.document
    if doc is None or not doc.ok:
        return None
    kinds = {s.ident: s.kind for sites in candidates.values() for s in sites}
    seen: dict[int, tuple[int, bool]] = {}
    names: dict[int, set[str]] = defaultdict(set)
    for el in doc.robot.iter():
        if not isinstance(el.tag, str) or el.get(MARK) is None:
            continue
        ident = int(el.get(MARK))
        count, ok = seen.get(ident, (0, True))
        seen[ident] = (count + 1, ok and applicable(el, kinds[ident], doc.robot))
        name = instance_name(el)
        if name is not None:
            names[ident].add(name)
    # instances.merge names the distinct instances, or counts them when fewer than two
    return {
        ident: (count, ok, len(names[ident]) if len(names[ident]) >= 2 else count)
        for ident, (count, ok) in seen.items()
    }


@dataclass
class Outcome:
    report: int  # index of the entry run
    entry: str
    site: Site
    instances: int
    verdict: str  # right, dup, elsewhere, missed, broken
    trace_ok: bool
    count_ok: bool  # the finding names as many instances as the expansion wrote
    found: list[dict]  # the new findings
    seconds: float


def run_plant(
    report: int,
    entry: str,
    args: dict[str, str],
    site: Site,
    params: str,
    instances: int,
    expected: int,
    baseline: list[tuple],
) -> Outcome:
    assert WORK is not None
    started = time.perf_counter()
    path = WORK / site.file
    text = path.read_text(encoding="utf-8")
    try:
        path.write_text(plant(text, site, params), encoding="utf-8")
        result = lint(WORK, entry, args, (site.kind, "X010"))
    finally:
        path.write_text(text, encoding="utf-8")
    before = Counter(tuple(b) for b in baseline)
    new = []
    for f in result.findings:
        k = key(f)
        if before[k]:
            before[k] -= 1
        else:
            new.append(f)
    found = [
        {
            **{
                k: v
                for k, v in f.to_dict().items()
                if k in ("code", "path", "line", "column", "message")
            },
            "trace": [str(c) for c in f.trace],
        }
        for f in new
    ]
    if any(f.code == "X010" for f in new):
        verdict = "broken"
    else:
        new = [f for f in new if f.code == site.kind]
        here = [f for f in new if f.path == site.file and f.line == site.line]
        verdict = "right" if len(here) == 1 else "dup" if here else "elsewhere" if new else "missed"
    trace_ok = count_ok = False
    if verdict in ("right", "dup"):
        outer = here[0].trace[-1].path if here[0].trace else None
        trace_ok = outer is not None and outer.split("/")[0] == entry.split("/")[0]
        count_ok = sum(merged(f.message) for f in here) == expected
    seconds = time.perf_counter() - started
    return Outcome(report, entry, site, instances, verdict, trace_ok, count_ok, found, seconds)


# -- entries and the report ----------------------------------------------------------------


def find_entries(workspace: Path) -> list[tuple[str, dict[str, str]]]:
    for folder in (workspace, workspace.parent, workspace.parent.parent):
        listed = folder / "entries.json"
        if listed.is_file():
            data = json.loads(listed.read_text(encoding="utf-8"))
            out = []
            for item in data:
                entry = item["entry"]
                if entry.endswith(".xacro") and (workspace / entry).is_file():
                    out.append((entry, {k: str(v) for k, v in item.get("args", {}).items()}))
            return out
    found: list[tuple[str, dict[str, str]]] = []
    for path in sorted(workspace.rglob("*.xacro")):
        head = path.read_text(encoding="utf-8", errors="replace")
        if "<robot" not in head:
            continue
        rel = path.relative_to(workspace).as_posix()
        result = lint(workspace, rel, {}, ("X010", "X011"))
        doc = result.document
        if not result.findings and doc is not None and doc.ok and doc.links:
            found.append((rel, {}))
    return found


def args_text(args: dict[str, str]) -> str:
    return " ".join(f"{k}:={v}" for k, v in args.items())


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--workspace", type=Path, default=DEFAULT_WORKSPACE)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--json", type=Path, help="write every outcome to this file")
    parser.add_argument(
        "--all-entries",
        action="store_true",
        help="plant a macro's defect once per entry that expands it (default: once, with the"
        " first entry)",
    )
    parser.add_argument("-v", "--verbose", action="store_true", help="list every miss")
    opts = parser.parse_args()
    workspace = opts.workspace.resolve()
    started = time.perf_counter()
    entries = find_entries(workspace)
    print(f"workspace {workspace}: {len(entries)} xacro entries", flush=True)

    with ProcessPoolExecutor(
        opts.jobs, initializer=init_worker, initargs=(str(workspace),)
    ) as pool:
        reports = list(pool.map(survey, *zip(*entries, strict=False)))
        tasks = []
        planted: set[tuple[str, str, str]] = set()
        for i, r in enumerate(reports):
            for s, p, n, expected in r.sites:
                where = (s.file, s.macro, s.kind)
                if where in planted and not opts.all_entries:
                    r.shared += 1
                    continue
                planted.add(where)
                tasks.append((i, r.entry, r.args, s, p, n, expected, r.baseline))
        outcomes: list[Outcome] = (
            list(pool.map(run_plant, *zip(*tasks, strict=False), chunksize=4)) if tasks else []
        )

    # per kind
    table: dict[str, Counter] = defaultdict(Counter)
    for o in outcomes:
        table[o.site.kind][o.verdict] += 1
        table[o.site.kind]["planted"] += 1
        table[o.site.kind]["multi"] += o.instances > 1
        table[o.site.kind]["trace_ok"] += o.trace_ok
        table[o.site.kind]["count_ok"] += o.count_ok
    every = {c for r in reports for c in r.candidates}
    for _, _, kind in every - planted:
        table[kind]["n/a"] += 1
    cols = (
        "planted",
        "right",
        "dup",
        "elsewhere",
        "missed",
        "broken",
        "trace_ok",
        "count_ok",
        "multi",
        "n/a",
    )
    print()
    print(f"{'defect':<26}" + "".join(f"{c:>10}" for c in cols))
    total: Counter[str] = Counter()
    for kind in KINDS:
        row = table[kind]
        total.update(row)
        print(f"{kind + ' ' + WHAT[kind]:<26}" + "".join(f"{row[c]:>10}" for c in cols))
    print(f"{'all':<26}" + "".join(f"{total[c]:>10}" for c in cols))
    share = 100.0 * total["right"] / total["planted"] if total["planted"] else 0.0
    print(
        f"\nreported exactly once at the right file:line: {total['right']}/{total['planted']}"
        f" = {share:.1f}%"
    )
    print(
        "dup: at the right file:line but more than once; trace_ok: the outermost call is in the"
        " entry's package;\ncount_ok: the finding names as many instances as the expansion"
        " wrote; multi: the planted line is expanded more than once;\nn/a: macro and kind"
        " without an element the expansion keeps where the rule applies (not planted)"
    )

    # per entry
    print(
        f"\n{'entry':<78}{'args':<28}{'findings':>10}{'files':>7}{'planted':>9}{'right':>7}{'shared':>8}{'s':>7}"
    )
    grouped: dict[int, list[Outcome]] = defaultdict(list)
    for o in outcomes:
        grouped[o.report].append(o)
    for i, r in enumerate(reports):
        mine = grouped[i]
        if r.error:
            print(f"{r.entry:<78}{args_text(r.args):<28}  not expanded: {r.error[:60]}")
            continue
        right = sum(o.verdict == "right" for o in mine)
        secs = r.seconds + sum(o.seconds for o in mine)
        print(
            f"{r.entry:<78}{args_text(r.args):<28}{r.findings:>10}{len(r.files):>7}{len(mine):>9}"
            f"{right:>7}{r.shared:>8}{secs:>7.1f}"
        )

    misses = [o for o in outcomes if o.verdict != "right" or not o.trace_ok or not o.count_ok]
    if misses:
        print(
            f"\n{len(misses)} plants not reported exactly once at the right file:line"
            " (or with a trace outside the entry's package):"
        )
        shown = misses if opts.verbose else misses[:40]
        for o in shown:
            print(
                f"  [{o.verdict}{'' if o.trace_ok or o.verdict != 'right' else ', trace'}]"
                f" {o.site.kind} {o.site.label()} x{o.instances} (entry {o.entry})"
            )
            for f in o.found[:3]:
                print(
                    f"      -> {f['code']} {f['path']}:{f['line']}:{f['column']} {f['message'][:110]}"
                )
                for call in f["trace"][-1:]:
                    print(f"         outermost: {call}")
        if len(shown) < len(misses):
            print(f"  ... and {len(misses) - len(shown)} more (-v lists all)")
    print(
        f"\n{len(outcomes)} plants over {len(entries)} entries in"
        f" {time.perf_counter() - started:.0f} s with {opts.jobs} jobs"
    )
    if opts.json:
        opts.json.write_text(
            json.dumps(
                {
                    "entries": [
                        {
                            "entry": r.entry,
                            "args": r.args,
                            "error": r.error,
                            "findings": r.findings,
                            "files": r.files,
                        }
                        for r in reports
                    ],
                    "outcomes": [{**asdict(o), "site": asdict(o.site)} for o in outcomes],
                },
                indent=1,
            ),
            encoding="utf-8",
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
