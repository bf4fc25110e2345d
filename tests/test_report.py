"""``urdflint report``: a dataset run's records summarised (text, JSON, HTML, Parquet).

The numbers are checked exactly on records built here (:func:`record`, in the layout of
``urdflint.outputs.records``), and end to end on records ``urdflint check --format jsonl``
writes for the fixtures and a few corpus robots.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CORPUS, FIXTURES, needs_corpus
from urdflint.cli import main
from urdflint.model.targets import LABELS
from urdflint.outputs import records
from urdflint.outputs.dataset import compare, fingerprint, html, load, summarize, text
from urdflint.outputs.dataset import histogram as H
from urdflint.outputs.dataset.summary import slim

CONSEQUENCE = {"changes": "link dropped", "refused": "refused", "crashes": "crash"}


def finding(
    code: str, severity: str, element: str, *, path: str = "arm.urdf", line: int = 1, **more: Any
) -> dict[str, Any]:
    """A v1 JSON finding object."""
    return {
        "path": path,
        "line": line,
        "column": 1,
        "code": code,
        "name": more.get("name", f"rule-{code.lower()}"),
        "severity": severity,
        "message": more.get("message", f"{code} at {element}"),
        "element": element,
        "fix": None,
        "trace": [],
        "effects": {},
        "engine": more.get("engine"),
        "autofix": None,
    }


def row(path: str, target: str, outcome: str, confirmed: str | None = None) -> dict[str, Any]:
    """A matrix row whose deciding findings give ``outcome`` (and ``measurable`` too)."""
    deciding = (
        []
        if outcome == "loads"
        else [
            {
                "code": "X",
                "path": path,
                "line": 1,
                "element": "/robot",
                "consequence": CONSEQUENCE[outcome],
                "detail": "",
            }
        ]
    )
    engine = {"mujoco": "mujoco", "pybullet": "pybullet"}.get(target, "sdformat")
    return {
        "path": path,
        "target": target,
        "label": LABELS[target],
        "basis": "engine",
        "predicted": {"outcome": outcome, "findings": deciding},
        "confirmed": None
        if confirmed is None
        else {"engine": engine, "outcome": confirmed, "findings": []},
        "selected": True,
    }


def record(
    path: str,
    findings: list[dict[str, Any]] = (),  # type: ignore[assignment]
    outcomes: dict[str, str] | None = None,
    **more: Any,
) -> dict[str, Any]:
    """A record in the layout of ``urdflint.outputs.records.record``."""
    findings = list(findings)
    summary = {s: sum(f["severity"] == s for f in findings) for s in ("error", "warning", "info")}
    confirmed = more.get("confirmed", {})
    matrix = [row(path, t, o, confirmed.get(t)) for t, o in (outcomes or {}).items()]
    return {
        "record": 1,
        "path": path,
        "hash": "h-" + path,
        "settings": "s",
        "tool": "0.1.0",
        "error": more.get("error"),
        "crashed": more.get("crashed", False),
        "summary": summary,
        "links": more.get("links"),
        "joints": more.get("joints"),
        "mass": more.get("mass"),
        "engines": more.get("engines", {}),
        "matrix": matrix,
        "targets": None,
        "model": None,
        "ran": [],
        "skipped": {},
        "findings": findings,
        "inputs": [],
    }


def three(gazebo: str, mujoco: str, pybullet: str) -> dict[str, str]:
    return {"gazebo-classic": gazebo, "mujoco": mujoco, "pybullet": pybullet}


LINK_A = "/robot/link[@name='a']"
ARM = record(
    "arm.urdf",
    [
        finding("I002", "error", LINK_A + "/inertial/mass"),
        finding("J007", "error", "/robot/joint[@name='j']/axis"),
        finding("C001", "warning", LINK_A, line=10),
    ],
    three("refused", "refused", "loads"),
    mass=5.0,
    links=4,
    joints=3,
)
ROVER = record(
    "rover.urdf",
    [
        finding("C001", "warning", "/robot/link[@name='w1']", path="rover.urdf"),
        finding("C001", "warning", "/robot/link[@name='w2']", path="rover.urdf"),
        finding("G002", "info", "/robot/link[@name='w1']/visual", path="rover.urdf"),
    ],
    three("changes", "loads", "loads"),
    mass=50.0,
    links=10,
)
GRIPPER = record(
    "gripper.urdf",
    [finding("G002", "info", "/robot/link[@name='f']/visual", path="gripper.urdf")],
    three("loads", "loads", "loads"),
    mass=0.5,
    links=3,
)
CLEAN = record("clean.urdf", [], three("loads", "loads", "loads"), mass=500.0, links=12)
CRASHY = record(
    "crashy.urdf",
    [finding("U001", "error", "/robot", path="crashy.urdf")],
    three("crashes", "loads", "crashes"),
    crashed=True,
)
MISSING = record("missing.urdf", error="missing.urdf: cannot read: No such file or directory")
DATASET = [ARM, ROVER, GRIPPER, CLEAN, CRASHY, MISSING]


def write(path: Path, items: list[dict[str, Any]], tail: str = "") -> Path:
    path.write_text("".join(records.dumps(r) for r in items) + tail, encoding="utf-8")
    return path


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


# -- the summary ------------------------------------------------------------------------------


def test_files_are_counted_by_their_worst_finding_and_findings_by_severity() -> None:
    s = summarize(DATASET)
    assert s["files"] == 6
    assert s["status"] == {
        "errors": 2,
        "warnings": 1,
        "infos": 1,
        "clean": 1,
        "unreadable": 1,
        "crashed": 1,
    }
    assert s["unreadable"] == [{"path": "missing.urdf", "error": MISSING["error"]}]
    assert s["crashed"] == ["crashy.urdf"]
    assert s["severities"] == [
        {"severity": "error", "findings": 3, "files": 2},
        {"severity": "warning", "findings": 3, "files": 2},
        {"severity": "info", "findings": 2, "files": 2},
    ]


def test_rules_are_counted_most_frequent_first() -> None:
    rules = summarize(DATASET)["rules"]
    assert [(r["code"], r["severity"], r["findings"], r["files"]) for r in rules] == [
        ("C001", "warning", 3, 2),
        ("G002", "info", 2, 2),
        ("I002", "error", 1, 1),
        ("J007", "error", 1, 1),
        ("U001", "error", 1, 1),
    ]
    assert rules[0]["name"] == "rule-c001"


def test_the_load_matrix_counts_files_per_target_and_outcome() -> None:
    m = summarize(DATASET)["matrix"]
    counts = {
        t["target"]: [t["loads"], t["changes"], t["refused"], t["crashes"], t["files"]]
        for t in m["targets"]
    }
    assert list(counts) == ["gazebo-classic", "mujoco", "pybullet"]  # the targets' order
    assert counts == {
        "gazebo-classic": [2, 1, 1, 1, 5],
        "mujoco": [4, 0, 1, 0, 5],
        "pybullet": [4, 0, 0, 1, 5],
    }
    assert m["targets"][0]["label"] == "Gazebo Classic"
    assert (m["modelled"], m["everywhere"]) == (5, 2)
    assert m["engines"] == [] and m["agreement"] == []


def test_the_worst_assets_are_ranked_by_refusals_then_errors_then_warnings() -> None:
    worst = summarize(DATASET)["worst"]
    assert [(w["path"], w["blocked"], w["errors"], w["warnings"]) for w in worst] == [
        ("arm.urdf", 2, 2, 1),
        ("crashy.urdf", 2, 1, 0),
        ("rover.urdf", 0, 0, 2),
    ]  # gripper (infos only) and clean are not listed
    assert worst[0]["refused"] == ["gazebo-classic", "mujoco"] and worst[0]["crashes"] == []
    assert worst[1]["crashes"] == ["gazebo-classic", "pybullet"]
    assert [(c["code"], c["count"]) for c in worst[0]["codes"]] == [
        ("I002", 1),
        ("J007", 1),
        ("C001", 1),
    ]
    assert [(c["code"], c["count"]) for c in worst[2]["codes"]] == [("C001", 2), ("G002", 1)]
    assert [w["path"] for w in summarize(DATASET, top=1)["worst"]] == ["arm.urdf"]


def test_the_distributions_have_their_bins_and_figures() -> None:
    d = summarize(DATASET)["distributions"]
    mass = d["mass"]  # 0.5, 5, 50, 500 kg: three decades, 1-2-5 log bins
    assert (mass["count"], mass["min"], mass["median"], mass["max"]) == (4, 0.5, 27.5, 500)
    assert mass["scale"] == "log" and mass["unit"] == "kg"
    assert [b["label"] for b in mass["bins"]] == [
        "0.5–1",
        "1–2",
        "2–5",
        "5–10",
        "10–20",
        "20–50",
        "50–100",
        "100–200",
        "200–500",
        "500–1000",
    ]
    assert [b["count"] for b in mass["bins"]] == [1, 0, 0, 1, 0, 0, 1, 0, 0, 1]
    links = d["links"]  # 3, 4, 10, 12: one bin per count
    assert (links["count"], links["min"], links["median"], links["max"]) == (4, 3, 7.0, 12)
    assert [b["label"] for b in links["bins"]] == [str(n) for n in range(3, 13)]
    assert [b["count"] for b in links["bins"]] == [1, 1, 0, 0, 0, 0, 0, 1, 0, 1]
    found = d["findings"]  # 3, 3, 1, 0, 1 (the unreadable file has none to count)
    assert (found["count"], found["min"], found["median"], found["max"]) == (5, 0, 1, 3)
    assert [(b["label"], b["count"]) for b in found["bins"]] == [
        ("0", 1),
        ("1", 2),
        ("2", 0),
        ("3", 2),
    ]


def test_histogram_bins() -> None:
    wide = H.describe(range(0, 301, 3), integer=True)  # width 50: 0-49 ... 300-349
    assert [b["label"] for b in wide["bins"]] == [f"{n}–{n + 49}" for n in range(0, 301, 50)]
    assert sum(b["count"] for b in wide["bins"]) == 101
    assert H.describe([1.5, 3.2, 9.9])["scale"] == "linear"
    assert H.describe([1.5, 3.2, 9.9])["bins"][0]["label"] == "1–2"
    odd = H.describe([-2.0, 0.0, 0.01, 3.0, 5e3], unit="kg")  # 5.7 decades: 1-3 steps
    assert odd["bins"][0] == {"low": None, "high": 0, "label": "≤ 0", "count": 2}
    assert [b["label"] for b in odd["bins"][1:4]] == ["0.01–0.03", "0.03–0.1", "0.1–0.3"]
    assert sum(b["count"] for b in odd["bins"]) == 5
    assert H.describe([None, float("nan"), True])["count"] == 0
    assert H.describe([])["bins"] == [] and H.describe([4.0])["bins"][0]["count"] == 1
    assert H.log_edges(0.5, 500)[0] == 0.5 and H.log_edges(0.5, 500)[-1] == 1000
    assert [H.nice(x) for x in (0.13, 3, 7, 11)] == [0.2, 5, 10, 20]


def test_engines_and_the_agreement_of_prediction_and_confirmation() -> None:
    items = [
        record(
            "x.urdf",
            [],
            {"mujoco": "refused"},
            confirmed={"mujoco": "refused"},
            engines={"mujoco": "refused", "pybullet": "loads with changes"},
        ),
        record(
            "y.urdf",
            [],
            {"mujoco": "loads"},
            confirmed={"mujoco": "loads"},
            engines={"mujoco": "loads"},
        ),
        record(
            "z.urdf",
            [],
            {"mujoco": "refused"},
            confirmed={"mujoco": "loads"},
            engines={"mujoco": "loads"},
        ),
        record(
            "w.urdf",
            [],
            {"mujoco": "loads"},
            confirmed={"mujoco": "not-installed"},
            engines={"mujoco": "not-installed"},
        ),
    ]
    m = summarize(items)["matrix"]
    assert m["engines"] == [
        {
            "engine": "mujoco",
            "files": 4,
            "loads": 2,
            "changes": 0,
            "refused": 1,
            "crashes": 0,
            "not-installed": 1,
        },
        {
            "engine": "pybullet",
            "files": 1,
            "loads": 0,
            "changes": 1,
            "refused": 0,
            "crashes": 0,
            "not-installed": 0,
        },
    ]
    assert m["agreement"] == [
        {
            "target": "mujoco",
            "label": "MuJoCo",
            "engine": "mujoco",
            "compared": 3,
            "agree": 2,
            "disagreements": [{"predicted": "refused", "confirmed": "loads", "files": 1}],
        }
    ]


def test_a_bad_field_counts_as_absent() -> None:
    odd = {
        "record": 1,
        "path": "odd.urdf",
        "summary": "many",
        "mass": "heavy",
        "links": True,
        "matrix": [None, {"target": 3}, {"target": "mujoco", "predicted": "x"}],
        "findings": [None, {"code": "C001", "severity": "warning"}],
        "engines": [],
        "crashed": "yes",
        "error": 3,
    }
    worse = {"record": 1, "path": "worse.urdf", "findings": 7, "matrix": {"a": 1}}
    s = summarize([odd, worse])
    assert s["status"]["warnings"] == 1 and s["status"]["clean"] == 1
    assert s["status"]["crashed"] == 0 and s["matrix"]["targets"] == []
    assert s["distributions"]["mass"]["count"] == 0
    assert s["distributions"]["links"]["count"] == 0
    text.render(s)
    html.render(s)
    compare([odd], [worse])
    assert slim(odd)["findings"][1]["code"] == "C001"


# -- two runs ---------------------------------------------------------------------------------


def test_a_diff_finds_better_worse_added_removed_new_and_fixed() -> None:
    k_old = record("k.urdf", [], {"gazebo-classic": "refused", "mujoco": "loads"})
    k_new = record("k.urdf", [], {"gazebo-classic": "loads", "mujoco": "refused"})
    arm_new = record(
        "arm.urdf",
        [
            finding("J007", "error", "/robot/joint[@name='j']/axis", line=3),
            finding("C001", "warning", LINK_A, line=12),  # moved two lines: not new, not fixed
        ],
        three("refused", "loads", "loads"),
        mass=5.0,
        links=4,
    )
    rover_new = record(
        "rover.urdf",
        [
            *ROVER["findings"],
            finding("J009", "error", "/robot/joint[@name='w']/limit", path="rover.urdf"),
        ],
        three("changes", "refused", "loads"),
    )
    old = [ARM, ROVER, k_old, record("gone.urdf")]
    new = [arm_new, rover_new, k_new, record("new.urdf")]
    d = compare(old, new)
    assert d["files"] == {
        "old": 4,
        "new": 4,
        "added": 1,
        "removed": 1,
        "worse": 1,
        "better": 1,
        "changed": 1,
        "same": 0,
    }
    assert (d["added"], d["removed"]) == (["new.urdf"], ["gone.urdf"])
    assert [(c["path"], c["errors"], c["warnings"], c["targets"]) for c in d["worse"]] == [
        ("rover.urdf", [0, 1], [2, 2], {"mujoco": ["loads", "refused"]})
    ]
    assert [(c["path"], c["errors"], c["targets"]) for c in d["better"]] == [
        ("arm.urdf", [2, 1], {"mujoco": ["refused", "loads"]})
    ]
    assert [c["path"] for c in d["changed"]] == ["k.urdf"]
    assert [(x["code"], x["path"]) for x in d["new_findings"]["items"]] == [("J009", "rover.urdf")]
    assert [(x["code"], x["path"]) for x in d["fixed_findings"]["items"]] == [("I002", "arm.urdf")]
    assert (d["new_findings"]["count"], d["fixed_findings"]["count"]) == (1, 1)
    assert [(r["code"], r["old"], r["new"]) for r in d["rules"]["up"]] == [("J009", 0, 1)]
    assert [(r["code"], r["old"], r["new"]) for r in d["rules"]["down"]] == [("I002", 1, 0)]
    mujoco = next(r for r in d["matrix"] if r["target"] == "mujoco")
    assert (mujoco["loads"], mujoco["refused"]) == ([2, 1], [1, 2])
    assert d["status"]["errors"] == [1, 2]


def test_a_fingerprint_is_the_findings_own() -> None:
    data = finding("I002", "error", LINK_A + "/inertial/mass", path="sub\\arm.urdf")
    assert fingerprint(data) == records.finding(data).fingerprint()


# -- the command ------------------------------------------------------------------------------


def test_text_output(capsys, tmp_path: Path) -> None:
    code, out, err = run(capsys, "report", str(write(tmp_path / "r.jsonl", DATASET)))
    assert (code, err) == (0, "")
    assert out.startswith("urdflint report: 6 files\n")
    assert re.search(r"with errors\s+2\s+33\.3 %", out)
    assert re.search(r"C001\s+rule-c001\s+warning\s+3\s+2", out)
    assert re.search(r"Gazebo Classic\s+2\s+1\s+1\s+1\s+5", out)
    assert "2 of 5 models load on every target" in out
    assert "  1. arm.urdf\n       2 errors, 1 warning; refused by gazebo-classic, mujoco" in out
    assert "unreadable: missing.urdf: cannot read" in out and "crashed: crashy.urdf" in out
    assert "mass (kg): 4 files, min 0.5, median 27.5, max 500, log bins" in out
    assert "Changes against" not in out


def test_json_output_and_the_diff(capsys, tmp_path: Path) -> None:
    new = write(tmp_path / "new.jsonl", DATASET)
    old = write(tmp_path / "old.jsonl", [ARM, CLEAN])
    code, out, _ = run(
        capsys, "report", str(new), "--format", "json", "--against", str(old), "--top", "2"
    )
    assert code == 0
    s = json.loads(out)
    assert set(s) >= {
        "report",
        "files",
        "status",
        "severities",
        "rules",
        "matrix",
        "worst",
        "distributions",
        "results",
        "against",
        "diff",
    }
    assert s["files"] == 6 and len(s["worst"]) == 2
    assert s["results"] == [str(new)] and s["against"] == [str(old)]
    assert s["diff"]["files"]["added"] == 4 and s["diff"]["files"]["same"] == 2
    code, out, _ = run(capsys, "report", str(new), "--against", str(old))
    assert "Changes against the earlier run (2 -> 6 files)" in out


def test_shards_are_one_run_and_a_cut_last_line_is_left_out(capsys, tmp_path: Path) -> None:
    first = write(tmp_path / "a.jsonl", [ARM, ROVER])
    fixed = record("arm.urdf", [], three("loads", "loads", "loads"))
    cut = records.dumps(GRIPPER)[:40]  # a run stopped while writing
    second = write(tmp_path / "b.jsonl", [fixed], tail=cut)
    code, out, err = run(capsys, "report", str(first), str(second), "--format", "json")
    assert (code, err) == (0, "")
    s = json.loads(out)
    assert s["files"] == 2  # arm (the later record) and rover; the cut gripper is left out
    assert s["status"]["clean"] == 1 and s["status"]["warnings"] == 1
    assert [r["path"] for r in load([first, second])] == ["rover.urdf", "arm.urdf"]


@pytest.mark.parametrize(
    "content",
    [
        "hello\nworld\n",
        '{"a": 1}\n',
        '[1, 2]\n{"record": 1}\n',
        "not json",
        "\x00\xff\xfe\n",
        '{"record": 1, "path": [1]}\n',
    ],
    ids=["text", "json-not-record", "list", "one-cut-line", "binary", "path-not-text"],
)
def test_a_file_that_is_not_records_is_one_line_and_exit_2(capsys, tmp_path, content) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_bytes(content.encode("latin-1"))
    code, out, err = run(capsys, "report", str(bad))
    assert code == 2 and out == ""
    assert err.startswith(f"urdflint: error: {bad}") and err.count("\n") == 1
    assert "Traceback" not in err


def test_missing_results_and_an_unwritable_output_are_usage_errors(capsys, tmp_path) -> None:
    code, _, err = run(capsys, "report", str(tmp_path / "none.jsonl"))
    assert code == 2 and "cannot read" in err and err.count("\n") == 1
    good = write(tmp_path / "r.jsonl", DATASET)
    code, _, err = run(capsys, "report", str(good), "--against", str(tmp_path))
    assert code == 2 and err.startswith(f"urdflint: error: {tmp_path}")
    code, _, err = run(capsys, "report", str(good), "--html", str(tmp_path / "no" / "r.html"))
    assert code == 2 and "cannot write" in err and err.count("\n") == 1
    with pytest.raises(SystemExit):
        main(["report", str(good), "--top", "-1"])
    capsys.readouterr()


def test_an_empty_results_file_is_an_empty_report(capsys, tmp_path) -> None:
    (tmp_path / "empty.jsonl").write_text("")
    code, out, _ = run(capsys, "report", str(tmp_path / "empty.jsonl"))
    assert code == 0 and out.startswith("urdflint report: 0 files")


# -- the page ---------------------------------------------------------------------------------

HOSTILE = "<script>window.owned = 1</script>.urdf"
MESSAGE = 'mass <img src=x onerror=alert(1)> & "quotes"'


def hostile() -> list[dict[str, Any]]:
    bad = record(
        HOSTILE,
        [
            finding(
                "Z999",
                "error",
                "/robot/link[@name='<blink>']",
                path=HOSTILE,
                message=MESSAGE,
                name="<marquee>name</marquee>",
            )
        ],
        three("refused", "loads", "loads"),
        mass=1.0,
        links=2,
    )
    return [*DATASET, bad]


def test_the_page_escapes_everything_from_the_records(capsys, tmp_path: Path) -> None:
    new = write(tmp_path / "new.jsonl", hostile())
    old = write(tmp_path / "old.jsonl", [*DATASET, record(HOSTILE)])  # its finding is new
    page = tmp_path / "report.html"
    code, _, _ = run(capsys, "report", str(new), "--against", str(old), "--html", str(page))
    assert code == 0
    content = page.read_text(encoding="utf-8")
    assert content.count("<script>") == 1  # the page's own (table sorting)
    assert "window.owned" in content  # as text
    assert "&lt;script&gt;window.owned = 1&lt;/script&gt;.urdf" in content
    assert "<img" not in content and "&lt;img src=x onerror=alert(1)&gt;" in content
    assert "<marquee>" not in content and "&lt;marquee&gt;name&lt;/marquee&gt;" in content
    assert "<blink>" not in content


def test_the_page_references_nothing_outside_itself(tmp_path: Path) -> None:
    s = summarize(hostile())
    s["diff"] = compare(DATASET, hostile())
    content = html.render(s)
    assert not re.search(r"""(?:src|href|action)\s*=\s*["']?\s*(?:https?:)?//""", content, re.I)
    assert not re.search(r"https?://", content)
    assert "@import" not in content and "url(" not in content
    assert content.startswith("<!DOCTYPE html>") and content.rstrip().endswith("</html>")
    for section in ("headline", "severities", "rules", "matrix", "worst", "distributions", "diff"):
        assert f'id="{section}"' in content
    for plot in ("mass", "links", "findings"):
        assert f'<svg class="plot" id="plot-{plot}"' in content
    assert 'data-target="gazebo-classic" data-outcome="refused" data-count="2"' in content


def test_the_page_of_records_without_a_matrix_or_findings() -> None:
    content = html.render(summarize([record("a.urdf"), record("b.urdf", mass=2.0)]))
    assert "check with <code>--matrix</code>" in content
    assert "No findings in these records" in content


# -- Parquet ----------------------------------------------------------------------------------


def test_parquet_round_trip(capsys, tmp_path: Path) -> None:
    pq = pytest.importorskip("pyarrow.parquet")
    items = [
        *DATASET,
        record(
            "m.urdf",
            [finding("E001", "error", "/robot", path="m.urdf", engine="mujoco")],
            {"mujoco": "refused"},
            confirmed={"mujoco": "refused"},
            engines={"mujoco": "refused"},
        ),
    ]
    folder = tmp_path / "tables"
    code, _, err = run(
        capsys, "report", str(write(tmp_path / "r.jsonl", items)), "--parquet", str(folder)
    )
    assert (code, err) == (0, "")
    files = pq.read_table(folder / "files.parquet").to_pylist()
    assert [f["path"] for f in files] == [r["path"] for r in items]
    arm = files[0]
    assert (
        arm["errors"],
        arm["warnings"],
        arm["infos"],
        arm["links"],
        arm["joints"],
        arm["mass"],
        arm["crashed"],
        arm["error"],
        arm["hash"],
    ) == (2, 1, 0, 4, 3, 5.0, False, None, "h-arm.urdf")
    assert (arm["predicted_gazebo_classic"], arm["predicted_mujoco"]) == ("refused", "refused")
    assert arm["confirmed_mujoco"] is None and files[-1]["confirmed_mujoco"] == "refused"
    assert files[5]["error"].startswith("missing.urdf") and files[5]["mass"] is None
    found = pq.read_table(folder / "findings.parquet")
    assert found.num_rows == sum(len(r["findings"]) for r in items)
    assert found.column_names == [
        "path",
        "code",
        "name",
        "severity",
        "line",
        "column",
        "file",
        "element",
        "message",
        "engine",
        "fingerprint",
    ]
    rows = found.to_pylist()
    assert rows[0]["code"] == "I002" and rows[0]["file"] == "arm.urdf"
    assert rows[-1]["engine"] == "mujoco"
    assert rows[0]["fingerprint"] == fingerprint(ARM["findings"][0])
    try:
        import duckdb
    except ImportError:
        return
    top = duckdb.sql(
        f"select code, count(*) n from '{folder / 'findings.parquet'}' "
        "group by code order by n desc, code limit 1"
    ).fetchall()
    assert top == [("C001", 3)]


def test_parquet_without_pyarrow_is_one_line(capsys, tmp_path, monkeypatch) -> None:
    from urdflint.model import optional

    monkeypatch.setattr(optional, "available", lambda module: module != "pyarrow")
    good = write(tmp_path / "r.jsonl", DATASET)
    code, out, err = run(capsys, "report", str(good), "--parquet", str(tmp_path / "t"))
    assert code == 2 and out == ""
    assert err.startswith("urdflint: error: --parquet needs pyarrow: pip install")
    assert "[cluster]" in err and err.count("\n") == 1
    assert not (tmp_path / "t").exists()


def test_the_command_imports_no_heavy_module(tmp_path: Path) -> None:
    good = write(tmp_path / "r.jsonl", DATASET)
    probe = (
        "import sys\nfrom urdflint.cli import main\n"
        f"main(['report', {str(good)!r}, '--html', {str(tmp_path / 'r.html')!r}])\n"
        "print(' '.join(sorted(sys.modules)))"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    loaded = set(done.stdout.splitlines()[-1].split())
    assert "urdflint.outputs.dataset.html" in loaded
    assert not {"pyarrow", "numpy", "trimesh", "urdflint.outputs.dataset.parquet"} & loaded


# -- real records -----------------------------------------------------------------------------


def check_jsonl(target: Path, paths: list[Path]) -> list[dict[str, Any]]:
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "urdflint",
            "check",
            "--format",
            "jsonl",
            "--matrix",
            "--exit-zero",
            "--output",
            str(target),
            *map(str, paths),
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode in (0, 2), done.stderr  # 2: a rule crashed on a file
    return records.read(target)[0]


def test_records_of_the_fixtures(capsys, tmp_path: Path) -> None:
    models = sorted((FIXTURES / "models").glob("*.urdf"))
    written = check_jsonl(tmp_path / "r.jsonl", models)
    code, out, _ = run(capsys, "report", str(tmp_path / "r.jsonl"), "--format", "json")
    assert code == 0
    s = json.loads(out)
    assert s["files"] == len(models) == len(written)
    assert sum(x["findings"] for x in s["severities"]) == sum(
        sum(r["summary"].values()) for r in written
    )
    assert sum(x["findings"] for x in s["rules"]) == sum(len(r["findings"]) for r in written)
    assert [t["target"] for t in s["matrix"]["targets"]] == list(LABELS)
    assert all(t["files"] == s["matrix"]["modelled"] for t in s["matrix"]["targets"])
    assert s["worst"][0]["path"].endswith("broken_arm.urdf")
    assert s["distributions"]["mass"]["count"] == sum(r["mass"] is not None for r in written)


@needs_corpus
def test_records_of_corpus_robots(capsys, tmp_path: Path) -> None:
    robots = [CORPUS / name / "model.urdf" for name in ("icub", "pr2", "rrbot", "ur5")]
    written = check_jsonl(tmp_path / "r.jsonl", robots)
    page = tmp_path / "report.html"
    code, out, _ = run(
        capsys, "report", str(tmp_path / "r.jsonl"), "--format", "json", "--html", str(page)
    )
    assert code == 0
    s = json.loads(out)
    assert s["files"] == 4 and s["status"]["unreadable"] == 0
    assert s["distributions"]["links"]["max"] == max(r["links"] for r in written)
    assert s["distributions"]["mass"]["max"] == round(max(r["mass"] for r in written), 6)
    icub = next(w for w in s["worst"] if w["path"].endswith("icub/model.urdf"))
    assert icub["codes"][0]["code"] == "I003"  # twelve all-zero tensors
    assert page.stat().st_size > 10_000
