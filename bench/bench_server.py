#!/usr/bin/env python3
"""Load test of the HTTP service: concurrent clients against a real `urdflint serve`.

    .venv/bin/python bench/bench_server.py [--robot husky] [--meshes] [--clients 16]
                                           [--duration 30] [--url http://127.0.0.1:PORT]

Without --url it starts `python -m urdflint serve` on a free loopback port (stopped
at the end); with --url it drives a running server (loopback only; give --pid to
sample that server's memory). The clients are threads of this process, one
keep-alive connection each, POSTing the robot's model.urdf as raw application/xml
(or, with --meshes, as multipart with a zip of its meshes) until --duration has
passed or --max-requests were sent. Prints:
  1. throughput (requests/s), p50/p90/p99/max latency, errors (any non-200 or failed
     request counts; the run fails unless there are none),
  2. the server's peak memory: the largest sampled sum of VmRSS over the server process
     and its children (the lint workers), and the sum of their VmHWM at the end,
  3. one client's latency (--solo sequential requests before the load), the in-process
     lint time of the same file in this process (urdflint.linter, same confinement as the
     service: Context(root=...), best of --repeat), and the overhead ratios p50 latency /
     in-process time, under load (queueing included) and with one client,
  4. whether every response's findings equal the in-process run's (code, line, message).
"""

from __future__ import annotations

import argparse
import http.client
import io
import json
import math
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
import uuid
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus" / "robots"
LOOPBACK = {"127.0.0.1", "localhost", "::1"}
CHECK = "/v1/check"


# -- the request -------------------------------------------------------------------------


@dataclass
class Payload:
    body: bytes
    content_type: str
    urdf: bytes
    packages: dict[str, Path] = field(default_factory=dict)


def robot_path(name: str) -> Path:
    path = Path(name)
    if path.is_file():
        return path
    path = CORPUS / name / "model.urdf"
    if not path.is_file():
        sys.exit(f"bench_server: no robot {name!r} (a file, or a folder name under {CORPUS})")
    return path


def package_folders(urdf: Path) -> dict[str, Path]:
    """``{package: folder}`` from the corpus robot's package_map.json (empty if none)."""
    mapping = urdf.parent / "package_map.json"
    if not mapping.is_file():
        return {}
    raw = json.loads(mapping.read_text(encoding="utf-8"))
    return {name: (urdf.parent / rel).resolve() for name, rel in raw.items()}


def mesh_zip(packages: dict[str, Path]) -> bytes:
    """A zip whose top-level folders are the packages (``package://NAME/x`` -> ``NAME/x``)."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, folder in sorted(packages.items()):
            for file in sorted(p for p in folder.rglob("*") if p.is_file()):
                archive.write(file, f"{name}/{file.relative_to(folder).as_posix()}")
    return buffer.getvalue()


def payload(urdf: Path, with_meshes: bool) -> Payload:
    source = urdf.read_bytes()
    if not with_meshes:
        return Payload(source, "application/xml", source)
    packages = package_folders(urdf)
    if not packages:
        sys.exit(f"bench_server: --meshes needs {urdf.parent / 'package_map.json'}")
    boundary = uuid.uuid4().hex
    parts = []
    for field_name, filename, ctype, data in (
        ("urdf", "model.urdf", "application/xml", source),
        ("meshes", "meshes.zip", "application/zip", mesh_zip(packages)),
    ):
        head = (
            f'--{boundary}\r\nContent-Disposition: form-data; name="{field_name}"; '
            f'filename="{filename}"\r\nContent-Type: {ctype}\r\n\r\n'
        )
        parts.append(head.encode() + data + b"\r\n")
    body = b"".join(parts) + f"--{boundary}--\r\n".encode()
    return Payload(body, f"multipart/form-data; boundary={boundary}", source, packages)


# -- the server --------------------------------------------------------------------------


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def get(host: str, port: int, path: str, timeout: float = 5.0) -> tuple[int, bytes]:
    conn = http.client.HTTPConnection(host, port, timeout=timeout)
    try:
        conn.request("GET", path)
        response = conn.getresponse()
        return response.status, response.read()
    finally:
        conn.close()


def wait_ready(host: str, port: int, proc: subprocess.Popen[bytes] | None, limit: float) -> None:
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        if proc is not None and proc.poll() is not None:
            sys.exit(f"bench_server: the server exited with {proc.returncode} before answering")
        try:
            if get(host, port, "/healthz", 2.0)[0] == 200:
                return
        except OSError:
            pass
        time.sleep(0.2)
    sys.exit(f"bench_server: no 200 from /healthz within {limit:.0f} s")


def start_server(port: int, jobs: int | None, log: Path) -> subprocess.Popen[bytes]:
    env = dict(os.environ)
    if jobs:
        env["URDFLINT_JOBS"] = str(jobs)
    command = [
        sys.executable,
        "-m",
        "urdflint",
        "serve",
        "--host",
        "127.0.0.1",
        "--port",
        str(port),
    ]
    with log.open("wb") as out:
        return subprocess.Popen(
            command, stdout=out, stderr=subprocess.STDOUT, env=env, cwd=ROOT, start_new_session=True
        )


def stop_server(proc: subprocess.Popen[bytes]) -> None:
    if proc.poll() is None:
        proc.send_signal(signal.SIGTERM)
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)  # its own session: the server and its workers
            proc.wait()


# -- memory ------------------------------------------------------------------------------


def descendants(pid: int) -> list[int]:
    """``pid`` and every process below it (from /proc/*/stat parent ids)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        children.setdefault(ppid, []).append(int(entry.name))
    found, todo = [], [pid]
    while todo:
        current = todo.pop()
        found.append(current)
        todo.extend(children.get(current, []))
    return found


def status_kib(pid: int, key: str) -> int:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith(key + ":"):
                return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0


class MemorySampler(threading.Thread):
    """Samples the summed VmRSS of a process tree; remembers the peak and each VmHWM."""

    def __init__(self, pid: int, interval: float = 0.1) -> None:
        super().__init__(daemon=True)
        self.pid, self.interval = pid, interval
        self.peak_rss_kib = 0
        self.hwm_kib: dict[int, int] = {}
        self.processes = 0
        self.stop = threading.Event()

    def sample(self) -> None:
        pids = descendants(self.pid)
        self.processes = max(self.processes, len(pids))
        self.peak_rss_kib = max(self.peak_rss_kib, sum(status_kib(p, "VmRSS") for p in pids))
        for p in pids:
            self.hwm_kib[p] = max(self.hwm_kib.get(p, 0), status_kib(p, "VmHWM"))

    def run(self) -> None:
        while not self.stop.is_set():
            self.sample()
            self.stop.wait(self.interval)


# -- the load ----------------------------------------------------------------------------


Findings = tuple[tuple[str, int, str], ...]


@dataclass
class Tally:
    latencies: list[float] = field(default_factory=list)
    statuses: dict[str, int] = field(default_factory=dict)
    results: dict[Findings, int] = field(default_factory=dict)  # distinct finding lists
    lock: threading.Lock = field(default_factory=threading.Lock)

    def add(self, status: str, latency: float | None, body: bytes | None = None) -> None:
        found = signature(body) if body is not None else None
        with self.lock:
            self.statuses[status] = self.statuses.get(status, 0) + 1
            if latency is not None:
                self.latencies.append(latency)
            if found is not None:
                self.results[found] = self.results.get(found, 0) + 1

    @property
    def errors(self) -> int:
        return sum(n for status, n in self.statuses.items() if status != "200")


def signature(body: bytes) -> Findings:
    """The (code, line, message) of a JSON response's findings; empty if unreadable."""
    try:
        return tuple(
            sorted((f["code"], f["line"], f["message"]) for f in json.loads(body)["findings"])
        )
    except (ValueError, KeyError, TypeError):
        return (("unreadable response", 0, body[:200].decode("utf-8", "replace")),)


def client(
    host: str,
    port: int,
    path: str,
    load: Payload,
    stop_at: float,
    budget: threading.Semaphore,
    tally: Tally,
    timeout: float,
) -> None:
    headers = {"Content-Type": load.content_type, "Accept": "application/json"}
    conn = http.client.HTTPConnection(host, port, timeout=timeout)
    try:
        while time.monotonic() < stop_at and budget.acquire(blocking=False):
            start = time.perf_counter()
            try:
                conn.request("POST", path, body=load.body, headers=headers)
                response = conn.getresponse()
                body = response.read()
            except (OSError, http.client.HTTPException) as exc:
                tally.add(type(exc).__name__, None)
                conn.close()
                conn = http.client.HTTPConnection(host, port, timeout=timeout)
                continue
            elapsed = time.perf_counter() - start
            tally.add(str(response.status), elapsed, body if response.status == 200 else None)
            if response.getheader("connection", "").lower() == "close":
                conn.close()
                conn = http.client.HTTPConnection(host, port, timeout=timeout)
    finally:
        conn.close()


def drive(
    host: str,
    port: int,
    path: str,
    load: Payload,
    clients: int,
    seconds: float,
    cap: int,
    timeout: float,
) -> tuple[Tally, float]:
    tally = Tally()
    budget = threading.Semaphore(cap)
    stop_at = time.monotonic() + seconds
    threads = [
        threading.Thread(
            target=client, args=(host, port, path, load, stop_at, budget, tally, timeout)
        )
        for _ in range(clients)
    ]
    start = time.perf_counter()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return tally, time.perf_counter() - start


def percentile(sorted_values: list[float], q: float) -> float:
    """Nearest-rank percentile of an ascending list."""
    if not sorted_values:
        return float("nan")
    rank = max(1, min(len(sorted_values), math.ceil(q / 100 * len(sorted_values))))
    return sorted_values[rank - 1]


# -- the in-process baseline -------------------------------------------------------------


def in_process(load: Payload, repeat: int) -> tuple[float, float, list[tuple[str, int, str]]]:
    """(best, median) seconds of linting the same bytes here, and its (code, line, message)."""
    from urdflint.engine import config, linter
    from urdflint.engine.context import Context

    settings = config.from_mapping({})
    times: list[float] = []
    findings: list[tuple[str, int, str]] = []
    for attempt in range(repeat + 1):  # the first run pays the imports (Pinocchio, trimesh)
        with tempfile.TemporaryDirectory(prefix="urdflint-bench-") as tmp:
            root = Path(tmp)
            packages = {}
            for name, folder in load.packages.items():
                shutil.copytree(folder, root / name)
                packages[name] = root / name
            start = time.perf_counter()
            context = Context(package_paths=packages, root=root, environ={})
            result = linter.lint_bytes(load.urdf, "model.urdf", settings, context, root)
            elapsed = time.perf_counter() - start
        if attempt:
            times.append(elapsed)
        findings = sorted((f.code, f.line, f.message) for f in result.findings)
    return min(times), statistics.median(times), findings


# -- main --------------------------------------------------------------------------------


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--robot", default="husky", help="corpus robot name or a URDF file")
    parser.add_argument("--meshes", action="store_true", help="send the meshes zip too (multipart)")
    parser.add_argument("--clients", type=int, default=16, help="concurrent clients (default 16)")
    parser.add_argument("--duration", type=float, default=30.0, help="seconds of load (default 30)")
    parser.add_argument("--max-requests", type=int, default=100_000, help="bound on requests")
    parser.add_argument(
        "--warmup", type=int, default=0, help="untimed requests first (default 2x clients)"
    )
    parser.add_argument(
        "--solo", type=int, default=30, help="sequential requests of one client before the load"
    )
    parser.add_argument("--timeout", type=float, default=120.0, help="per-request timeout, s")
    parser.add_argument("--url", help="drive this running server instead of starting one")
    parser.add_argument(
        "--pid", type=int, help="with --url: the server's pid, to sample its memory"
    )
    parser.add_argument("--jobs", type=int, help="URDFLINT_JOBS for the server started here")
    parser.add_argument(
        "--query", default="", help="query string for /v1/check, e.g. target=gz-sim"
    )
    parser.add_argument("--repeat", type=int, default=10, help="in-process runs (best of)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON too")
    args = parser.parse_args()

    urdf = robot_path(args.robot)
    load = payload(urdf, args.meshes)
    path = CHECK + (f"?{args.query}" if args.query else "")

    proc = None
    log = Path(tempfile.mkstemp(prefix="urdflint-serve-", suffix=".log")[1])
    if args.url:
        parts = urlsplit(args.url)
        host, port = parts.hostname or "", parts.port or 80
        if host not in LOOPBACK:
            sys.exit("bench_server: loopback servers only (127.0.0.1, localhost, ::1)")
        wait_ready(host, port, None, 10)
        server_pid = args.pid
    else:
        host, port = "127.0.0.1", free_port()
        proc = start_server(port, args.jobs, log)
        server_pid = proc.pid
    try:
        if proc is not None:
            wait_ready(host, port, proc, 60)
        sampler = MemorySampler(server_pid) if server_pid else None
        if sampler:
            sampler.start()
        idle_rss = 0
        warm = args.warmup or 2 * args.clients
        warm_tally, _ = drive(host, port, path, load, args.clients, 600, warm, args.timeout)
        if sampler:
            sampler.sample()
            idle_rss = sampler.peak_rss_kib
        solo, _ = drive(host, port, path, load, 1, 600, args.solo, args.timeout)
        tally, wall = drive(
            host, port, path, load, args.clients, args.duration, args.max_requests, args.timeout
        )
        if sampler:
            sampler.stop.set()
            sampler.join()
            sampler.sample()
    finally:
        if proc is not None:
            stop_server(proc)

    best, median, local = in_process(load, args.repeat)
    latencies = sorted(tally.latencies)
    done = sum(tally.statuses.values())
    p50 = percentile(latencies, 50)
    solo_p50 = percentile(sorted(solo.latencies), 50)
    figures = {
        "robot": str(urdf.relative_to(CORPUS) if urdf.is_relative_to(CORPUS) else urdf),
        "urdf_bytes": len(load.urdf),
        "request_bytes": len(load.body),
        "meshes": args.meshes,
        "clients": args.clients,
        "seconds": round(wall, 2),
        "requests": done,
        "warmup_requests": sum(warm_tally.statuses.values()),
        "warmup_errors": warm_tally.errors + solo.errors,
        "throughput_rps": round(done / wall, 1) if wall else 0.0,
        "latency_ms": {
            "p50": round(p50 * 1000, 1),
            "p90": round(percentile(latencies, 90) * 1000, 1),
            "p99": round(percentile(latencies, 99) * 1000, 1),
            "max": round(latencies[-1] * 1000, 1) if latencies else None,
            "mean": round(statistics.fmean(latencies) * 1000, 1) if latencies else None,
        },
        "errors": tally.errors,
        "statuses": tally.statuses,
        "in_process_ms": {"best": round(best * 1000, 1), "median": round(median * 1000, 1)},
        "overhead_p50_over_in_process": round(p50 / best, 2) if best else None,
        "one_client_latency_ms": {
            "p50": round(solo_p50 * 1000, 1),
            "p99": round(percentile(sorted(solo.latencies), 99) * 1000, 1),
        },
        "overhead_one_client_p50_over_in_process": round(solo_p50 / best, 2) if best else None,
        "cpus": len(os.sched_getaffinity(0)),
        "server_jobs": args.jobs or os.environ.get("URDFLINT_JOBS") or "default",
    }
    if sampler:
        figures["server_memory_mib"] = {
            "processes": sampler.processes,
            "rss_after_warmup": round(idle_rss / 1024, 1),
            "peak_rss_sum": round(sampler.peak_rss_kib / 1024, 1),
            "hwm_sum": round(sum(sampler.hwm_kib.values()) / 1024, 1),
        }
    same = None
    if tally.results:
        same = set(tally.results) == {tuple(local)}
        if not same:
            for found, count in tally.results.items():
                extra = sorted(set(found) - set(local))
                missing = sorted(set(local) - set(found))
                print(f"{count} responses differ: extra {extra[:3]}, missing {missing[:3]}")
    figures["same_findings_as_in_process"] = same

    lat = figures["latency_ms"]
    print(
        f"robot            {figures['robot']} ({len(load.urdf):,} bytes; request {len(load.body):,} bytes)"
    )
    print(
        f"load             {args.clients} clients, {wall:.1f} s, {done} requests "
        f"(+{figures['warmup_requests']} warm-up), {figures['cpus']} CPUs, "
        f"server jobs {figures['server_jobs']}"
    )
    print(f"throughput       {figures['throughput_rps']} requests/s")
    print(
        f"latency          p50 {lat['p50']} ms, p90 {lat['p90']} ms, p99 {lat['p99']} ms, "
        f"max {lat['max']} ms"
    )
    print(f"errors           {tally.errors} (statuses {tally.statuses})")
    if sampler:
        mem = figures["server_memory_mib"]
        print(
            f"server memory    peak RSS {mem['peak_rss_sum']} MiB summed over {mem['processes']} "
            f"processes (after warm-up {mem['rss_after_warmup']} MiB; sum of VmHWM {mem['hwm_sum']} MiB)"
        )
    else:
        print("server memory    not sampled (give --pid with --url)")
    print(
        f"in-process lint  best {figures['in_process_ms']['best']} ms, "
        f"median {figures['in_process_ms']['median']} ms"
    )
    solo_lat = figures["one_client_latency_ms"]
    print(
        f"one client       p50 {solo_lat['p50']} ms, p99 {solo_lat['p99']} ms "
        f"({args.solo} sequential requests before the load)"
    )
    print(
        f"overhead         p50 / in-process best = {figures['overhead_p50_over_in_process']}x "
        f"under load, {figures['overhead_one_client_p50_over_in_process']}x with one client"
    )
    print(
        f"findings         {'identical to' if same else 'DIFFERENT from'} the in-process run"
        if same is not None
        else "findings         no 200 response to compare"
    )
    if args.json:
        print(json.dumps(figures, indent=2))
    errors = tally.errors + warm_tally.errors + solo.errors
    if proc is not None and errors:
        print(f"server log: {log}", file=sys.stderr)
    else:
        log.unlink(missing_ok=True)
    return 1 if errors or not done or same is False else 0


if __name__ == "__main__":
    sys.exit(main())
