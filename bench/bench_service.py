#!/usr/bin/env python3
"""Issue 22's service measure: many clients post real robots with mesh zips to `urdflint serve`.

    .venv/bin/python bench/bench_service.py [--mode edited|identical|both] [--clients 16]
                                            [--jobs 2] [--duration 30] [--max-requests 2000]
                                            [--robots pr2,tiago,ur5,husky,eve_r3,valkyrie]
                                            [--cold] [--cache-dir DIR] [--verify 24]
                                            [--seed N] [--json] [--url http://127.0.0.1:PORT]
                                            [--kill-every S]

Without --url it starts `python -m urdflint serve` on a free loopback port with
URDFLINT_JOBS=--jobs lint workers (stopped at the end), URDFLINT_CACHE_DIR=DIR/cache,
XDG_CACHE_HOME=DIR/xdg and, when `urdflint serve --help` lists --cache-dir, also
`--cache-dir DIR/cache`. DIR (--cache-dir, default $TMPDIR/urdflint-bench-service-cache)
is kept between runs, so a run starts with what the last one left; --cold empties it
first. The user's cache is never touched. With --url it drives a running loopback server
(its cache is its own; --cold is refused).

Every request is multipart: a corpus robot's model.urdf plus a zip of its mesh packages
(package_map.json), built once per robot, the robots taken in turn. Modes:
  edited     each request's URDF has ONE number changed: one positive <mass value> of a
             random link scaled by 1 +- 0.1..1 %, never the same edit twice in a run (the
             --seed, random unless given, is printed), so the URDF bytes are new while
             the meshes zip is byte-identical to one already sent;
  identical  the robots' files exactly as in the corpus, repeated byte for byte.
Phases, in one run against one server:
  1. first pass: one client sends every robot once, unedited (fresh server; the cache as
     the last run left it, empty with --cold);
  2. per mode: one client, --solo sequential requests (no queueing), then --clients
     clients with one keep-alive connection each until --duration has passed or
     --max-requests were sent (requests in flight are awaited; the time counts).
With --kill-every S, one lint worker (chosen at random) is SIGKILLed every S seconds during
the many-client phases, and the clients resend a 503 after its Retry-After (at most 1 s),
as a well-behaved client would; latencies count from the first send, and the report says
how many workers were killed and how many requests were answered 503 first.
Prints per phase requests/s, p50/p95/max latency and errors (any non-200 or failed request),
p50 per robot, the CPU seconds used by the server's front process (HTTP, multipart, zip
saving), by its lint workers, by this client and by the rest of the machine (with --url:
give --pid), the server's peak memory, the cache folder's size, and the targets
of issue 22 (edited >= 5 requests/s on 2 workers, p95 <= 4 s, no errors; identical >= 20/s).
After the server stops, responses are checked against an uncached in-process lint of the
same bytes (urdflint.linter.lint_path in a folder holding the packages, as a worker does;
findings compared as (code, line, message), paths shown as the worker shows them): every
first-pass and identical response, 4 one-client edited ones and --verify edited ones under
load (spread over the robots). Exit 1 on any error or differing findings; missing a target
fails only with --require-targets.
"""

from __future__ import annotations

import argparse
import contextlib
import http.client
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_server import (  # the sibling load test's helpers
    CHECK,
    CORPUS,
    LOOPBACK,
    MemorySampler,
    descendants,
    free_port,
    get,
    mesh_zip,
    package_folders,
    percentile,
    signature,
    stop_server,
)

ROOT = Path(__file__).resolve().parent.parent
ROBOTS = ("pr2", "tiago", "ur5", "husky", "eve_r3", "valkyrie")
CACHE = Path(tempfile.gettempdir()) / "urdflint-bench-service-cache"
MASS = re.compile(rb"""(<mass\s+value\s*=\s*["'])([^"']+)(["'])""")
TARGETS = {"edited_rps": 5.0, "edited_p95_s": 4.0, "identical_rps": 20.0}


# -- the requests ------------------------------------------------------------------------


@dataclass
class Robot:
    name: str
    urdf: bytes
    boundary: str
    packages: dict[str, Path]
    prefix: bytes  # multipart up to the URDF's bytes
    suffix: bytes  # the rest: the meshes zip part and the closing boundary
    masses: list[tuple[int, int, float]]  # (start, end, value) of each positive mass value

    def source(self, edit: tuple[int, bytes] | None) -> bytes:
        if edit is None:
            return self.urdf
        start, end, _ = self.masses[edit[0]]
        return self.urdf[:start] + edit[1] + self.urdf[end:]


def load_robot(name: str) -> Robot:
    urdf = CORPUS / name / "model.urdf"
    if not urdf.is_file():
        sys.exit(f"bench_service: no robot {name!r} under {CORPUS}")
    packages = package_folders(urdf)
    if not packages:
        sys.exit(f"bench_service: {name} has no package_map.json (no meshes to send)")
    source = urdf.read_bytes()
    masses = []
    for match in MASS.finditer(source):
        with contextlib.suppress(ValueError):
            value = float(match.group(2))
            if value > 0:
                masses.append((match.start(2), match.end(2), value))
    if not masses:
        sys.exit(f"bench_service: {name} has no positive <mass value> to edit")
    boundary = uuid.uuid4().hex
    head = (
        f'--{boundary}\r\nContent-Disposition: form-data; name="urdf"; filename="model.urdf"\r\n'
        "Content-Type: application/xml\r\n\r\n"
    ).encode()
    zipped = (
        f'\r\n--{boundary}\r\nContent-Disposition: form-data; name="meshes"; '
        'filename="meshes.zip"\r\nContent-Type: application/zip\r\n\r\n'
    ).encode() + mesh_zip(packages)
    tail = f"\r\n--{boundary}--\r\n".encode()
    return Robot(name, source, boundary, packages, head, zipped + tail, masses)


class Requests:
    """The run's requests: robot k mod n, edited (a new mass value each) or not."""

    def __init__(self, robots: list[Robot], seed: int) -> None:
        self.robots = robots
        self.rng = random.Random(seed)
        self.count = 0
        self.seen: set[tuple[int, int, bytes]] = set()
        self.lock = threading.Lock()

    def next(self, edited: bool) -> tuple[int, tuple[int, bytes] | None]:
        with self.lock:
            index = self.count % len(self.robots)
            self.count += 1
            if not edited:
                return index, None
            robot = self.robots[index]
            while True:
                which = self.rng.randrange(len(robot.masses))
                start, end, value = robot.masses[which]
                scale = 1 + self.rng.choice((-1, 1)) * self.rng.uniform(0.001, 0.01)
                text = f"{value * scale:.10g}".encode()
                if text != robot.urdf[start:end] and (index, which, text) not in self.seen:
                    self.seen.add((index, which, text))
                    return index, (which, text)


# -- the server --------------------------------------------------------------------------


def serve_supports_cache_dir() -> bool:
    help_text = subprocess.run(
        [sys.executable, "-m", "urdflint", "serve", "--help"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=60,
        check=False,
    ).stdout
    return "--cache-dir" in help_text


def start_server(
    port: int, jobs: int, cache: Path, log: Path
) -> tuple[subprocess.Popen[bytes], bool]:
    env = dict(
        os.environ,
        URDFLINT_JOBS=str(jobs),
        URDFLINT_CACHE_DIR=str(cache / "cache"),  # the analysis cache's folder (urdflint.cache)
        XDG_CACHE_HOME=str(cache / "xdg"),  # anything else that caches: not the user's
    )
    command = [sys.executable, "-m", "urdflint", "serve", "--host", "127.0.0.1"]
    command += ["--port", str(port), "--log-level", "warning"]
    flag = serve_supports_cache_dir()
    if flag:
        command += ["--cache-dir", str(cache / "cache")]
    with log.open("wb") as out:
        proc = subprocess.Popen(
            command, stdout=out, stderr=subprocess.STDOUT, env=env, cwd=ROOT, start_new_session=True
        )
    return proc, flag


def wait_ready(host: str, port: int, proc: subprocess.Popen[bytes] | None, limit: float) -> float:
    """Seconds until ``/readyz`` answers 200 (a worker built a Pinocchio model, loaded a mesh)."""
    start = time.monotonic()
    while time.monotonic() - start < limit:
        if proc is not None and proc.poll() is not None:
            sys.exit(f"bench_service: the server exited with {proc.returncode} before answering")
        with contextlib.suppress(OSError):
            if get(host, port, "/readyz", 2.0)[0] == 200:
                return time.monotonic() - start
        time.sleep(0.2)
    sys.exit(f"bench_service: no 200 from /readyz within {limit:.0f} s")


def cpu_seconds(pid: int | None) -> dict[int, float]:
    """User + system CPU seconds of ``pid`` and each process below it (workers, engines)."""
    if pid is None:
        return {}
    tick = os.sysconf("SC_CLK_TCK")
    found = {}
    for each in descendants(pid):
        with contextlib.suppress(OSError, ValueError, IndexError):
            fields = Path(f"/proc/{each}/stat").read_text().rsplit(")", 1)[1].split()
            found[each] = (int(fields[11]) + int(fields[12])) / tick  # utime, stime
    return found


def machine_busy_seconds() -> float:
    """CPU seconds the whole machine spent busy since boot (/proc/stat, all CPUs)."""
    try:
        values = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
    except (OSError, ValueError):
        return float("nan")
    idle = values[3] + (values[4] if len(values) > 4 else 0)  # idle, iowait
    busy = sum(values[:8]) - idle  # user nice system idle iowait irq softirq steal
    return busy / os.sysconf("SC_CLK_TCK")


def folder_size(path: Path) -> tuple[int, int]:
    files = [p for p in path.rglob("*") if p.is_file()] if path.is_dir() else []
    return len(files), sum(p.stat().st_size for p in files)


# -- the load ----------------------------------------------------------------------------


@dataclass
class Record:
    robot: int
    edit: tuple[int, bytes] | None
    status: str
    latency: float | None
    found: tuple[tuple[str, int, str], ...] | None
    retries: int = 0  # 503s answered before this one (--kill-every: a worker died under it)


@dataclass
class Phase:
    name: str
    mode: str  # "first", "edited" or "identical"
    clients: int
    records: list[Record] = field(default_factory=list)
    wall: float = 0.0
    cpu: dict[str, float] = field(default_factory=dict)  # CPU seconds used in the phase
    killed: list[int] = field(default_factory=list)  # lint workers SIGKILLed (--kill-every)
    lock: threading.Lock = field(default_factory=threading.Lock)

    def add(self, record: Record) -> None:
        with self.lock:
            self.records.append(record)

    @property
    def statuses(self) -> dict[str, int]:
        counts: dict[str, int] = {}
        for record in self.records:
            counts[record.status] = counts.get(record.status, 0) + 1
        return counts

    @property
    def errors(self) -> int:
        return sum(1 for record in self.records if record.status != "200")

    def figures(self, robots: list[Robot]) -> dict[str, object]:
        latencies = sorted(r.latency for r in self.records if r.latency is not None)
        done = len(self.records)
        per_robot = {}
        for index, robot in enumerate(robots):
            mine = sorted(
                r.latency for r in self.records if r.robot == index and r.latency is not None
            )
            if mine:
                per_robot[robot.name] = round(percentile(mine, 50), 2)
        return {
            "requests": done,
            "seconds": round(self.wall, 1),
            "rps": round(done / self.wall, 2) if self.wall else 0.0,
            "p50_s": round(percentile(latencies, 50), 2),
            "p95_s": round(percentile(latencies, 95), 2),
            "max_s": round(latencies[-1], 2) if latencies else None,
            "errors": self.errors,
            "statuses": self.statuses,
            "retried_503": sum(r.retries for r in self.records),
            "workers_killed": len(self.killed),
            "p50_s_by_robot": per_robot,
            "cpu_s": {key: round(value, 1) for key, value in self.cpu.items()},
        }


def client(
    host: str,
    port: int,
    robots: list[Robot],
    requests: Requests,
    edited: bool,
    stop_at: float,
    budget: threading.Semaphore,
    phase: Phase,
    timeout: float,
    retry: bool = False,
) -> None:
    """One client's requests; with ``retry``, a 503 is sent again after its Retry-After (at
    most 1 s), as a well-behaved client does, and the latency counts from the first send."""
    conn = http.client.HTTPConnection(host, port, timeout=timeout)
    try:
        while time.monotonic() < stop_at and budget.acquire(blocking=False):
            index, edit = requests.next(edited)
            robot = robots[index]
            body = robot.prefix + robot.source(edit) + robot.suffix
            headers = {
                "Content-Type": f"multipart/form-data; boundary={robot.boundary}",
                "Accept": "application/json",
            }
            start, retries = time.perf_counter(), 0
            while True:
                try:
                    conn.request("POST", CHECK, body=body, headers=headers)
                    response = conn.getresponse()
                    answer = response.read()
                except (OSError, http.client.HTTPException) as exc:
                    phase.add(Record(index, edit, type(exc).__name__, None, None, retries))
                    conn.close()
                    conn = http.client.HTTPConnection(host, port, timeout=timeout)
                    break
                if response.getheader("connection", "").lower() == "close":
                    conn.close()
                    conn = http.client.HTTPConnection(host, port, timeout=timeout)
                wait = response.getheader("retry-after")
                if retry and response.status == 503 and wait and retries < 20:
                    retries += 1
                    time.sleep(min(float(wait), 1.0))
                    continue
                elapsed = time.perf_counter() - start
                found = signature(answer) if response.status == 200 else None
                phase.add(Record(index, edit, str(response.status), elapsed, found, retries))
                break
    finally:
        conn.close()


def drive(
    mode: str,
    host: str,
    port: int,
    robots: list[Robot],
    requests: Requests,
    edited: bool,
    clients: int,
    seconds: float,
    cap: int,
    timeout: float,
    server_pid: int | None,
    kill_every: float = 0.0,
) -> Phase:
    name = "first pass" if mode == "first" else f"{mode}, {clients} client{'s' * (clients > 1)}"
    phase = Phase(name, mode, clients)
    budget = threading.Semaphore(cap)
    stop_at = time.monotonic() + seconds
    killing = bool(kill_every and server_pid and clients > 1)
    args = (host, port, robots, requests, edited, stop_at, budget, phase, timeout, killing)
    threads = [threading.Thread(target=client, args=args) for _ in range(clients)]
    done = threading.Event()
    if killing:
        assert server_pid is not None
        killer = threading.Thread(target=kill_workers, args=(server_pid, kill_every, done, phase))
        threads.append(killer)
    before, mine, busy = cpu_seconds(server_pid), os.times(), machine_busy_seconds()
    start = time.perf_counter()
    for thread in threads:
        thread.start()
    for thread in threads[:clients]:
        thread.join()
    phase.wall = time.perf_counter() - start
    done.set()
    for thread in threads[clients:]:
        thread.join()
    after, now, busy = cpu_seconds(server_pid), os.times(), machine_busy_seconds() - busy
    if server_pid is not None:
        used = {p: t - before.get(p, 0.0) for p, t in after.items()}  # new workers: all
        phase.cpu = {
            "server_front": used.get(server_pid, 0.0),
            "lint_workers": sum(t for p, t in used.items() if p != server_pid),
        }
    phase.cpu["this_client"] = now.user + now.system - mine.user - mine.system
    phase.cpu["others"] = busy - sum(phase.cpu.values())  # the rest of the machine
    print(f"  {name}: {len(phase.records)} requests in {phase.wall:.1f} s", file=sys.stderr)
    return phase


def lint_workers(server_pid: int) -> list[int]:
    """The server's lint workers: descendants leading their own process group (each worker
    does; the fork server and the resource tracker do not)."""
    found = []
    for pid in descendants(server_pid)[1:]:
        with contextlib.suppress(OSError):
            if os.getpgid(pid) == pid:
                found.append(pid)
    return found


def kill_workers(server_pid: int, every: float, done: threading.Event, phase: Phase) -> None:
    """SIGKILL one lint worker every ``every`` seconds until the phase is done (the busiest
    moment: workers are checking requests), as an OOM killer or an operator would."""
    rng = random.Random(server_pid)
    while not done.wait(every):
        workers = lint_workers(server_pid)
        if workers:
            victim = rng.choice(workers)
            with contextlib.suppress(OSError):
                os.kill(victim, signal.SIGKILL)
                phase.killed.append(victim)


# -- the in-process check ----------------------------------------------------------------


class InProcess:
    """Lints URDF bytes here as a worker does: in a folder holding the robot's packages."""

    def __init__(self, robots: list[Robot]) -> None:
        from urdflint.engine import config

        self.robots = robots
        self.settings = config.from_mapping({})
        self.tmp = tempfile.TemporaryDirectory(prefix="urdflint-bench-service-")
        self.roots: dict[int, Path] = {}
        self.memo: dict[tuple[int, tuple[int, bytes] | None], list[tuple[str, int, str]]] = {}

    def findings(self, index: int, edit: tuple[int, bytes] | None) -> list[tuple[str, int, str]]:
        from urdflint.server.jobs import Scrub  # the worker's: paths shown relative to root

        from urdflint.engine import linter
        from urdflint.engine.context import Context

        key = (index, edit)
        if key in self.memo:
            return self.memo[key]
        robot = self.robots[index]
        root = self.roots.get(index)
        if root is None:
            root = self.roots[index] = Path(self.tmp.name) / robot.name
            for package, folder in robot.packages.items():
                shutil.copytree(folder, root / package)
        packages = {package: root / package for package in robot.packages}
        target = root / "model.urdf"
        target.write_bytes(robot.source(edit))
        context = Context(package_paths=packages, root=root, environ={})
        with contextlib.chdir(root):
            result = linter.lint_path(target, "model.urdf", self.settings, context)
        scrub = Scrub(root, root.parent)
        self.memo[key] = sorted((f.code, f.line, scrub.text(f.message)) for f in result.findings)
        return self.memo[key]


def sample_edited(records: list[Record], count: int, rng: random.Random) -> list[Record]:
    """Up to ``count`` 200 responses, taken from each robot in turn."""
    by_robot: dict[int, list[Record]] = {}
    for record in records:
        if record.found is not None:
            by_robot.setdefault(record.robot, []).append(record)
    for group in by_robot.values():
        rng.shuffle(group)
    picked: list[Record] = []
    while len(picked) < count and any(by_robot.values()):
        for group in by_robot.values():
            if group and len(picked) < count:
                picked.append(group.pop())
    return picked


def verify(checker: InProcess, records: list[Record]) -> tuple[int, list[str]]:
    """How many responses were compared, and a line for each that differs."""
    differences = []
    for record in records:
        local = checker.findings(record.robot, record.edit)
        if record.found is not None and list(record.found) != local:
            extra = sorted(set(record.found) - set(local))[:2]
            missing = sorted(set(local) - set(record.found))[:2]
            name = checker.robots[record.robot].name
            edit = f" mass #{record.edit[0]}={record.edit[1].decode()}" if record.edit else ""
            differences.append(f"{name}{edit}: extra {extra}, missing {missing}")
    return sum(1 for r in records if r.found is not None), differences


# -- main --------------------------------------------------------------------------------


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--mode", choices=("edited", "identical", "both"), default="edited")
    parser.add_argument("--robots", default=",".join(ROBOTS), help="corpus robots with meshes")
    parser.add_argument("--clients", type=int, default=16, help="concurrent clients (default 16)")
    parser.add_argument("--jobs", type=int, default=2, help="URDFLINT_JOBS (default 2)")
    parser.add_argument(
        "--duration", type=float, default=30.0, help="seconds of load per mode (default 30)"
    )
    parser.add_argument("--max-requests", type=int, default=2000, help="bound on requests per mode")
    parser.add_argument(
        "--solo", type=int, default=12, help="one client's sequential requests per mode"
    )
    parser.add_argument("--timeout", type=float, default=120.0, help="per-request timeout, s")
    parser.add_argument("--cache-dir", type=Path, default=CACHE, help=f"default {CACHE}")
    parser.add_argument("--cold", action="store_true", help="empty --cache-dir first")
    parser.add_argument("--verify", type=int, default=24, help="edited responses to re-lint here")
    parser.add_argument("--seed", type=int, help="the edits' random seed (default: random)")
    parser.add_argument("--url", help="drive this running loopback server instead")
    parser.add_argument("--pid", type=int, help="with --url: the server's pid (memory)")
    parser.add_argument("--require-targets", action="store_true", help="exit 1 if one is missed")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    parser.add_argument(
        "--kill-every",
        type=float,
        default=0.0,
        help="SIGKILL one lint worker every S seconds during the many-client phases; clients "
        "then resend a 503 after its Retry-After (default 0: never)",
    )
    args = parser.parse_args()
    if args.url and args.cold:
        sys.exit("bench_service: --cold needs the server started here (not --url)")
    seed = args.seed if args.seed is not None else random.SystemRandom().randrange(1 << 31)
    modes = ("edited", "identical") if args.mode == "both" else (args.mode,)

    robots = [load_robot(name.strip()) for name in args.robots.split(",") if name.strip()]
    requests = Requests(robots, seed)

    cache: Path = args.cache_dir.resolve()
    proc, flag = None, False
    log = Path(tempfile.mkstemp(prefix="urdflint-serve-", suffix=".log")[1])
    if args.url:
        parts = urlsplit(args.url)
        host, port = parts.hostname or "", parts.port or 80
        if host not in LOOPBACK:
            sys.exit("bench_service: loopback servers only (127.0.0.1, localhost, ::1)")
        cache_note = "the server's own (--url)"
    else:
        if args.cold and cache.exists():
            shutil.rmtree(cache)
        cache.mkdir(parents=True, exist_ok=True)
        files, size = folder_size(cache)
        host, port = "127.0.0.1", free_port()
        proc, flag = start_server(port, args.jobs, cache, log)
        cache_note = (
            f"{cache} ({'emptied: --cold' if args.cold else 'kept from earlier runs'}; "
            f"{files} files, {size / 2**20:.1f} MiB at start; "
            + ("passed as --cache-dir" if flag else "serve has no --cache-dir: environment only")
            + ("; URDFLINT_NO_CACHE is set" if os.environ.get("URDFLINT_NO_CACHE") else "")
            + ")"
        )
    phases: list[Phase] = []
    sampler = None
    try:
        ready = wait_ready(host, port, proc, 120)
        pid = proc.pid if proc is not None else args.pid
        sampler = MemorySampler(pid) if pid else None
        if sampler:
            sampler.start()
        print(f"bench_service: ready after {ready:.1f} s; seed {seed}", file=sys.stderr)
        first = drive(
            "first", host, port, robots, requests, False, 1, 3600, len(robots), args.timeout, pid
        )
        phases.append(first)
        for mode in modes:
            edited = mode == "edited"
            requests.count = 0  # each phase starts with the first robot
            phases.append(
                drive(
                    mode,
                    host,
                    port,
                    robots,
                    requests,
                    edited,
                    1,
                    3600,
                    args.solo,
                    args.timeout,
                    pid,
                )
            )
            phases.append(
                drive(
                    mode,
                    host,
                    port,
                    robots,
                    requests,
                    edited,
                    args.clients,
                    args.duration,
                    args.max_requests,
                    args.timeout,
                    pid,
                    args.kill_every,
                )
            )
        if sampler:
            sampler.stop.set()
            sampler.join()
            sampler.sample()
    finally:
        if proc is not None:
            stop_server(proc)

    # the findings, re-linted here (after the server stopped: no CPU taken from it), with
    # no analysis cache (Context.cache stays None; the environment says so too)
    os.environ.update(
        URDFLINT_NO_CACHE="1",
        URDFLINT_CACHE_DIR=str(cache / "in-process"),
        XDG_CACHE_HOME=str(cache / "xdg"),
    )
    checker = InProcess(robots)
    rng = random.Random(seed)
    checked, differences = 0, []
    for phase in phases:
        if phase.mode == "edited":
            picked = sample_edited(phase.records, args.verify if phase.clients > 1 else 4, rng)
        else:
            picked = phase.records
        count, bad = verify(checker, picked)
        checked += count
        differences += [f"{phase.name}: {line}" for line in bad]
    checker.tmp.cleanup()

    figures: dict[str, object] = {
        "robots": {
            r.name: {"urdf_bytes": len(r.urdf), "request_bytes": len(r.prefix + r.urdf + r.suffix)}
            for r in robots
        },
        "clients": args.clients,
        "server_jobs": args.jobs if proc is not None else "the server's (--url)",
        "cpus": len(os.sched_getaffinity(0)),
        "seed": seed,
        "cache": cache_note,
        "phases": {phase.name: phase.figures(robots) for phase in phases},
        "responses_checked_in_process": checked,
        "differing_findings": differences,
    }
    if proc is not None:
        files, size = folder_size(cache)
        figures["cache_at_end"] = {"files": files, "mib": round(size / 2**20, 1)}
    if sampler:
        figures["server_peak_rss_mib"] = round(sampler.peak_rss_kib / 1024, 1)

    print(f"robots      {', '.join(r.name for r in robots)} (each with its meshes zip)")
    for r in robots:
        print(
            f"            {r.name}: URDF {len(r.urdf):,} bytes, request "
            f"{len(r.prefix) + len(r.urdf) + len(r.suffix):,} bytes, {len(r.masses)} masses"
        )
    print(
        f"server      {figures['server_jobs']} lint workers, {figures['cpus']} CPUs here, "
        f"{args.clients} clients; seed {seed}"
    )
    print(f"cache       {cache_note}")
    if "cache_at_end" in figures:
        end = figures["cache_at_end"]
        print(f"            at the end: {end['files']} files, {end['mib']} MiB")  # type: ignore[index]
    if sampler:
        print(f"memory      server peak RSS {figures['server_peak_rss_mib']} MiB (all processes)")
    print(
        f"{'phase':<24} {'requests':>8} {'seconds':>8} {'req/s':>7} {'p50 s':>7} {'p95 s':>7} "
        f"{'max s':>7} {'errors':>6}"
    )
    all_figures = figures["phases"]
    assert isinstance(all_figures, dict)
    for name, f in all_figures.items():
        print(
            f"{name:<24} {f['requests']:>8} {f['seconds']:>8} {f['rps']:>7} {f['p50_s']:>7} "
            f"{f['p95_s']:>7} {f['max_s']!s:>7} {f['errors']:>6}"
        )
    for name, f in all_figures.items():
        by_robot = ", ".join(f"{robot} {p50}" for robot, p50 in f["p50_s_by_robot"].items())
        print(f"p50 s by robot, {name}: {by_robot}")
        cpu = f["cpu_s"]
        if "server_front" in cpu:
            print(
                f"  CPU s: server front process {cpu['server_front']}, lint workers "
                f"{cpu['lint_workers']}, this client {cpu['this_client']}, other processes "
                f"{cpu['others']} (of {f['seconds']} s x {figures['cpus']} CPUs)"
            )
        if f["errors"]:
            print(f"  statuses: {f['statuses']}")
        if f["workers_killed"]:
            print(
                f"  {f['workers_killed']} lint workers SIGKILLed; {f['retried_503']} requests "
                "answered 503 and were sent again"
            )
    print(
        f"findings    {checked} responses compared with an in-process lint of the same bytes: "
        + ("all equal" if not differences else f"{len(differences)} DIFFER")
    )
    for line in differences[:10]:
        print(f"            {line}")

    missed = []
    load = {p.mode: all_figures[p.name] for p in phases if p.mode != "first" and p.clients > 1}
    if "edited" in load:
        f = load["edited"]
        print(
            f"target      edited: {f['rps']} req/s (>= {TARGETS['edited_rps']}), p95 {f['p95_s']} s "
            f"(<= {TARGETS['edited_p95_s']}), {f['errors']} errors (0)"
        )
        if f["rps"] < TARGETS["edited_rps"] or f["p95_s"] > TARGETS["edited_p95_s"] or f["errors"]:
            missed.append("edited")
    if "identical" in load:
        f = load["identical"]
        print(f"target      identical: {f['rps']} req/s (>= {TARGETS['identical_rps']})")
        if f["rps"] < TARGETS["identical_rps"]:
            missed.append("identical")
    print(f"targets     {'missed: ' + ', '.join(missed) if missed else 'met'}")
    if args.json:
        print(json.dumps(figures, indent=2))

    errors = sum(phase.errors for phase in phases)
    if proc is not None and errors:
        print(f"server log: {log}", file=sys.stderr)
    else:
        log.unlink(missing_ok=True)
    failed = errors or differences or not all(p.records for p in phases)
    return 1 if failed or (args.require_targets and missed) else 0


if __name__ == "__main__":
    sys.exit(main())
