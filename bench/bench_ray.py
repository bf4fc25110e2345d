#!/usr/bin/env python3
"""``urdflint check --executor ray`` against ``--jobs N`` on generated datasets: wall
times, the overhead, each worker's memory over the run, the outputs compared, and a
projection to 100,000 files on a cluster.

    .venv/bin/python bench/bench_ray.py [--files 2000] [--confirm-files 200]
        [--engines mujoco,pybullet] [--repeat 1] [--cpus 2] [--node-cpus 16]
        [--largest BYTES] [--order interleaved|sorted] [--timeout S] [--keep] [--json]

Input: ``--files`` variants of the corpus robots (../shared/corpus/robots) written by
:func:`tests.variants.make` in a temporary folder (each robot's folder with its meshes
linked and a ``urdflint.toml`` naming its packages; one defect planted in most files),
given robot by robot in turn (``--order interleaved``: a worker meets every robot's
meshes within its first files, and what its memory does after is the steady state of a
long run) or as the folder is walked (``--order sorted``: new robots, new meshes, until
the last file).
A Ray head with ``--cpus`` CPUs is started for the run on 127.0.0.1 (``ray start --head
--block`` in its own session and temporary folder, token authentication off,
``RAY_AUTH_MODE=disabled``) and stopped at the end (SIGTERM, then SIGKILL, to its process
group and session only: never ``ray stop``, which stops every Ray of the machine).

Each command is a whole process as a user runs it (interpreter, imports, Ray's connection),
from the dataset's folder, without the analysis cache (``URDFLINT_NO_CACHE=1``); one run of
each on a few files first writes the bytecode caches and is not counted; within each of
``--repeat`` turns the commands take turns (a load that comes and goes on a shared machine
spreads over all of them); the medians are reported:

  1. ``check . --jobs N --format jsonl --output F`` against ``check . --executor ray
     --ray-address HEAD --format jsonl --output F`` (joining the running head): the overhead
     ray/jobs − 1 (the issue asks ≤ 15 %). Once each, for scale: ``--jobs 1`` (serial) and
     the lxml floor (one process parsing every file with a hardened parser). Ray's own
     start-up is measured apart, in fresh processes: ``import ray``, ``ray.init(address=
     HEAD)`` and a new local ``ray.init(num_cpus=N)``, the first task (a worker started),
     what a new worker pays to import urdflint and its rules' modules (a ``--jobs`` worker,
     forked, inherits them), and the driver's ``ray.wait(num_returns=1)`` over 16 and 4096
     tasks in flight (its cost per task finished, for 5.).
  2. the same two commands with ``--confirm ENGINES`` on the first ``--confirm-files``
     files (each worker's engines in warm probes beside it, as in a ``--jobs`` worker); the
     overhead.
  3. memory: every 0.5 s while each command of 1. runs, the RSS (``/proc/PID/status``
     VmRSS) of the driver (the urdflint process) and of each worker: Ray's (processes of the
     head's session whose title starts with ``ray::``, the agents aside; ``ray::IDLE``
     until a task runs) and the ``--jobs`` pool's (the driver's children), and the engines'
     warm probes (their children, ``urdflint.engines.probe``). Per worker: the
     RSS at the first sample after it started working, at the middle of its working time,
     the largest, the last; flat when last/first ≤ 1.25 (and when not: whether the second
     half still grows, last/mid > 1.10, or it levelled off once its meshes were read). The
     head's own processes (gcs_server, raylet...) before and after, and the CPU time of
     every process (``/proc/PID/stat``: each process's own, the driver's, the workers',
     the probes'; the head's with their waited-for children): where Ray's overhead goes.
     A worker does not wait for its warm probes when it exits, so no rusage has their CPU:
     the CPU column is these sampled times summed (the last 0.5 s of a process may be
     missed), the rusage beside it.
  4. the records of the Ray run and of ``--jobs N`` compared by path, ``inputs`` aside
     (a folder listed once per process is recorded by the first of its files that process
     checks); with --confirm too.
  5. a projection for 100,000 files on nodes × ``--node-cpus`` CPUs (1, 4, 16, 64 nodes)
     from the measured CPU: the workers' per file once warm (the slope over the second half
     of the records) plus each worker's own cost (start, imports, first meshes), spread over
     the CPUs, against the driver's per file (the slope of its CPU against the records
     written) plus one ``ray.wait`` per task, the driver being one process; without and with
     --confirm (its CPU per file and per engine from 2.). What the driver holds: its RSS
     against the records written (lean mode keeps counts per file) and its peak, the head's
     gcs_server and raylet, and the JSONL bytes per file, extrapolated (a slope needs samples
     spanning 50 records at least).

The load average before and after is printed (the machine may be shared); ``--json`` also
prints every figure as JSON. Small sizes (``--files 200 --confirm-files 20``) run in about
4 minutes; the defaults in about half an hour on 2 idle CPUs. ``--keep`` keeps the
temporary folder (the dataset, each command's records and stderr, the head's log).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))  # tests.variants, urdflint

ENV = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "RAY_ADDRESS")}
ENV.update(URDFLINT_NO_CACHE="1", RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")
URDFLINT = [sys.executable, "-m", "urdflint"]
RAY_BIN = Path(sys.executable).with_name("ray")
TICK = 0.5  # seconds between memory samples
CLK = os.sysconf("SC_CLK_TCK")
AGENTS = (b"ray::DashboardAgent", b"ray::RuntimeEnvAgent")  # the head's, not workers
PROBE = b"urdflint.engines.probe"  # an engine's probe process, a worker's child
STARTING = (b"setup_worker.py", b"default_worker.py")  # a Ray worker before its title
FLAT = 1.25  # last/first within this: flat
LEVEL = 1.10  # last/mid within this: levelled off
PROJECTED = 100_000
SPAN = 50  # records a per-file slope is measured over, at least
NODES = (1, 4, 16, 64)
FLOOR = (
    "import sys\nfrom lxml import etree\n"
    "parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)\n"
    "for name in open(sys.argv[1], encoding='utf-8').read().splitlines():\n"
    "    etree.parse(name, parser)\n"
)
STARTUP = """
import json, logging, sys, time
start = time.perf_counter()
import ray
found = {"import_s": time.perf_counter() - start}
address, cpus, temp = sys.argv[1], int(sys.argv[2]), sys.argv[3]
quiet = {"log_to_driver": False, "logging_level": logging.ERROR}
start = time.perf_counter()
if address == "local":
    ray.init(address="local", num_cpus=cpus, include_dashboard=False, _temp_dir=temp, **quiet)
else:
    ray.init(address=address, **quiet)
found["init_s"] = time.perf_counter() - start

@ray.remote
def nop():
    return 0

@ray.remote
def imports():
    start = time.perf_counter()
    import importlib
    from urdflint.cli import parallel  # noqa: F401 (what a task's arguments import)
    from urdflint.engine import config, linter, registry  # noqa: F401
    from urdflint.model import optional
    rules = registry.load_rules()
    needs = set()
    for code in config.Settings().enabled():
        needs.update(rules[code].needs if code in rules else ())
    for module in sorted(needs):
        if optional.available(module):
            try:
                importlib.import_module(module)
            except Exception:
                pass
    return time.perf_counter() - start

start = time.perf_counter()
ray.get(nop.remote())
found["first_task_s"] = time.perf_counter() - start
start = time.perf_counter()
ray.get(nop.remote())
found["next_task_s"] = time.perf_counter() - start
if address != "local":
    found["worker_imports_s"] = ray.get(imports.remote())
    # the driver's ray.wait(num_returns=1) over n refs in flight, one of them done (the
    # others: calls queued behind a call that sleeps, on one actor)
    @ray.remote(num_cpus=0)
    class Gate:
        def block(self, seconds):
            time.sleep(seconds)
        def nop(self):
            return 0
    gate = Gate.remote()
    ray.get(gate.nop.remote())
    gate.block.remote(600)
    costs = {}
    for n in (16, 4096):
        refs = [gate.nop.remote() for _ in range(n - 1)] + [ray.put(0)]
        ray.wait(refs, num_returns=1)
        start = time.perf_counter()
        for _ in range(20):
            ray.wait(refs, num_returns=1)
        costs[n] = (time.perf_counter() - start) / 20
    ray.kill(gate)
    found["wait_per_ref_s"] = max(0.0, (costs[4096] - costs[16]) / (4096 - 16))
    found["wait_base_s"] = max(0.0, costs[16] - 16 * found["wait_per_ref_s"])
start = time.perf_counter()
ray.shutdown()
found["shutdown_s"] = time.perf_counter() - start
print(json.dumps(found))
"""


class BenchError(RuntimeError):
    """A command failed or timed out: the bench stops (the head is stopped all the same)."""


# -- /proc -----------------------------------------------------------------------------------


@dataclass
class Proc:
    pid: int
    ppid: int
    sid: int
    cpu_s: float  # utime + stime + cutime + cstime (waited-for children included)
    own_s: float  # utime + stime


def processes() -> dict[int, Proc]:
    """Every process now (pid, parent, session, CPU time), from /proc/PID/stat."""
    found = {}
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat", "rb") as handle:
                text = handle.read()
        except OSError:
            continue
        rest = text[text.rindex(b")") + 2 :].split()
        ticks = sum(int(x) for x in rest[11:15])
        own = int(rest[11]) + int(rest[12])
        found[int(entry.name)] = Proc(
            int(entry.name), int(rest[1]), int(rest[3]), ticks / CLK, own / CLK
        )
    return found


def cpu_of(pid: int) -> float:
    """The CPU time of ``pid`` so far (its own: user + system), in seconds."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as handle:
            text = handle.read()
    except OSError:
        return 0.0
    rest = text[text.rindex(b")") + 2 :].split()
    return (int(rest[11]) + int(rest[12])) / CLK


def cmdline(pid: int) -> bytes:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as handle:
            return handle.read()
    except OSError:
        return b""


def status(pid: int) -> dict[str, int]:
    """VmRSS and VmHWM of ``pid`` in bytes (empty when it is gone)."""
    found = {}
    try:
        with open(f"/proc/{pid}/status", "rb") as handle:
            for line in handle:
                if line.startswith((b"VmRSS:", b"VmHWM:")):
                    key, value = line.split(b":", 1)
                    found[key.decode()] = int(value.split()[0]) * 1024
    except OSError:
        return {}
    return found


def is_worker(raw: bytes) -> bool:
    """Whether a command line is a Ray worker's: its title, or (before the title is set)
    ``python .../setup_worker.py`` or ``default_worker.py`` (the raylet's own command line
    names them too, further on)."""
    if raw.startswith(b"ray::"):
        return not raw.startswith(AGENTS)
    argv = raw.split(b"\0")
    return any(arg.endswith(STARTING) for arg in argv[1:3])


def title(raw: bytes) -> str:
    """A process's name for the report: a Ray title, a program, a Python script or module."""
    parts = [p for p in raw.replace(b"\0", b" ").decode(errors="replace").split(" ") if p]
    if not parts:
        return "?"
    if parts[0].startswith("ray::"):
        return parts[0]
    program = os.path.basename(parts[0])
    if program.startswith("python"):
        for index, part in enumerate(parts[1:], 1):
            if part == "-m" and index + 1 < len(parts):
                return parts[index + 1]
            if not part.startswith("-"):
                return os.path.basename(part)  # a script (``ray start``: ray)
    return program


# -- one command, watched ----------------------------------------------------------------------


@dataclass
class Track:
    """One process over a run: (t, RSS) samples, the titles seen, its CPU time."""

    pid: int
    name: str
    samples: list[tuple[float, int]] = field(default_factory=list)
    titles: list[str] = field(default_factory=list)
    started: int | None = None  # index of the first sample at work
    cpu_first: float = 0.0
    cpu_last: float = 0.0

    def summary(self) -> dict[str, Any]:
        work = self.samples[self.started or 0 :]
        first, last = work[0][1], work[-1][1]
        mid = work[len(work) // 2][1]
        peak = max(rss for _, rss in work)
        grows = last / first > FLAT
        verdict = "flat" if not grows else ("levelled" if last / mid <= LEVEL else "grows")
        return {
            "pid": self.pid, "name": self.name, "titles": self.titles, "samples": len(work),
            "worked_s": work[-1][0] - work[0][0], "first_b": first, "mid_b": mid,
            "max_b": peak, "last_b": last, "last_first": last / first, "last_mid": last / mid,
            "verdict": verdict, "cpu_s": self.cpu_last,
        }  # fmt: skip


@dataclass
class Watch:
    """What the sampler saw during one command."""

    driver: list[tuple[float, int, int, int, float, float]] = field(default_factory=list)
    # (t, RSS, peak RSS, records written, its CPU s, the workers' CPU s so far)
    workers: dict[int, Track] = field(default_factory=dict)
    probes: dict[int, Track] = field(default_factory=dict)  # the engines' (workers' children)
    head: dict[int, Track] = field(default_factory=dict)
    first_record_s: float | None = None
    last_record_s: float | None = None  # the first sample that saw the last record


class Sampler(threading.Thread):
    """Every :data:`TICK` s: the driver's RSS and records written; the workers (``ray``: the
    head session's ``ray::`` processes; ``pool``: the driver's children) and the head's
    processes."""

    def __init__(self, pid: int, kind: str | None, head_sid: int | None, output: Path | None):
        super().__init__(daemon=True)
        self.pid, self.kind, self.head_sid, self.output = pid, kind, head_sid, output
        self.found = Watch()
        self.stop = threading.Event()
        self.start_t = time.perf_counter()
        self.records = 0
        self.records_seen = 0
        self.offset = 0

    def run(self) -> None:
        while True:
            with contextlib.suppress(Exception):  # a process gone between two reads
                self.sample()
            if self.stop.wait(TICK):
                return

    def count(self) -> int:
        if self.output is None or not self.output.exists():
            return 0
        with open(self.output, "rb") as handle:
            handle.seek(self.offset)
            data = handle.read()
        self.offset += len(data)
        self.records += data.count(b"\n")
        return self.records

    def sample(self) -> None:
        now = time.perf_counter() - self.start_t
        driver = status(self.pid)
        if not driver:
            return
        records = self.count()
        cpu = cpu_of(self.pid)
        if records and self.found.first_record_s is None:
            self.found.first_record_s = now
        if records > self.records_seen:
            self.found.last_record_s = now
            self.records_seen = records
        if self.kind is not None:
            self.workers()
        workers_cpu = sum(t.cpu_last for t in self.found.workers.values())
        sample = (now, driver["VmRSS"], driver["VmHWM"], records, cpu, workers_cpu)
        self.found.driver.append(sample)

    def workers(self) -> None:
        table = processes()
        if self.kind == "pool":
            pool = {p.pid for p in table.values() if p.ppid == self.pid}
            for proc in table.values():
                if proc.ppid == self.pid:
                    self.note(self.found.workers, proc, "pool", busy=True)
                elif proc.ppid in pool and PROBE in cmdline(proc.pid):
                    self.note(self.found.probes, proc, title(cmdline(proc.pid)), busy=True)
            return
        session = {p.pid: cmdline(p.pid) for p in table.values() if p.sid == self.head_sid}
        workers = {pid for pid, raw in session.items() if is_worker(raw)}
        for pid, raw in session.items():
            if pid in workers:
                busy = raw.startswith(b"ray::") and not raw.startswith(b"ray::IDLE")
                name = title(raw) if raw.startswith(b"ray::") else "ray::(starting)"
                self.note(self.found.workers, table[pid], name, busy=busy)
            elif table[pid].ppid not in workers:
                self.note(self.found.head, table[pid], title(raw), busy=True, own=False)
            elif PROBE in raw:  # a worker's child: an engine's probe
                self.note(self.found.probes, table[pid], title(raw), busy=True)

    def note(
        self, tracks: dict[int, Track], proc: Proc, name: str, busy: bool, own: bool = True
    ) -> None:
        """One sample of ``proc``; its CPU its own (``own``: the workers and the probes,
        whose children are the probes, sampled apart: a probe a worker stops and waits for
        would count twice) or with its waited-for children (the head's processes)."""
        rss = status(proc.pid).get("VmRSS")
        if rss is None:
            return
        track = tracks.get(proc.pid)
        if track is None:
            first = proc.own_s if own else proc.cpu_s
            track = tracks[proc.pid] = Track(proc.pid, name, cpu_first=first)
        if busy and track.started is None:
            track.started = len(track.samples)
        if name not in track.titles:
            track.titles.append(name)
        track.samples.append((time.perf_counter() - self.start_t, rss))
        track.cpu_last = proc.own_s if own else proc.cpu_s


@dataclass
class Result:
    label: str
    wall_s: float
    cpu_s: float  # the process and its waited-for descendants (rusage)
    maxrss_b: int  # the largest of those (rusage)
    returncode: int
    watch: Watch
    output: Path | None = None


def execute(
    label: str,
    argv: list[str],
    cwd: Path,
    logs: Path,
    timeout: float,
    kind: str | None = None,
    head_sid: int | None = None,
    output: Path | None = None,
    ok: tuple[int, ...] = (0, 1),
) -> Result:
    """Run ``argv`` (its own session), sampled while it runs; wall time, CPU, exit code."""
    if output is not None:
        output.unlink(missing_ok=True)
    err = logs / f"{label}.err"
    with open(logs / f"{label}.out", "wb") as out, open(err, "wb") as errs:
        start = time.perf_counter()
        proc = subprocess.Popen(
            argv, cwd=cwd, env=ENV, stdout=out, stderr=errs, start_new_session=True
        )
    sampler = Sampler(proc.pid, kind, head_sid, output)
    sampler.start_t = start
    sampler.start()
    expired = threading.Event()

    def kill() -> None:
        expired.set()
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)

    timer = threading.Timer(timeout, kill)
    timer.start()
    try:
        _, code, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
    except BaseException:  # (Ctrl-C: the command runs in its own session, stop it too)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        with contextlib.suppress(ChildProcessError):
            os.wait4(proc.pid, 0)
        proc.returncode = -signal.SIGKILL
        raise
    finally:
        timer.cancel()
        sampler.stop.set()
        sampler.join()
    proc.returncode = os.waitstatus_to_exitcode(code)
    with contextlib.suppress(ProcessLookupError):  # a pool worker left behind
        os.killpg(proc.pid, signal.SIGKILL)
    if expired.is_set():
        raise BenchError(f"{label}: no answer in {timeout:.0f} s: {' '.join(argv[:8])}...")
    if proc.returncode not in ok:
        tail = err.read_text(errors="replace")[-3000:]
        raise BenchError(f"{label}: {' '.join(argv)} exited {proc.returncode}:\n{tail}")
    cpu = usage.ru_utime + usage.ru_stime
    return Result(label, wall, cpu, usage.ru_maxrss * 1024, proc.returncode, sampler.found, output)


# -- the Ray head --------------------------------------------------------------------------------


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class Head:
    """``ray start --head --block`` on 127.0.0.1 in its own session and temporary folder."""

    def __init__(self, cpus: int, folder: Path) -> None:
        self.cpus, self.folder = cpus, folder
        self.proc: subprocess.Popen[bytes] | None = None
        self.address = ""

    def start(self, timeout: float = 120.0) -> str:
        if not RAY_BIN.exists():
            raise BenchError(
                f"no {RAY_BIN}: install the cluster extra (pip install -e '.[cluster]')"
            )
        port = free_port()
        command = [
            str(RAY_BIN), "start", "--head", "--block", "--num-cpus", str(self.cpus),
            "--node-ip-address", "127.0.0.1", "--port", str(port), "--include-dashboard",
            "false", "--disable-usage-stats", "--temp-dir", str(self.folder / "r"),
        ]  # fmt: skip
        log = self.folder / "head.log"
        with log.open("wb") as out:
            self.proc = subprocess.Popen(
                command, env=ENV, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
            )
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise BenchError(f"ray start exited: {log.read_text()[-2000:]}")
            try:
                with socket.create_connection(("127.0.0.1", port), timeout=1):
                    self.address = f"127.0.0.1:{port}"
                    return self.address
            except OSError:
                time.sleep(0.5)
        raise BenchError(f"the Ray head did not answer within {timeout:.0f} s")

    @property
    def sid(self) -> int | None:
        return self.proc.pid if self.proc is not None else None

    def stop(self) -> None:
        """SIGTERM to the head's process group, SIGKILL after 15 s; then anything left in its
        session (workers that changed group)."""
        if self.proc is None:
            return
        kill_session(self.proc, grace=15.0)
        self.proc = None


def kill_session(proc: subprocess.Popen[bytes], grace: float) -> None:
    """Stop a process started with ``start_new_session`` and everything in its session."""
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGTERM)
    with contextlib.suppress(subprocess.TimeoutExpired):
        proc.wait(timeout=grace)
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)
    with contextlib.suppress(subprocess.TimeoutExpired):
        proc.wait(timeout=10)
    for other in processes().values():
        if other.sid == proc.pid and other.pid != proc.pid:
            with contextlib.suppress(ProcessLookupError):
                os.kill(other.pid, signal.SIGKILL)


def startup(address: str, cpus: int, folder: Path, timeout: float) -> dict[str, float]:
    """Ray's own start-up in a fresh process (see STARTUP): joining ``address``, or a new
    local Ray (``local``: its own session and temporary folder, stopped after)."""
    temp = folder / "l"
    temp.mkdir(exist_ok=True)
    command = [sys.executable, "-c", STARTUP, address, str(cpus), str(temp)]
    start = time.perf_counter()
    proc = subprocess.Popen(
        command, env=ENV, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        start_new_session=True,
    )  # fmt: skip
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_session(proc, grace=5.0)  # type: ignore[arg-type]
        raise BenchError(f"ray.init({address}) did not return in {timeout:.0f} s") from None
    except BaseException:  # (SIGTERM, Ctrl-C: its session too)
        kill_session(proc, grace=0.0)  # type: ignore[arg-type]
        raise
    wall = time.perf_counter() - start
    if address == "local":  # a local Ray's processes, if ray.shutdown left some
        kill_session(proc, grace=0.0)  # type: ignore[arg-type]
    if proc.returncode != 0:
        raise BenchError(f"ray.init({address}) failed:\n{err.decode(errors='replace')[-2000:]}")
    found: dict[str, float] = json.loads(out.decode().strip().splitlines()[-1])
    found["process_s"] = wall
    return found


# -- figures ----------------------------------------------------------------------------------


def median(values: list[float]) -> float:
    return statistics.median(values) if values else float("nan")


def slope(points: list[tuple[float, float]]) -> float | None:
    """Least-squares slope of y on x (None: fewer than 5 distinct x, or x spanning less than
    :data:`SPAN` records: a small run's slope is its start-up's noise)."""
    xs = {x for x, _ in points}
    if len(xs) < 5 or max(xs) - min(xs) < SPAN:
        return None
    mx = statistics.fmean(x for x, _ in points)
    my = statistics.fmean(y for _, y in points)
    sxx = sum((x - mx) ** 2 for x, _ in points)
    return sum((x - mx) * (y - my) for x, y in points) / sxx


def memory(result: Result, files: int) -> dict[str, Any]:
    """The driver's and the workers' memory, the head's, the CPU by process kind. The
    driver's RSS and CPU per record: the slopes over the samples once a fifth of the records
    are written (before, its imports and first tasks)."""
    w = result.watch
    steady = [s for s in w.driver if s[3] >= max(1, files // 5)]
    driver = {
        "peak_b": max((s[2] for s in w.driver), default=0),
        "last_b": w.driver[-1][1] if w.driver else 0,
        "cpu_s": w.driver[-1][4] if w.driver else 0.0,
        "first_record_s": w.first_record_s,
        "last_record_s": w.last_record_s,
        "b_per_record": slope([(float(s[3]), float(s[1])) for s in steady]),
        "cpu_per_record_s": slope([(float(s[3]), s[4]) for s in steady]),
        "steady_samples": len(steady),
    }
    late = [s for s in w.driver if s[3] >= max(1, files // 2)]
    warm = slope([(float(s[3]), s[5]) for s in late])
    workers = [t.summary() for t in w.workers.values() if t.started is not None]
    idle = [t.pid for t in w.workers.values() if t.started is None]
    head: dict[str, Any] = {}
    for track in w.head.values():
        item = head.setdefault(track.name, {"first_b": 0, "last_b": 0, "max_b": 0, "cpu_s": 0.0})
        item["first_b"] += track.samples[0][1]
        item["last_b"] += track.samples[-1][1]
        item["max_b"] += max(rss for _, rss in track.samples)
        item["cpu_s"] += track.cpu_last - track.cpu_first
    return {
        "driver": driver,
        "workers": workers,
        "idle_workers": idle,
        "workers_cpu_s": sum(t.cpu_last for t in w.workers.values()),
        "workers_warm_cpu_per_file_s": warm,  # the slope over the second half of the records
        "head": head,
        "head_cpu_s": sum(v["cpu_s"] for v in head.values()),
        # the engines' warm probes: not waited for by their worker (it exits without
        # waiting), so in no rusage: sampled (the last 0.5 s of each may be missed)
        "probes": [t.summary() for t in w.probes.values() if t.samples],
        "probes_cpu_s": sum(t.cpu_last for t in w.probes.values()),
        # every process's own CPU, sampled: the driver, workers, probes (and Ray's head)
        "total_cpu_s": driver["cpu_s"]
        + sum(t.cpu_last for t in w.workers.values())
        + sum(t.cpu_last for t in w.probes.values())
        + sum(v["cpu_s"] for v in head.values()),
    }


def compare(mine: Path, theirs: Path) -> dict[str, Any]:
    """The records of two runs by path, ``inputs`` aside. ``settings`` is a digest of
    urdflint's code too: when every digest of one run maps to one digest of the other
    (``settings_renamed``), the code changed between the runs (someone editing the
    checkout), not the runs' verdicts; ``equal_but_settings`` says whether everything else
    is equal."""
    from urdflint.outputs import records

    def load(path: Path) -> dict[str, dict[str, Any]]:
        items = records.read(path)[0]
        return {i["path"]: {k: v for k, v in i.items() if k != "inputs"} for i in items}

    def without_settings(found: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
        return {p: {k: v for k, v in i.items() if k != "settings"} for p, i in found.items()}

    a, b = load(mine), load(theirs)
    pairs = {(a[p]["settings"], b[p]["settings"]) for p in a.keys() & b.keys()}
    renamed = len(pairs) == len({x for x, _ in pairs}) == len({y for _, y in pairs})
    differ = sorted(p for p in a.keys() & b.keys() if a[p] != b[p])
    keys = sorted({k for p in differ[:50] for k in a[p] if a[p].get(k) != b[p].get(k)})
    return {
        "equal": a == b, "equal_but_settings": without_settings(a) == without_settings(b),
        "settings_renamed": renamed and any(x != y for x, y in pairs),
        "records": [len(a), len(b)], "only_ray": sorted(a.keys() - b.keys())[:5],
        "only_jobs": sorted(b.keys() - a.keys())[:5], "differ": differ[:5],
        "differ_count": len(differ), "differ_keys": keys,
    }  # fmt: skip


# -- the bench --------------------------------------------------------------------------------


def interleaved(names: list[str]) -> list[str]:
    """The files robot by robot in turn (``a/0, b/0, ..., a/1, b/1, ...``)."""
    groups: dict[str, list[str]] = {}
    for name in sorted(names):
        groups.setdefault(name.split(os.sep, 1)[0], []).append(name)
    columns = list(groups.values())
    return [c[i] for i in range(max(map(len, columns), default=0)) for c in columns if i < len(c)]


def measure(args: argparse.Namespace, tmp: Path) -> dict[str, Any]:
    from tests import variants

    dataset, logs, outs = tmp / "dataset", tmp / "logs", tmp / "out"
    logs.mkdir()
    outs.mkdir()
    made = variants.make(dataset, args.files, largest=args.largest)
    names = [str(p.relative_to(dataset)) for p in made]
    if args.order == "interleaved":
        names = interleaved(names)
    listing = tmp / "files.txt"
    listing.write_text("\n".join(names) + "\n", encoding="utf-8")
    confirm_names = names[: args.confirm_files]
    engines = [e.strip() for e in args.engines.split(",") if e.strip()]
    from urdflint.engines import runner

    missing = [e for e in engines if not runner.installed(e)]
    engines = [e for e in engines if e not in missing]
    say(f"dataset: {len(made)} files in {dataset}; engines {engines or 'none'}")
    jobs = str(args.cpus)
    lean = ["--format", "jsonl", "--output"]
    timeout = args.timeout or 300 + 3.0 * len(made)
    ctimeout = args.timeout or 300 + 6.0 * len(confirm_names) * max(1, len(engines))

    head = Head(args.cpus, tmp)
    found: dict[str, Any] = {
        "files": len(made), "confirm_files": len(confirm_names), "engines": engines,
        "missing_engines": missing, "cpus": args.cpus, "repeat": args.repeat,
        "order": args.order,
        "cpu_count": os.cpu_count(), "load": [list(os.getloadavg())],
    }  # fmt: skip
    try:
        address = head.start()
        say(f"Ray head at {address} ({args.cpus} CPUs)")

        def check(label: str, extra: list[str], paths: list[str], kind: str | None,
                  limit: float) -> Result:  # fmt: skip
            out = outs / f"{label}.jsonl"
            argv = [*URDFLINT, "check", *paths, *extra, *lean, str(out)]
            result = execute(label, argv, dataset, logs, limit, kind, head.sid, out)
            say(f"  {label}: {result.wall_s:.2f} s")
            return result

        ray_flags = ["--executor", "ray", "--ray-address", address]
        pool_flags = ["--jobs", jobs]
        confirm = ["--confirm", ",".join(engines)] if engines else []
        # not counted: bytecode caches, the head's first job
        say("warm-up (not counted)")
        few = names[: min(len(names), 4 * args.cpus)]
        check("warm-jobs", pool_flags, few, None, timeout)
        check("warm-ray", ray_flags, few, "ray", timeout)
        if confirm and confirm_names:
            check("warm-jobs-confirm", [*pool_flags, *confirm], names[:2], None, ctimeout)
            check("warm-ray-confirm", [*ray_flags, *confirm], names[:2], "ray", ctimeout)

        say("Ray's start-up (fresh processes)")
        found["startup_join"] = startup(address, args.cpus, tmp, 300)
        found["startup_local"] = startup("local", args.cpus, tmp, 300)

        runs: dict[str, list[Result]] = {k: [] for k in ("jobs", "ray", "jobs_c", "ray_c")}
        for turn in range(args.repeat):
            say(f"turn {turn + 1}/{args.repeat}")
            every = ["."] if args.order == "sorted" else names
            runs["jobs"].append(check(f"jobs{turn}", pool_flags, every, "pool", timeout))
            runs["ray"].append(check(f"ray{turn}", ray_flags, every, "ray", timeout))
            if confirm and confirm_names:
                c_pool, c_ray = [*pool_flags, *confirm], [*ray_flags, *confirm]
                runs["jobs_c"].append(
                    check(f"jobsc{turn}", c_pool, confirm_names, "pool", ctimeout)
                )
                runs["ray_c"].append(check(f"rayc{turn}", c_ray, confirm_names, "ray", ctimeout))
        say("once: --jobs 1, one file, the lxml floor")
        serial = check("jobs1", ["--jobs", "1"], every, None, timeout * args.cpus)
        single = check("single", ["--jobs", "1"], names[:1], None, timeout)
        floor = execute("floor", [sys.executable, "-c", FLOOR, str(listing)], dataset, logs,
                        timeout, ok=(0,))  # fmt: skip
        say(f"  floor: {floor.wall_s:.2f} s")
        found["load"].append(list(os.getloadavg()))
    finally:
        say("stopping the Ray head")
        head.stop()

    found["runs"] = {
        k: [{"wall_s": r.wall_s, "cpu_s": r.cpu_s, "maxrss_b": r.maxrss_b} for r in v]
        for k, v in runs.items()
    }
    found["serial"] = {"wall_s": serial.wall_s, "cpu_s": serial.cpu_s}
    found["single"] = {"wall_s": single.wall_s, "cpu_s": single.cpu_s}
    found["floor"] = {"wall_s": floor.wall_s, "cpu_s": floor.cpu_s}
    found["median_s"] = {k: median([r.wall_s for r in v]) for k, v in runs.items() if v}
    med = found["median_s"]
    found["overhead"] = med["ray"] / med["jobs"] - 1
    if runs["ray_c"]:
        found["overhead_confirm"] = med["ray_c"] / med["jobs_c"] - 1
    sizes = {"jobs": len(made), "ray": len(made), "jobs_c": len(confirm_names),
             "ray_c": len(confirm_names)}  # fmt: skip
    found["memory"] = {k: memory(v[0], sizes[k]) for k, v in runs.items() if v}
    found["agree"] = compare(runs["ray"][0].output, runs["jobs"][0].output)  # type: ignore[arg-type]
    if runs["ray_c"]:
        found["agree_confirm"] = compare(runs["ray_c"][0].output, runs["jobs_c"][0].output)  # type: ignore[arg-type]
    found["jsonl_b_per_file"] = runs["ray"][0].output.stat().st_size / len(made)  # type: ignore[union-attr]
    found["projection"] = project(found, len(made), len(confirm_names), len(engines), args)
    return found


def project(
    found: dict[str, Any], files: int, cfiles: int, engines: int, args: argparse.Namespace
) -> dict[str, Any]:
    """CPU per file (Ray's workers; the driver's share, one process) and the projection to
    :data:`PROJECTED` files (see :func:`projected`)."""
    mem, join = found["memory"], found["startup_join"]
    fixed = found["single"]["cpu_s"]  # urdflint's start-up and one file, in one process
    ray_start = join["import_s"] + join["init_s"]

    def driver(key: str, count: int) -> float:
        """The driver's CPU per file: its slope once started, else its whole CPU less its
        start-up (a small run has too few samples for a slope)."""
        found_slope = mem[key]["driver"]["cpu_per_record_s"]
        if found_slope is not None:
            return max(0.0, found_slope)
        whole = median([r["cpu_s"] for r in found["runs"][key]])
        return max(0.0, whole - fixed - ray_start) / count

    per: dict[str, Any] = {
        "worker_cpu_s": mem["ray"]["workers_cpu_s"] / files,
        "driver_cpu_s": driver("ray", files),
        "jobs_driver_cpu_s": driver("jobs", files),
        "head_cpu_s": mem["ray"]["head_cpu_s"] / files,
        "serial_cpu_s": max(0.0, found["serial"]["cpu_s"] - fixed) / max(1, files - 1),
        "jobs_cpu_s": max(0.0, median([r["cpu_s"] for r in found["runs"]["jobs"]]) - fixed)
        / max(1, files - 1),
    }
    if "ray_c" in mem and engines:
        confirm_worker = (mem["ray_c"]["workers_cpu_s"] + mem["ray_c"]["probes_cpu_s"]) / cfiles
        per.update(
            confirm_worker_cpu_s=confirm_worker,
            confirm_driver_cpu_s=driver("ray_c", cfiles),
            engine_cpu_s=max(0.0, confirm_worker - per["worker_cpu_s"]) / engines,
            confirm_head_cpu_s=mem["ray_c"]["head_cpu_s"] / cfiles,
        )
    # a new worker: started (the first task) and importing urdflint, once per CPU
    worker_start = join["first_task_s"] + join.get("worker_imports_s", 0.0)
    # each worker's own cost (start, imports, the first meshes): the workers' CPU less the
    # warm cost per file (the slope over the second half) times the files, per busy worker
    warm = mem["ray"]["workers_warm_cpu_per_file_s"]
    busy = max(1, len(mem["ray"]["workers"]))
    if warm is None or warm <= 0:  # (too few samples)
        warm, cold = per["worker_cpu_s"], worker_start
    else:
        cold = max(0.0, mem["ray"]["workers_cpu_s"] - warm * files) / busy
    per.update(worker_warm_cpu_s=warm, worker_cold_s=cold,
               jobs_warm_cpu_s=mem["jobs"]["workers_warm_cpu_per_file_s"])  # fmt: skip
    rows = []
    for nodes in NODES:
        cpus = nodes * args.node_cpus
        row: dict[str, Any] = {"nodes": nodes, "cpus": cpus}
        row["plain"] = projected(warm, cold, per["driver_cpu_s"], cpus, join)
        if "confirm_worker_cpu_s" in per:
            row["confirm"] = projected(per["confirm_worker_cpu_s"], worker_start,
                                       per["confirm_driver_cpu_s"], cpus, join)  # fmt: skip
        rows.append(row)
    drv = mem["ray"]["driver"]
    grows = drv["b_per_record"] or 0.0
    control = [v for k, v in mem["ray"]["head"].items() if k in ("gcs_server", "raylet")]
    head_growth = (
        sum(v["last_b"] - v["first_b"] for v in control) / files if files >= SPAN else None
    )
    held = {
        "driver_peak_b": drv["peak_b"],
        "driver_b_per_file": drv["b_per_record"],
        "driver_projected_b": None
        if drv["b_per_record"] is None
        else drv["peak_b"] + max(0.0, grows) * (PROJECTED - files),
        "jsonl_b_per_file": found["jsonl_b_per_file"],
        "jsonl_projected_b": found["jsonl_b_per_file"] * PROJECTED,
        "head_b_per_file": head_growth,
        "head_projected_b": None
        if head_growth is None
        else sum(v["last_b"] for v in control) + max(0.0, head_growth) * (PROJECTED - files),
    }
    return {"per_file": per, "rows": rows, "memory": held, "worker_start_s": worker_start}


def projected(
    worker: float, worker_start: float, driver: float, cpus: int, join: dict[str, float]
) -> dict[str, Any]:
    """:data:`PROJECTED` files on ``cpus`` CPUs: each worker's start, then the workers' CPU
    per file spread over the CPUs, against the driver's, which is one process and also pays
    one ``ray.wait`` over the tasks in flight (4 per CPU) per task finished (chunks of files,
    as ray_run sizes them, with or without --confirm); plus joining."""
    in_flight = cpus * 4
    chunk = max(1, min(16, PROJECTED // (cpus * 8)))
    waits = PROJECTED / chunk
    wait_s = join["wait_base_s"] + join["wait_per_ref_s"] * in_flight
    workers_s = worker_start + PROJECTED * worker / cpus
    driver_s = PROJECTED * driver + waits * wait_s
    wall = join["import_s"] + join["init_s"] + max(workers_s, driver_s)
    return {
        "workers_s": workers_s, "driver_s": driver_s, "wait_s": waits * wait_s, "chunk": chunk,
        "wall_s": wall, "bound": "driver" if driver_s > workers_s else "workers",
    }  # fmt: skip


# -- the report --------------------------------------------------------------------------------


def say(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


def mb(value: float | None) -> str:
    return "-" if value is None else f"{value / 1e6:.0f} MB"


def clock(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.1f} s"
    if seconds < 7200:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.1f} h"


def table(head: tuple[str, ...], rows: list[list[str]]) -> str:
    lines = [" | ".join(head), " | ".join("---" for _ in head)]
    lines += [" | ".join(row) for row in rows]
    return "\n".join(f"| {line} |" for line in lines)


def report(f: dict[str, Any], args: argparse.Namespace) -> str:
    """The readable report: times, start-up, CPU, agreement, memory, projection."""
    med, n, c = f["median_s"], f["files"], f["cpus"]
    mem, p = f["memory"], f["projection"]
    per, held = p["per_file"], p["memory"]
    before, after = f["load"][0], f["load"][-1]
    confirmed = (f"{f['confirm_files']} with --confirm {','.join(f['engines'])}"
                 if "jobs_c" in med else "no --confirm run")  # fmt: skip
    out = [
        f"{n} files ({confirmed}), "
        f"median of {f['repeat']} run(s), a {c}-CPU Ray head and --jobs {c}, {f['cpu_count']} "
        f"CPUs; load average {before[0]:.2f} before, {after[0]:.2f} after (1 min)"
    ]
    if f["missing_engines"]:
        out.append(f"not installed, left out: {', '.join(f['missing_engines'])}")

    # 1, 2: wall times
    floor = f["floor"]["wall_s"]
    labels = {"jobs": f"check --jobs {c}", "ray": "check --executor ray"}
    if "jobs_c" in med:
        labels.update(jobs_c=f"+ --confirm, --jobs {c}", ray_c="+ --confirm, --executor ray")
    rows = [
        ["lxml parse floor (1 process)", str(n), f"{floor:.2f}", f"{f['floor']['cpu_s']:.1f}", "1"],
        ["check --jobs 1", str(n), f"{f['serial']['wall_s']:.2f}", f"{f['serial']['cpu_s']:.1f}",
         f"{f['serial']['wall_s'] / floor:.0f}"],
    ]  # fmt: skip
    for key, label in labels.items():  # every process's own CPU, sampled
        cpu_text = f"{mem[key]['total_cpu_s']:.1f}"
        count = n if key in ("jobs", "ray") else f["confirm_files"]
        rows.append([label, str(count), f"{med[key]:.2f}", cpu_text, f"{med[key] / floor:.0f}"])
    out += ["", table(("command", "files", "wall s", "CPU s", "× floor"), rows)]
    line = f"Ray overhead, ray / jobs {c} − 1: {f['overhead'] * 100:+.1f} % (goal ≤ 15 %)"
    if "overhead_confirm" in f:
        line += f"; with --confirm: {f['overhead_confirm'] * 100:+.1f} %"
    out += ["", line]

    # Ray's start-up and where the CPU went
    for key, name in (("startup_join", f"joining the {c}-CPU head"),
                      ("startup_local", f"a new local Ray ({c} CPUs)")):  # fmt: skip
        s = f[key]
        extra = ""
        if "worker_imports_s" in s:
            extra = f"; a new worker imports urdflint and its rules' modules in {s['worker_imports_s']:.2f} s"
        out.append(
            f"Ray start-up, {name}: import ray {s['import_s']:.2f} s, ray.init {s['init_s']:.2f} s, "
            f"first task {s['first_task_s']:.2f} s (a worker started), next {s['next_task_s'] * 1e3:.0f} ms, "
            f"shutdown {s['shutdown_s']:.2f} s; the whole process {s['process_s']:.2f} s{extra}"
        )
    for key, label in labels.items():
        m, drv = mem[key], mem[key]["driver"]
        cpu = median([r["cpu_s"] for r in f["runs"][key]])
        probes = f", engines' probes {m['probes_cpu_s']:.1f} s" if m["probes"] else ""
        own = f"driver {drv['cpu_s']:.1f} s, workers {m['workers_cpu_s']:.1f} s{probes}"
        if "ray" in key:
            parts = f"{own}, head {m['head_cpu_s']:.1f} s (the driver's rusage {cpu:.1f} s)"
        else:
            parts = f"{own} (rusage of the driver and its pool: {cpu:.1f} s)"
        first, last = drv["first_record_s"], drv["last_record_s"]
        span = "-" if first is None or last is None else f"{first:.1f} s to {last:.1f} s"
        out.append(f"CPU, {label}: {parts}; records written from {span}, exit at {med[key]:.1f} s")

    # 4: the outputs
    out.append("")
    for key, name in (("agree", "without --confirm"), ("agree_confirm", "with --confirm")):
        if key not in f:
            continue
        a = f[key]
        text = (f"records of Ray and --jobs {c}, {name}, equal but for inputs: {a['equal']} "
                f"({a['records'][0]} and {a['records'][1]} records)")  # fmt: skip
        if not a["equal"]:
            text += (f"; {a['differ_count']} differ in {a['differ_keys']}, e.g. {a['differ'][:2]}; "
                     f"only Ray: {a['only_ray']}, only --jobs: {a['only_jobs']}")  # fmt: skip
            if a["equal_but_settings"] and a["settings_renamed"]:
                text += ("; all else is equal, and each settings digest of one run maps to one "
                         "of the other: it hashes urdflint's code, which changed between the "
                         "runs (edits in the checkout)")  # fmt: skip
        out.append(text)

    # 3: memory
    out += ["", f"memory over the runs without --confirm (RSS every {TICK} s; flat: "
                f"last/first ≤ {FLAT}; levelled: grew, then last/mid ≤ {LEVEL})"]  # fmt: skip
    rows = []
    for key in ("jobs", "ray"):
        m, d = mem[key], mem[key]["driver"]
        growth = "-" if d["b_per_record"] is None else f"{d['b_per_record'] / 1e3:+.2f} kB/file"
        rows.append([f"{labels[key]}: driver", "-", "-", mb(d["peak_b"]), mb(d["last_b"]),
                     growth, ""])  # fmt: skip
        for w in m["workers"]:
            rows.append([
                f"{labels[key]}: pid {w['pid']} {'/'.join(w['titles'])}", mb(w["first_b"]),
                mb(w["mid_b"]), mb(w["max_b"]), mb(w["last_b"]),
                f"{w['last_first']:.2f}× (last/mid {w['last_mid']:.2f}×)", w["verdict"],
            ])  # fmt: skip
        if m["idle_workers"]:
            rows.append([f"{labels[key]}: {len(m['idle_workers'])} worker(s) never busy",
                         "", "", "", "", "", ""])  # fmt: skip
    out.append(table(("process", "first", "mid", "max", "last", "last/first", "verdict"), rows))
    from urdflint.engines import warm

    for key in ("jobs_c", "ray_c"):
        probes = mem.get(key, {}).get("probes") or []
        if probes:  # (each starts small, then imports its engine: no verdict from first)
            late = [p["last_b"] for p in probes]
            out.append(
                f"the engines' warm probes over {labels[key]}: {len(probes)} process(es) "
                f"(a new one every {warm.RECYCLE} models), the largest {mb(max(late))} at its end, "
                f"{mb(max(p['max_b'] for p in probes))} at most"
            )
    head = mem["ray"]["head"]
    if head:
        parts = [f"{k} {mb(v['first_b'])} → {mb(v['last_b'])}" for k, v in sorted(head.items())]
        out.append("the head's processes over the Ray run: " + ", ".join(parts))

    # 5: projection
    jobs_warm = per["jobs_warm_cpu_s"]
    jobs_warm_text = "" if jobs_warm is None else f", {jobs_warm * 1e3:.0f} ms warm"
    text = (f"CPU per file: --jobs 1 {per['serial_cpu_s'] * 1e3:.0f} ms; --jobs {c} "
            f"{per['jobs_cpu_s'] * 1e3:.0f} ms{jobs_warm_text} (its driver "
            f"{per['jobs_driver_cpu_s'] * 1e3:.1f} ms); Ray workers {per['worker_cpu_s'] * 1e3:.0f} ms, "
            f"{per['worker_warm_cpu_s'] * 1e3:.0f} ms warm (the second half's slope) + "
            f"{per['worker_cold_s']:.1f} s per worker, driver {per['driver_cpu_s'] * 1e3:.1f} ms, "
            f"head {per['head_cpu_s'] * 1e3:.1f} ms")  # fmt: skip
    if "engine_cpu_s" in per:
        text += (f"; with --confirm: Ray workers {per['confirm_worker_cpu_s'] * 1e3:.0f} ms "
                 f"({per['engine_cpu_s'] * 1e3:.0f} ms per engine), driver "
                 f"{per['confirm_driver_cpu_s'] * 1e3:.1f} ms, head "
                 f"{per['confirm_head_cpu_s'] * 1e3:.1f} ms")  # fmt: skip
    join = f["startup_join"]
    out += ["", text]
    out.append(
        f"projection for {PROJECTED:,} files with --executor ray on nodes × {args.node_cpus} CPUs: "
        f"workers = each worker's own cost + files × warm worker CPU / CPUs (--confirm: a "
        f"worker's start, {p['worker_start_s']:.1f} s, + files × worker CPU / CPUs); "
        f"driver (one process) = files × driver CPU + one ray.wait per task over 4 tasks per CPU "
        f"({join['wait_base_s'] * 1e6:.0f} µs + {join['wait_per_ref_s'] * 1e9:.0f} ns per ref); "
        f"wall = joining + the larger of the two"
    )
    rows = []
    for row in p["rows"]:
        cells = [f"{row['nodes']} × {args.node_cpus}"]
        for key in ("plain", "confirm"):
            r = row.get(key)
            cells += (["-", "-", "-"] if r is None else
                      [clock(r["workers_s"]), clock(r["driver_s"]),
                       f"**{clock(r['wall_s'])}** ({r['bound']})"])  # fmt: skip
        rows.append(cells)
    confirm = f"--confirm {','.join(f['engines'])}" if f["engines"] else "--confirm"
    out.append(table(("nodes × CPUs", "workers", "driver", "wall", f"{confirm}: workers",
                      "driver", "wall"), rows))  # fmt: skip
    few = "not measured (too short a run)"
    driver_b, head_b = held["driver_b_per_file"], held["head_b_per_file"]
    driver_text = few if driver_b is None else (
        f"{driver_b / 1e3:+.2f} kB per file → about {mb(held['driver_projected_b'])} for "
        f"{PROJECTED:,} files, if it grows linearly")  # fmt: skip
    head_text = few if head_b is None else (
        f"{head_b / 1e3:+.2f} kB per file → about {mb(held['head_projected_b'])} if linearly")  # fmt: skip
    out.append(
        f"the driver holds (lean --format jsonl): peak {mb(held['driver_peak_b'])} for {n} files, "
        f"{driver_text}; the head's gcs_server + raylet: {head_text}; the JSONL "
        f"{held['jsonl_b_per_file'] / 1e3:.1f} kB per file → {mb(held['jsonl_projected_b'])} on disk"
    )
    return "\n".join(out)


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--files", type=int, default=2000, help="generated files (default 2000)")
    parser.add_argument("--confirm-files", type=int, default=200,
                        help="the first N of them checked with --confirm (default 200; 0: skip)")  # fmt: skip
    parser.add_argument("--engines", default="mujoco,pybullet", help="the --confirm engines")
    parser.add_argument("--repeat", type=int, default=1, help="turns of each command (median)")
    parser.add_argument(
        "--cpus", type=int, default=2, help="the head's CPUs and --jobs (default 2)"
    )
    parser.add_argument(
        "--order",
        choices=("interleaved", "sorted"),
        default="interleaved",
        help="the files in turn robot by robot (default), or the folder as walked",
    )
    parser.add_argument("--node-cpus", type=int, default=16, help="CPUs per node, projection")
    parser.add_argument("--largest", type=int, default=None, help="corpus robots up to N bytes")
    parser.add_argument("--timeout", type=float, default=None,
                        help="seconds per command (default: from the number of files)")  # fmt: skip
    parser.add_argument("--keep", action="store_true", help="keep the temporary folder")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    args = parser.parse_args()
    args.repeat = max(1, args.repeat)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # cleanup (finally) on SIGTERM too
    from tests import variants

    if not variants.CORPUS.is_dir():
        say(f"no corpus at {variants.CORPUS} (is ../shared/corpus present?)")
        return 2
    tmp = Path(tempfile.mkdtemp(prefix="bench-ray-"))
    try:
        found = measure(args, tmp)
    except BenchError as exc:
        say(f"bench_ray: {exc}")
        if not args.keep:
            say("(--keep keeps the temporary folder: each command's stderr, the Ray logs)")
        return 1
    finally:
        if args.keep:
            say(f"kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    print(report(found, args))
    if args.json:
        print(json.dumps(found, indent=2, default=str))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
