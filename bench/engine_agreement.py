#!/usr/bin/env python3
"""Planted defects × engines: what each engine does, and (once ``--matrix`` predicts it)
whether urdflint's per-simulator prediction agrees.

    .venv/bin/python bench/engine_agreement.py [--out FILE] [--md FILE] [--jobs N]
                                               [--robots a,b] [--defects a,b] [--real-fixtures]
                                               [--bases URDF...] [--merge JSON]
                                               [--rescore JSON]

With ``--real-fixtures`` the bases are the fixtures cut down from real files for issue 29
(mesh formats, a package nobody resolves, a terrain), each loaded as it is (the control).

The base robots are the four of ``fixtures/planted/``, or with ``--bases`` real URDF files
(a robot is named after its file, or its folder for ``model.urdf``; a ``package_map.json``
next to the file, ``{"package": "folder relative to the file"}``, says where its
``package://`` meshes are; ``--robots`` then picks among them by name). For each base robot
and each defect of ``tests/planted.py`` (skipping those that do not apply to the robot),
plus the unplanted robot (``none``, the control), the script writes the planted URDF to a
temporary folder (beside links to everything next to the base file, so relative mesh paths
resolve) and lints it twice, in-process, with the robot's package map:

- observed: only the E rules, with every engine (``Settings(confirm=all)``); each
  engine's E findings are sorted into ``crashes`` (E005), ``refused`` (E001),
  ``changes`` (E002, E003, E004) or ``loads``, noting E006 warnings;
- predicted: every rule, no engine, ``urdflint check --format json --matrix --target all``;
  :func:`predicted` reads the report's ``"matrix"`` (absent: no prediction), and
  :func:`effects` keeps each finding's measurable effects.

Cases run in parallel in ``--jobs`` processes (each case also starts one process per
engine). Raw results go to ``--out`` (JSON), the table to ``--md``; with predictions,
:func:`agreement` prints recall and precision per target, and the disagreements.

Scoring against the control: an engine that already refuses (or crashes on) the unplanted
robot tells nothing about a defect planted in it, so that robot/engine pair is left out and
listed apart. Otherwise a planted case is scored on what it adds to the control: the
engine's E findings that the control does not have, against the measurable effects of the
findings the control does not have (so an engine that already lumps a fixed link in the
control, or a finding the real robot already has, counts once: in the control's own row).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import re
import sys
import tempfile
import time
from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests import planted  # noqa: E402
from urdflint import cli  # noqa: E402
from urdflint.engine import config, linter  # noqa: E402
from urdflint.model import targets  # noqa: E402
from urdflint.model.effects import MEASURABLE, Consequence  # noqa: E402
from urdflint.model.finding import Finding  # noqa: E402

NOTES = ROOT / "bench" / "results"  # git-ignored
CONTROL = "none"
CATEGORIES = ("crashes", "refused", "changes", "loads")
ORDER = ("loads", "changes", "refused", "crashes")  # best to worst (Outcome)
CODES = {"E005": "crashes", "E001": "refused", "E002": "changes", "E003": "changes",
         "E004": "changes"}  # fmt: skip
LABELS = {"MuJoCo": "mujoco", "PyBullet": "pybullet", "Drake": "drake",
          "Pinocchio": "pinocchio", "sdformat (Gazebo)": "sdformat"}  # fmt: skip
NOT_INSTALLED = "not-installed"
PACKAGE_MAP = "package_map.json"
LINE = re.compile(r"\bline \d+")

Case = tuple[str, str]  # (robot, defect)
Observation = dict[str, Any]  # category, codes, warned, messages


@dataclass(frozen=True)
class Base:
    """A base robot: its URDF file and where its packages are (absolute folders)."""

    name: str
    path: Path
    packages: dict[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {"path": str(self.path), "packages": self.packages}


def fixtures(names: Iterable[str] = planted.ROBOTS) -> dict[str, Base]:
    return {name: Base(name, planted.BASES / f"{name}.urdf") for name in names}


def base_of(path: Path) -> Base:
    """A real URDF as a base robot: named after its folder when the file is ``model.urdf``,
    else after the file; packages from the ``package_map.json`` beside it."""
    path = path.resolve()
    name = path.parent.name if path.stem == "model" else path.stem
    mapping = path.parent / PACKAGE_MAP
    table = json.loads(mapping.read_text()) if mapping.is_file() else {}
    return Base(name, path, {k: str((path.parent / v).resolve()) for k, v in table.items()})


# --- running one case -------------------------------------------------------------------


def engines() -> tuple[str, ...]:
    return config.engines("confirm", ("all",))


def cases(bases: Iterable[Base], defects: Iterable[str]) -> list[tuple[Base, str, str | None]]:
    """Every applicable (robot, defect), with the planted element's path (control: None)."""
    found: list[tuple[Base, str, str | None]] = []
    for defect in defects:
        for base in bases:
            tree, element = _planted(base, defect)
            if defect == CONTROL or element is not None:
                found.append((base, defect, planted.xpath(tree, element)))
    return found


def _planted(base: Base, defect: str) -> tuple[Any, Any]:
    if defect == CONTROL:
        return planted.load(base.path), None
    return planted.plant(base.path, defect)


def run_case(job: tuple[Base, str]) -> dict[str, Any]:
    """Plant, write, observe and predict one case (in a worker process)."""
    base, defect = job
    tree, _ = _planted(base, defect)
    with tempfile.TemporaryDirectory(prefix="urdflint-planted-") as folder:
        path = _write(tree, base, defect, Path(folder))
        found = report(path, base.packages)
        return {"observed": observe(path, base.packages), "predicted": predicted(found),
                "effects": effects(found)}  # fmt: skip


def _write(tree: Any, base: Base, defect: str, folder: Path) -> Path:
    """Write the planted tree into ``folder``, beside links to everything next to the base
    file (so relative mesh paths resolve as they do for the base)."""
    for entry in base.path.parent.iterdir():
        if entry != base.path and not (folder / entry.name).exists():
            (folder / entry.name).symlink_to(entry)
    path = folder / f"{base.name}-{defect}.urdf"
    tree.write(str(path), xml_declaration=True, encoding="utf-8")
    return path


def observe(path: Path, packages: dict[str, str] | None = None) -> dict[str, Observation]:
    paths = {name: Path(folder) for name, folder in (packages or {}).items()}
    settings = config.Settings(confirm=engines(), select=("E",), package_paths=paths)
    findings = linter.lint_path(path, path.name, settings).findings
    mine: dict[str, list[Finding]] = defaultdict(list)
    for finding in findings:
        mine[engine_of(finding)].append(finding)
    return {engine: categorize(mine[engine]) for engine in engines()}


def engine_of(finding: Finding) -> str:
    """The engine an E finding is about: its ``engine``, else the label it starts with."""
    if getattr(finding, "engine", None):
        return str(finding.engine)
    for label, engine in sorted(LABELS.items(), key=lambda item: -len(item[0])):
        if finding.message.startswith(label + " "):
            return engine
    return finding.message.split(" ", 1)[0].lower()


def categorize(findings: list[Finding]) -> Observation:
    codes = sorted({f.code for f in findings})
    messages = [f"{f.code} line {f.line}: {f.message}" for f in findings]
    if any(f.code == "E001" and "not installed" in f.message for f in findings):
        category = NOT_INSTALLED
    else:
        category = _category(codes)
    changes = [k for k in codes if CODES.get(k) == "changes"]
    return {"category": category, "changes": changes, "warned": "E006" in codes,
            "messages": messages}  # fmt: skip


def _category(codes: Iterable[str]) -> str:
    codes = set(codes)
    return next((c for c in CATEGORIES if any(CODES.get(k) == c for k in codes)), "loads")


def report(path: Path, packages: dict[str, str] | None = None) -> dict[str, Any]:
    """The JSON report of ``urdflint check --matrix --target all`` ({} if the CLI refuses)."""
    out = path.with_suffix(".json")
    argv = ["check", "--format", "json", "--matrix", "--target", "all", "--isolated",
            "--exit-zero", "--output", str(out)]  # fmt: skip
    for name, folder in (packages or {}).items():
        argv += ["--package-path", f"{name}={folder}"]
    with contextlib.redirect_stderr(io.StringIO()), contextlib.suppress(SystemExit):
        cli.main([*argv, str(path)])
    return json.loads(out.read_text()) if out.is_file() else {}


def predicted(report: dict[str, Any]) -> dict[str, str]:
    """Target -> predicted outcome, from the report's ``"matrix"`` ({} when absent), counting
    only what an engine's load can show (:func:`urdflint.engine.matrix.measurable`: a tag
    ignored or a joint converted is not something --confirm sees)."""
    from urdflint.engine.matrix import measurable

    rows = report.get("matrix") or []
    return {row["target"]: measurable(row) for row in rows
            if isinstance(row, dict) and row.get("predicted")}  # fmt: skip


def effects(report: dict[str, Any]) -> list[dict[str, Any]]:
    """The report's findings with a measurable effect on some target: ``code``, ``element``,
    ``message`` and ``outcomes`` (target -> outcome of that effect)."""
    keys = {c.key: c for c in Consequence}
    found = []
    for finding in report.get("findings") or []:
        outcomes = {
            target: keys[effect["consequence"]].outcome.key
            for target, effect in (finding.get("effects") or {}).items()
            if keys.get(effect.get("consequence")) in MEASURABLE
        }
        if outcomes:
            found.append({"code": finding["code"], "element": finding.get("element"),
                          "message": finding["message"], "outcomes": outcomes})  # fmt: skip
    return found


def rescore(path: Path) -> list[dict[str, Any]]:
    """The saved observations of ``path`` with fresh predictions (no engine runs)."""
    data = json.loads(path.read_text())
    bases = _saved_bases(data)
    for result in data["cases"]:
        base = bases[result["robot"]]
        tree, _ = _planted(base, result["defect"])
        with tempfile.TemporaryDirectory(prefix="urdflint-planted-") as folder:
            found = report(_write(tree, base, result["defect"], Path(folder)), base.packages)
            result["predicted"] = predicted(found)
            result["effects"] = effects(found)
    return list(data["cases"])


def _saved_bases(data: dict[str, Any]) -> dict[str, Base]:
    """The bases a saved run used (runs before ``--bases``: the fixtures)."""
    saved = data.get("bases")
    if not saved:
        return fixtures()
    return {name: Base(name, Path(b["path"]), dict(b.get("packages") or {}))
            for name, b in saved.items()}  # fmt: skip


# --- the observed table -----------------------------------------------------------------


def mark_new_warnings(results: list[dict[str, Any]]) -> None:
    """Set each observation's ``new_warnings``: its E006 warnings that the unplanted robot
    (the control, when it ran) does not print."""
    control = {
        (result["robot"], engine): _warnings(observation)
        for result in results
        if result["defect"] == CONTROL
        for engine, observation in result["observed"].items()
    }
    for result in results:
        for engine, observation in result["observed"].items():
            key = (result["robot"], engine)
            seen = set() if result["defect"] == CONTROL else control.get(key, set())
            observation["new_warnings"] = sorted(_warnings(observation) - seen)


def _warnings(observation: Observation) -> set[str]:
    """The text of its E006 messages (``E006 line N: text``), without the line."""
    return {m.split(": ", 1)[1] for m in observation["messages"] if m.startswith("E006 ")}


def _shown(observation: Observation) -> list[str]:
    """Its messages but the warnings the control prints too."""
    new = set(observation["new_warnings"])
    return [m for m in observation["messages"]
            if not m.startswith("E006 ") or m.split(": ", 1)[1] in new]  # fmt: skip


def label(observation: Observation) -> str:
    """``changes(E003,E004)``, ``loads(warn)``, ``refused``..."""
    category = observation["category"]
    if category == "changes":
        return f"changes({','.join(observation['changes'])})"
    warned = category == "loads" and observation["new_warnings"]
    return f"{category}(warn)" if warned else category


def cells(results: list[dict[str, Any]], engine: str, defect: str) -> dict[str, list[dict]]:
    """Label -> the cases of ``defect`` with that label for ``engine``, in robot order."""
    found: dict[str, list[dict]] = {}
    for result in results:
        if result["defect"] == defect:
            found.setdefault(label(result["observed"][engine]), []).append(result)
    return found


def cell_text(by_label: dict[str, list[dict]]) -> str:
    return " ".join(f"{name}×{len(rows)}" for name, rows in by_label.items())


def markdown(results: list[dict[str, Any]], names: list[str], seconds: float) -> str:
    defects = list(dict.fromkeys(r["defect"] for r in results))
    robots = list(dict.fromkeys(r["robot"] for r in results))
    lines = [
        "# Planted defects: what the engines do",
        "",
        f"{len(results)} cases, {len(robots)} robots ({', '.join(robots)}), "
        f"{len(defects)} defects, engines {', '.join(names)}; "
        f"{seconds:.0f} s. Cell: category × robots "
        "(warn: E006 warnings that the unplanted robot does not print).",
        "",
        "| defect | robots | " + " | ".join(names) + " |",
        "|---|---|" + "---|" * len(names),
    ]
    for defect in defects:
        robots_ = ",".join(r["robot"] for r in results if r["defect"] == defect)
        row = [cell_text(cells(results, e, defect)) for e in names]
        lines.append(f"| {defect} | {robots_} | " + " | ".join(row) + " |")
    return "\n".join([*lines, "", *uninformative_lines(results),
                      *details(results, names, defects)]) + "\n"  # fmt: skip


def details(results: list[dict[str, Any]], names: list[str], defects: list[str]) -> list[str]:
    """The messages of the first case of each cell label."""
    lines = ["## Messages (first robot of each cell)", ""]
    for defect in defects:
        lines.append(f"### {defect}")
        for engine in names:
            for name, rows in cells(results, engine, defect).items():
                first = rows[0]
                for message in _shown(first["observed"][engine]):
                    lines.append(f"- {engine} {name} [{first['robot']}]: {message}")
        lines.append("")
    return lines


# --- against the control ----------------------------------------------------------------


def _message_key(message: str) -> str:
    """``E004 line 70: text`` -> ``E004: text``, any ``line N`` inside the text as well."""
    match = re.match(r"(E\d+) line \S+: (.*)", message, re.S)
    code, text = match.groups() if match else ("", message)
    return f"{code}: {_unnumbered(text)}"


def _effect_key(effect: dict[str, Any]) -> str:
    return f"{effect['code']} {effect['element']}: {_unnumbered(effect['message'])}"


def _unnumbered(text: str) -> str:
    """The text with each ``line N`` the same (lines move when a planter removes one)."""
    return LINE.sub("line N", text)


def controls(results: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Robot -> its control's result (robots whose control ran)."""
    return {r["robot"]: r for r in results if r["defect"] == CONTROL}


def uninformative(results: list[dict[str, Any]]) -> dict[tuple[str, str], Observation]:
    """(robot, engine) -> the control's observation, where the engine already refuses or
    crashes on the unplanted robot: no planted case of that pair is scored."""
    return {
        (robot, engine): observation
        for robot, control in controls(results).items()
        for engine, observation in control["observed"].items()
        if observation["category"] in ("refused", "crashes")
    }


def observed_outcome(
    result: dict[str, Any], engine: str, control: dict[str, Any] | None
) -> str | None:
    """What the engine did (control given: what it did that the control does not show);
    None: not installed, or the pair is uninformative."""
    observation = result["observed"].get(engine)
    if observation is None or observation["category"] not in CATEGORIES:
        return None
    if control is None or result is control:
        return str(observation["category"])
    before = control["observed"].get(engine) or {}
    if before.get("category") not in ("loads", "changes"):
        return None
    seen = {_message_key(m) for m in before.get("messages", [])}
    new = [m.split(" ", 1)[0] for m in observation["messages"] if _message_key(m) not in seen]
    return _category(new)


def new_messages(result: dict[str, Any], engine: str, control: dict[str, Any] | None) -> list[str]:
    observation = result["observed"].get(engine) or {"messages": []}
    before = {} if control is None or result is control else control["observed"].get(engine) or {}
    seen = {_message_key(m) for m in before.get("messages", [])}
    return [m for m in observation["messages"] if _message_key(m) not in seen]


def predicted_outcome(
    result: dict[str, Any], target: str, control: dict[str, Any] | None
) -> str | None:
    """The prediction (control given: of the findings the control does not have)."""
    if target not in result["predicted"]:
        return None
    if control is None or result is control or "effects" not in result:
        return str(result["predicted"][target])
    seen = {_effect_key(e) for e in control.get("effects", [])}
    found = [e["outcomes"][target] for e in result["effects"]
             if target in e["outcomes"] and _effect_key(e) not in seen]  # fmt: skip
    return max(found, key=ORDER.index, default="loads")


def deciding(result: dict[str, Any], target: str, control: dict[str, Any] | None) -> list[str]:
    """The new findings behind the prediction: ``code (outcome)``."""
    seen = (
        set()
        if control is None or result is control
        else {_effect_key(e) for e in control.get("effects", [])}
    )
    return [f"{e['code']}({e['outcomes'][target]})" for e in result.get("effects", [])
            if target in e["outcomes"] and _effect_key(e) not in seen]  # fmt: skip


# --- agreement --------------------------------------------------------------------------

Pair = tuple[dict[str, Any], str, str, str]  # result, target, predicted, observed


def agreement(results: list[dict[str, Any]]) -> str:
    """Per target with an engine: recall (engine outcomes other than loads that were
    predicted with the same category) and precision (predictions other than loads that
    the engine confirmed), on the planted cases and, apart, on the controls; then the
    uninformative pairs and the disagreements, with the engines' messages."""
    planted_, control_ = _pairs(results)
    lines = ["planted cases (scored against the control):"]
    lines += [_score(target, rows) for target, rows in planted_.items()]
    lines.append("controls (the unplanted robots):")
    lines += [_score(target, rows) for target, rows in control_.items()]
    lines += uninformative_lines(results)
    lines.append("disagreements:")
    both = [*(r for rows in control_.values() for r in rows),
            *(r for rows in planted_.values() for r in rows)]  # fmt: skip
    by_defect: dict[tuple[str, str], list[Pair]] = defaultdict(list)
    for row in both:
        if row[2] != row[3]:
            by_defect[(row[0]["defect"], row[1])].append(row)
    found = controls(results)
    for (defect, target), rows in by_defect.items():
        lines.append(f"  {defect} / {target}:")
        for result, _, guess, seen in rows:
            control = found.get(result["robot"])
            why = ", ".join(deciding(result, target, control)) or "-"
            lines.append(f"    {result['robot']:20} predicted {guess:8} observed {seen:8} "
                         f"(findings: {why})")  # fmt: skip
            engine = targets.ENGINE.get(target) or ""
            none = "(no E finding)" if result is control else "(no E finding the control lacks)"
            shown = new_messages(result, engine, control) or [none]
            lines += [f"      {message[:300]}" for message in shown[:3]]
    return "\n".join(lines)


def uninformative_lines(results: list[dict[str, Any]]) -> list[str]:
    pairs = uninformative(results)
    lines = ["", "## Left out: engines that refuse or crash on the unplanted robot", ""]
    if not pairs:
        return [*lines, "(none)", ""]
    for (robot, engine), observation in sorted(pairs.items()):
        first = next(iter(observation["messages"]), "")
        lines.append(f"- {robot} / {engine}: {observation['category']}: {first[:300]}")
    return [*lines, ""]


def _pairs(results: list[dict[str, Any]]) -> tuple[dict[str, list[Pair]], dict[str, list[Pair]]]:
    """Target -> (result, target, predicted, observed) where both exist: planted cases
    (against their control) and controls."""
    found = controls(results)
    planted_: dict[str, list[Pair]] = defaultdict(list)
    control_: dict[str, list[Pair]] = defaultdict(list)
    for result in results:
        control = found.get(result["robot"])
        for target in result["predicted"]:
            engine = targets.ENGINE.get(target) or ""
            seen = observed_outcome(result, engine, control)
            guess = predicted_outcome(result, target, control)
            if seen is None or guess is None:
                continue
            into = control_ if result["defect"] == CONTROL else planted_
            into[target].append((result, target, guess, seen))
    return planted_, control_


def _score(target: str, rows: Sequence[Pair]) -> str:
    seen = [(g, s) for _, _, g, s in rows if s != "loads"]
    guessed = [(g, s) for _, _, g, s in rows if g != "loads"]
    recall = _share(sum(g == s for g, s in seen), len(seen))
    precision = _share(sum(g == s for g, s in guessed), len(guessed))
    agree = _share(sum(g == s for _, _, g, s in rows), len(rows))
    engine = targets.ENGINE.get(target)
    return f"  {target} ({engine}): recall {recall}, precision {precision}, agreement {agree}"


def _share(hits: int, total: int) -> str:
    return f"{hits}/{total} = {hits / total:.0%}" if total else "0/0"


# --- main -------------------------------------------------------------------------------


def run(chosen: list[tuple[Base, str, str | None]], jobs: int) -> list[dict[str, Any]]:
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        outcomes = pool.map(run_case, [(base, defect) for base, defect, _ in chosen])
        return [
            {"robot": base.name, "defect": defect, "element": element, **outcome}
            for (base, defect, element), outcome in zip(chosen, outcomes, strict=True)
        ]


def summary(results: list[dict[str, Any]], names: list[str]) -> str:
    counts = {e: Counter(r["observed"][e]["category"] for r in results) for e in names}
    return "\n".join(f"{e}: {dict(c)}" for e, c in counts.items())


def parse(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=NOTES / "observed.json")
    parser.add_argument("--md", type=Path, default=NOTES / "observed.md")
    parser.add_argument("--jobs", type=int, default=3)
    parser.add_argument("--robots", help="robots to run, by name (default: every base)")
    parser.add_argument("--defects", default=",".join([CONTROL, *planted.DEFECTS]))
    parser.add_argument(
        "--bases",
        type=Path,
        nargs="+",
        metavar="URDF",
        help="real URDF files as the base robots (default: the fixtures)",
    )
    parser.add_argument(
        "--real-fixtures",
        action="store_true",
        help="the files cut down from real ones for issue 29 (tests/test_agreement.py's "
        "REAL_FIXTURES) as the bases, each loaded as it is (defect: none)",
    )
    parser.add_argument(
        "--merge",
        type=Path,
        metavar="JSON",
        help="keep the cases saved in JSON that this run does not redo",
    )
    parser.add_argument(
        "--rescore",
        type=Path,
        metavar="JSON",
        help="re-predict the observations saved in JSON (runs no engine)",
    )
    return parser.parse_args(argv)


def bases(args: argparse.Namespace) -> dict[str, Base]:
    if args.real_fixtures:
        from tests.test_agreement import REAL_FIXTURES

        args.bases, args.defects = list(REAL_FIXTURES), CONTROL
    found = {b.name: b for b in map(base_of, args.bases)} if args.bases else fixtures()
    if args.robots:
        names = args.robots.split(",")
        unknown = [n for n in names if n not in found]
        if unknown:
            raise SystemExit(f"unknown robots {unknown} (known: {', '.join(found)})")
        found = {n: found[n] for n in names}
    return found


def merge(
    path: Path, results: list[dict[str, Any]], saved: dict[str, Any], seconds: float
) -> tuple[list[dict[str, Any]], dict[str, Any], float]:
    """The cases saved in ``path`` with this run's in place of those it redid (same robot
    and defect), then its new ones; the bases of both; the seconds of both."""
    data = json.loads(path.read_text())
    fresh = {(r["robot"], r["defect"]): r for r in results}
    kept = [fresh.pop((r["robot"], r["defect"]), r) for r in data["cases"]]
    bases_ = {**(data.get("bases") or {}), **saved}
    return [*kept, *fresh.values()], bases_, float(data.get("seconds") or 0) + seconds


def main(argv: list[str] | None = None) -> int:
    args = parse(argv)
    if args.rescore:
        results = rescore(args.rescore)
        mark_new_warnings(results)
        print(agreement(results))
        return 0
    start = time.monotonic()
    chosen_bases = bases(args)
    chosen = cases(chosen_bases.values(), args.defects.split(","))
    results = run(chosen, args.jobs)
    seconds = time.monotonic() - start
    saved = {n: b.to_json() for n, b in chosen_bases.items()}
    if args.merge:
        results, saved, seconds = merge(args.merge, results, saved, seconds)
    mark_new_warnings(results)
    names = list(engines())
    args.out.parent.mkdir(parents=True, exist_ok=True)
    data = {"engines": names, "seconds": round(seconds, 1), "bases": saved, "cases": results}
    args.out.write_text(json.dumps(data, indent=1) + "\n")
    args.md.write_text(markdown(results, names, seconds))
    print(f"{len(results)} cases in {seconds:.0f} s -> {args.out}, {args.md}")
    print(summary(results, names))
    if any(r["predicted"] for r in results):
        print(agreement(results))
    else:
        print('no predictions (the JSON report has no "matrix" yet): observations only')
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
