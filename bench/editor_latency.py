#!/usr/bin/env python3
"""``urdflint lsp`` in real editors, Neovim and Emacs + Eglot, on a real package workspace.

    .venv/bin/python bench/editor_latency.py [--workspace DIR] [--file FILE] [--rounds 5]
        [--editors nvim,emacs] [--emacs-idle SECONDS] [--json OUT]

Opens FILE (default: PR2's ``pr2_description/urdf/forearm_v0/forearm.urdf.xacro``, a macro
file that the robots in ``pr2_description/robots/`` include; the server checks it through
them) in each editor with ``python -m urdflint lsp`` as its language server and the
workspace (default ``/work/realpkgs/PR2+pr2_common``) as the workspace folder, and measures
in the editor:

* **open**: from opening the file (the editor then starts the server) to the first
  ``publishDiagnostics`` for it that the editor handled, and to the server going quiet
  (every robot that includes the file analysed);
* **plant**: the file's first ``<axis xyz="..."/>`` becomes ``<axis xyz="0 0 0"/>`` (a
  zero axis, J007) by an edit in the buffer: from the edit to the J007 shown by the editor;
* **revert**: the line back: from the edit to the J007 gone.

``--rounds`` plant/revert rounds per session, the server left quiet between edits. Three
sessions per editor: the server with ``--no-cache``; with ``--cache-dir`` a new empty folder;
and a new session with that folder as the first left it (warm). The file is never saved.

Neovim runs headless (bench/editor_latency.lua). Emacs runs interactive, ``emacs -nw -Q``,
in a pseudo-terminal (bench/editor_latency.el) that this script types the edits into: Eglot
sends a change after ``eglot-send-changes-idle-time`` (0.5 s by default, ``--emacs-idle``)
of idleness after the last key, which needs a command loop with real input. Neovim sends a
change at once after a pause (``debounce_text_changes``, 150 ms, is shortened by the time
since the last change it sent). Needs ``nvim`` (0.7+) and ``emacs`` (28+ with Eglot: Debian
``emacs-nox elpa-eglot``). No figure is asserted: it prints a table.
"""

from __future__ import annotations

import argparse
import fcntl
import json
import os
import pty
import re
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import termios
import threading
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
PR2 = Path("/work/realpkgs/PR2+pr2_common")
FOREARM = "pr2_description/urdf/forearm_v0/forearm.urdf.xacro"
AXIS = re.compile(r'(<axis\s+xyz=")([^"]*)(")')
CODE = "J007"  # zero axis
DEBIAN = {"nvim": "neovim", "emacs": "emacs-nox elpa-eglot"}
SESSIONS = (("no-cache", None), ("new cache", "new"), ("warm cache", "again"))
KEYS = {"open": b"\x03o", "plant": b"\x03p", "revert": b"\x03r"}  # C-c o, C-c p, C-c r


def server_command(cache: Path | None) -> list[str]:
    args = ["--no-cache"] if cache is None else ["--cache-dir", str(cache)]
    return [sys.executable, "-m", "urdflint", "lsp", *args]


def run_nvim(env: dict[str, str], tmp: Path) -> dict[str, Any]:
    nvim = shutil.which("nvim")
    assert nvim is not None
    xdg = {f"XDG_{k}_HOME": str(tmp / "nvim" / k.lower()) for k in ("CONFIG", "DATA", "STATE")}
    done = subprocess.run(
        [nvim, "--headless", "-u", "NONE", "-i", "NONE", "-c",
         f"luafile {HERE / 'editor_latency.lua'}"],
        env={**os.environ, **env, **xdg}, cwd=env["B_ROOT"], capture_output=True, text=True,
        timeout=900, check=False,
    )  # fmt: skip
    out = Path(env["B_OUT"])
    if not out.is_file():
        raise RuntimeError(f"nvim wrote no report: {done.stderr[-2000:]}")
    report: dict[str, Any] = json.loads(out.read_text())
    if not report.get("ok"):
        raise RuntimeError(f"nvim: {report.get('error')}")
    return report


def _own_terminal() -> None:
    """In the child: a session of its own whose controlling terminal is the pty (stdin)."""
    os.setsid()
    fcntl.ioctl(0, termios.TIOCSCTTY, 0)


def run_emacs(env: dict[str, str], tmp: Path, timeout: float = 900) -> dict[str, Any]:
    emacs = shutil.which("emacs")
    assert emacs is not None
    want = Path(env["B_WANT"])
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
    proc = subprocess.Popen(
        [emacs, "-nw", "-Q", "-l", str(HERE / "editor_latency.el")],
        stdin=slave, stdout=slave, stderr=slave, cwd=env["B_ROOT"], preexec_fn=_own_terminal,
        env={**os.environ, **env, "TERM": "xterm-256color", "HOME": str(tmp / "emacs-home")},
    )  # fmt: skip
    os.close(slave)
    screen = bytearray()

    def drain() -> None:  # the terminal's output: read it so that Emacs never blocks
        while True:
            try:
                chunk = os.read(master, 65536)
            except OSError:
                return
            if not chunk:
                return
            screen.extend(chunk)
            del screen[:-20000]

    reader = threading.Thread(target=drain, daemon=True)
    reader.start()
    answered = ""
    deadline = time.monotonic() + timeout
    try:
        while proc.poll() is None and time.monotonic() < deadline:
            asked = want.read_text() if want.is_file() else ""
            if asked and asked != answered:
                answered = asked
                key = KEYS.get(asked.split()[0])
                if key is not None:
                    os.write(master, key)
            time.sleep(0.002)
        if proc.poll() is None:
            raise RuntimeError(f"emacs timed out after {answered!r}")
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        os.close(master)
    out = Path(env["B_OUT"])
    if not out.is_file():
        tail = bytes(screen[-3000:]).decode(errors="replace")
        raise RuntimeError(f"emacs wrote no report (last asked {answered!r}); screen: {tail}")
    report: dict[str, Any] = json.loads(out.read_text())
    if not report.get("ok"):
        raise RuntimeError(f"emacs: {report.get('error')}")
    return report


def session(
    editor: str, base: dict[str, str], cache: Path | None, tmp: Path, name: str
) -> dict[str, Any]:
    out, want = tmp / f"{editor}-{name}.json", tmp / f"{editor}-{name}.want"
    env = {**base, "B_CMD": json.dumps(server_command(cache)), "B_OUT": str(out),
           "B_WANT": str(want)}  # fmt: skip
    return (run_nvim if editor == "nvim" else run_emacs)(env, tmp)


def ms(seconds: float | None) -> str:
    return "-" if seconds is None else f"{seconds * 1e3:.0f}"


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--workspace", type=Path, default=PR2)
    parser.add_argument("--file", default=FOREARM, help="relative to the workspace, or absolute")
    parser.add_argument("--rounds", type=int, default=5, help="plant/revert rounds per session")
    parser.add_argument("--editors", default="nvim,emacs")
    parser.add_argument("--quiet", type=float, default=2.0, help="s without a publish: idle")
    parser.add_argument("--emacs-idle", type=float, help="eglot-send-changes-idle-time (0.5)")
    parser.add_argument("--emacs-eval", help="an Emacs Lisp form evaluated after the setup")
    parser.add_argument("--json", type=Path, help="write every session's report here")
    args = parser.parse_args()

    workspace = args.workspace.resolve()
    path = Path(args.file)
    path = (path if path.is_absolute() else workspace / path).resolve()
    text = path.read_text()
    found = AXIS.search(text)
    if found is None:
        raise SystemExit(f"{path}: no <axis xyz=...> to plant a zero axis in")
    line = text.count("\n", 0, found.start())
    original = text.splitlines()[line]
    start_of_line = text.rfind("\n", 0, found.start()) + 1
    planted = (
        original[: found.start(2) - start_of_line]
        + "0 0 0"
        + original[found.end(2) - start_of_line :]
    )
    editors = [e.strip() for e in args.editors.split(",") if e.strip()]
    for editor in editors:
        if editor not in DEBIAN:
            raise SystemExit(f"--editors: {editor}? (nvim, emacs)")
        if shutil.which(editor) is None:
            raise SystemExit(f"{editor} not found (Debian: apt-get install {DEBIAN[editor]})")
    base = {
        "B_FILE": str(path), "B_ROOT": str(workspace), "B_CODE": CODE, "B_LINE": str(line),
        "B_PLANTED": planted, "B_ROUNDS": str(args.rounds), "B_QUIET": str(args.quiet),
        "PYTHONPATH": str(HERE.parent),
    }  # fmt: skip
    if args.emacs_idle is not None:
        base["B_IDLE"] = str(args.emacs_idle)
    if args.emacs_eval:
        base["B_EVAL"] = args.emacs_eval

    load = loadavg()
    reports: dict[str, dict[str, dict[str, Any]]] = {}
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        for name, cache_dir in SESSIONS:  # the editors in turn: alike under a changing load
            for editor in editors:
                print(f"{editor}: {name} ...", file=sys.stderr, flush=True)
                where = None if cache_dir is None else tmp / f"{editor}-cache"
                runs = reports.setdefault(editor, {})
                runs[name] = session(editor, base, where, tmp, name.replace(" ", "-"))
    if args.json:
        args.json.write_text(json.dumps(reports, indent=1))
    print(
        f"{path.relative_to(workspace)} in {workspace.name}; plant: line {line + 1} "
        f"{original.strip()} -> {planted.strip()} ({CODE}); {args.rounds} rounds; ms"
    )
    print_table(reports)
    print(f"load average (1, 5, 15 min): before {load}, after {loadavg()}; {os.cpu_count()} CPUs")
    return 0


def loadavg() -> str:
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


def median_max(times: list[float]) -> str:
    return f"{ms(statistics.median(times))} / {ms(max(times))}"


def print_table(reports: dict[str, dict[str, dict[str, Any]]]) -> None:
    print()
    print(
        "| editor | server | open -> first publish | open -> first displayed | open -> quiet "
        "| diagnostics | edit -> J007, median / max | revert -> J007 gone, median / max "
        "| edit -> didChange sent, median |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for runs in reports.values():
        for name, r in runs.items():
            sent = ms(statistics.median(r["sent"])) if r["sent"] else "-"
            print(
                f"| {r['editor']} | {name} | {ms(r['open_first_publish'])} "
                f"| {ms(r['open_first_shown'])} | {ms(r['open_quiet'])} "
                f"| {r['open_diagnostics']} ({r['open_displayed']} displayed) "
                f"| {median_max(r['shown'])} | {median_max(r['cleared'])} | {sent} |"
            )
    print()
    for editor, runs in reports.items():
        for name, r in runs.items():
            shown, cleared, sent = r["shown"], r["cleared"], r["sent"]
            text = f"{editor} {name}: J007 " + " ".join(ms(t) for t in shown)
            text += " | gone " + " ".join(ms(t) for t in cleared)
            if len(sent) == 2 * len(shown):  # didChange sent -> the publish: the server's part
                edits = shown + cleared
                server = [a - b for a, b in zip(edits, sent[::2] + sent[1::2], strict=True)]
                text += f" | didChange sent -> handled, median {ms(statistics.median(server))}"
            if "cpu" in r:
                text += f" | Emacs CPU {r['cpu']:.1f} s, events log {r['events_chars']} chars"
            print(text)
        idle = next(iter(runs.values()))["idle"]
        if editor == "emacs":
            print(f"emacs: eglot-send-changes-idle-time {idle} s, in every edit's time")
        else:
            print(f"nvim: debounce_text_changes {idle} s, shortened by the pause before an edit")


if __name__ == "__main__":
    raise SystemExit(main())
