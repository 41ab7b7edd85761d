"""``grader bench isolation``: does one user's abuse slow everyone else's ``POST /check``?

It starts its own ``grader serve`` (as ``grader bench http`` does, with the server's real rate limits,
size caps and derivation budget) and measures the ``POST /check`` latency of a few well-behaved
students, each sending one check a second, in three phases:

1. **quiet**: nothing else runs; the reference median (measured half before and half after the flood).
2. **oversized flood**: meanwhile one student sends ``POST /check`` bodies far over the size cap, as
   fast as ``--flood-clients`` connections allow.
3. **pathological uploads**: meanwhile ``--uploads`` scene files that the engine cannot derive in
   time (a chain of three pendulums) are uploaded at once by instructors, two each; each upload
   answers ``202`` and is derived by the derivation workers, one at a time, in niced sandbox children.

It prints one table with each phase's median and its ratio to the quiet median (the target is at
most 2x), and writes ``bench-results/isolation.json``.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import platform
import shutil
import statistics
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import click

__all__ = ["pathological_scene", "bench_isolation"]

TARGET_RATIO = 2.0


def pathological_scene(links: int = 4, slug: str | None = None) -> str:
    """A valid scene the engine is slow on: a chain of ``links`` pendulums in absolute angles.

    Two links derive in under a second and three in about one and a half; four take several
    seconds (the coupled mass matrix is inverted symbolically), so with four links every
    derivation runs into a time limit of a second or two.
    """
    terms = []
    for k in range(links):
        xdot = " + ".join(f"cos(q{i})*q{i}dot" for i in range(k + 1))
        ydot = " + ".join(f"sin(q{i})*q{i}dot" for i in range(k + 1))
        terms.append(f"({xdot})^2 + ({ydot})^2")
    coordinates = "\n".join(f'q{i} = {{ dimension = "angle" }}' for i in range(links))
    potential = " + ".join(f"{links - i}*cos(q{i})" for i in range(links))
    return f'''id = "{slug or f'chain{links}'}"
title = "A chain of {links} pendulums"
statement = "Equal bobs of mass $m$ on light rods of length $l$, each hanging from the one above."
[parameters]
m = {{ dimension = "mass", domain = "positive" }}
g = {{ dimension = "acceleration", domain = "positive" }}
l = {{ dimension = "length", domain = "positive" }}
[coordinates]
{coordinates}
[energy]
kinetic = "m*l^2/2*({' + '.join(terms)})"
potential = "-m*g*l*({potential})"
[[answers]]
name = "first"
prompt = "Angular acceleration of the top link"
expr = "q0ddot"
dimension = "angular_acceleration"
'''


@dataclass
class Calls:
    """Latencies and statuses of one kind of request in one phase."""

    name: str
    latencies_ms: list[float] = field(default_factory=list)
    statuses: dict[int, int] = field(default_factory=dict)
    failures: list[str] = field(default_factory=list)
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def add(self, ms: float, status: int) -> None:
        with self.lock:
            self.latencies_ms.append(ms)
            self.statuses[status] = self.statuses.get(status, 0) + 1

    def median(self) -> float:
        return statistics.median(self.latencies_ms) if self.latencies_ms else float("nan")

    def p90(self) -> float:
        ordered = sorted(self.latencies_ms)
        return ordered[min(len(ordered) - 1, int(0.9 * len(ordered)))] if ordered else float("nan")

    def summary(self) -> dict:
        return {"name": self.name, "requests": len(self.latencies_ms), "p50_ms": round(self.median(), 2),
                "p90_ms": round(self.p90(), 2), "max_ms": round(max(self.latencies_ms, default=float("nan")), 2),
                "statuses": {str(k): v for k, v in sorted(self.statuses.items())},
                "failures": len(self.failures), "failure_examples": self.failures[:3]}


def _timed(http, calls: Calls, method: str, url: str, **kwargs) -> None:
    import requests

    start = time.perf_counter()
    try:
        response = http.request(method, url, timeout=60, **kwargs)
    except requests.RequestException as error:
        with calls.lock:
            calls.failures.append(f"{type(error).__name__}: {error}"[:200])
        return
    calls.add((time.perf_counter() - start) * 1000, response.status_code)


def _paced_checks(base_url: str, tokens: list[str], stop: threading.Event, calls: Calls, interval_s: float) -> list:
    """One thread per token: a check every ``interval_s`` (under the per-user rate limit)."""
    import requests

    from grader.bench.http import CHECK_ANSWERS, CHECK_BODY

    def client(number: int, token: str) -> None:
        http = requests.Session()
        headers = {"Authorization": f"Bearer {token}"}
        sent = 0
        stop.wait(interval_s * number / len(tokens))  # spread the clients over the interval
        while not stop.is_set():
            started = time.monotonic()
            body = dict(CHECK_BODY, answer=CHECK_ANSWERS[(number + sent) % len(CHECK_ANSWERS)])
            _timed(http, calls, "POST", base_url + "/api/v1/check", json=body, headers=headers)
            sent += 1
            stop.wait(max(0.0, interval_s - (time.monotonic() - started)))
        http.close()

    return [threading.Thread(target=client, args=(n, t), daemon=True) for n, t in enumerate(tokens)]


def _flood(base_url: str, token: str, clients: int, body_bytes: int, duration_s: float, results) -> None:
    """In a process of its own (so its threads do not slow the measuring clients' GIL): ``clients``
    connections of one user sending oversized ``POST /check`` bodies back to back for ``duration_s``."""
    import requests

    calls = Calls("oversized POST /check flood")
    body = b'{"reference": "m", "answer": "m", "variables": {}, "pad": "' + b" " * body_bytes + b'"}'
    deadline = time.monotonic() + duration_s

    def client() -> None:
        http = requests.Session()
        headers = {"Authorization": f"Bearer {token}", "Content-Type": "application/json"}
        while time.monotonic() < deadline:
            _timed(http, calls, "POST", base_url + "/api/v1/check", data=body, headers=headers)
        http.close()

    threads = [threading.Thread(target=client, daemon=True) for _ in range(clients)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    results.put((calls.latencies_ms, calls.statuses, calls.failures))


def _uploads(base_url: str, tokens: list[str], count: int, calls: Calls) -> list[str]:
    """``count`` pathological scenes uploaded at once (two per instructor); returns the job URLs."""
    import requests

    locations: list[str] = []
    lock = threading.Lock()

    def upload(number: int) -> None:
        http = requests.Session()
        headers = {"Authorization": f"Bearer {tokens[number % len(tokens)]}", "Content-Type": "application/toml"}
        source = pathological_scene(5, slug=f"chain5-{number}").encode()  # over a minute: past the 20 s budget
        start = time.perf_counter()
        try:
            response = http.post(base_url + "/api/v1/problems", data=source, headers=headers, timeout=60)
        except requests.RequestException as error:
            with calls.lock:
                calls.failures.append(f"{type(error).__name__}: {error}"[:200])
            return
        calls.add((time.perf_counter() - start) * 1000, response.status_code)
        if response.status_code == 202:
            with lock:
                locations.append(response.headers["Location"])
        http.close()

    threads = [threading.Thread(target=upload, args=(n,), daemon=True) for n in range(count)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return locations


def _job_statuses(base_url: str, token_of: dict[str, str], locations: list[str]) -> dict:
    import requests

    counts: dict[str, int] = {}
    errors: list[str] = []
    for location in locations:
        body = requests.get(base_url + location, headers={"Authorization": f"Bearer {token_of[location]}"},
                            timeout=30).json()
        counts[body["status"]] = counts.get(body["status"], 0) + 1
        if body.get("error"):
            errors.append(body["error"])
    return {"statuses": counts, "error_examples": errors[:2]}


@click.command("isolation")
@click.option("--duration", default=20.0, show_default=True, help="Seconds per phase.")
@click.option("--users", default=8, show_default=True, help="Well-behaved students measuring POST /check.")
@click.option("--interval", default=0.75, show_default=True, help="Seconds between one student's checks.")
@click.option("--flood-clients", default=8, show_default=True, help="Connections of the flooding student.")
@click.option("--flood-kib", default=2048, show_default=True, help="Size of each flood body, in KiB.")
@click.option("--uploads", default=20, show_default=True, help="Pathological scene uploads at once.")
@click.option("--output", default="bench-results/isolation.json", show_default=True,
              type=click.Path(path_type=Path))
def bench_isolation(duration: float, users: int, interval: float, flood_clients: int, flood_kib: int,
                    uploads: int, output: Path) -> None:
    """Other users' POST /check under an oversized-request flood and concurrent pathological uploads."""
    from grader.bench.http import YOYO, Server, make_tokens

    workdir = Path(tempfile.mkdtemp(prefix="lagrade-isolation-"))
    problems = workdir / "problems"
    problems.mkdir()
    shutil.copy(YOYO, problems / "yoyo.toml")
    database_url = f"sqlite:///{workdir / 'bench.sqlite'}"
    students = make_tokens(database_url, "student", users + 1)
    measuring, flooder = students[:users], students[users]
    instructors = make_tokens(database_url, "instructor", max(1, (uploads + 1) // 2))
    server = Server(workdir, database_url=database_url, problems=problems)
    click.echo(f"starting grader serve in {workdir} ...")
    phases: list[dict] = []
    with server:
        base = server.base_url

        def phase(name: str, background: list[threading.Thread], stop: threading.Event,
                  seconds: float = duration) -> Calls:
            checks = Calls(f"POST /check, other users ({name})")
            measure_stop = threading.Event()
            threads = _paced_checks(base, measuring, measure_stop, checks, interval)
            for thread in background + threads:
                thread.start()
            time.sleep(seconds)
            measure_stop.set()
            stop.set()
            for thread in background + threads:
                thread.join(65)
            return checks

        warm = Calls("warm-up")
        warm_stop = threading.Event()
        warmers = _paced_checks(base, measuring, warm_stop, warm, interval)
        for thread in warmers:  # start the checkers' sandbox children before anything is measured
            thread.start()
        time.sleep(min(5.0, duration))
        warm_stop.set()
        for thread in warmers:
            thread.join(65)

        # The quiet reference is measured in two halves, before and after the flood, so that a change
        # in the machine's other load during the run shifts the reference as much as the phases.
        quiet = phase("quiet", [], threading.Event(), duration / 2)

        context = multiprocessing.get_context("spawn")
        results = context.Queue()
        flooder_process = context.Process(target=_flood, args=(base, flooder, flood_clients, flood_kib * 1024,
                                                                duration, results), daemon=True)
        flooder_process.start()
        flooded = phase("oversized flood", [], threading.Event())
        flood_calls = Calls("oversized POST /check flood")
        flood_calls.latencies_ms, flood_calls.statuses, flood_calls.failures = results.get(timeout=120)
        flooder_process.join(30)
        phases.append({"phase": "oversized flood", "checks": flooded.summary(), "abuse": flood_calls.summary()})
        after = phase("quiet", [], threading.Event(), duration / 2)
        halves = {"before_flood_p50_ms": round(quiet.median(), 2), "after_flood_p50_ms": round(after.median(), 2)}
        quiet.latencies_ms += after.latencies_ms
        for status, count in after.statuses.items():
            quiet.statuses[status] = quiet.statuses.get(status, 0) + count
        quiet.failures += after.failures
        phases.insert(0, {"phase": "quiet", "checks": quiet.summary(), "halves": halves})

        upload_calls = Calls("POST /problems (pathological scenes)")
        locations: list[str] = []
        upload_stop = threading.Event()
        uploader = threading.Thread(target=lambda: locations.extend(_uploads(base, instructors, uploads, upload_calls)),
                                    daemon=True)
        pathological = phase("pathological uploads", [uploader], upload_stop)
        jobs = _job_statuses(base, _owner_tokens(base, instructors, locations), locations)
        phases.append({"phase": "pathological uploads", "checks": pathological.summary(),
                       "abuse": upload_calls.summary(), "jobs_after_phase": jobs})
    shutil.rmtree(workdir, ignore_errors=True)

    reference = phases[0]["checks"]["p50_ms"]
    for entry in phases:
        entry["ratio_to_quiet"] = round(entry["checks"]["p50_ms"] / reference, 2) if reference else None
    report = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()},
        "settings": {"duration_s": duration, "users": users, "interval_s": interval, "flood_clients": flood_clients,
                     "flood_body_kib": flood_kib, "uploads": uploads, "target_ratio": TARGET_RATIO,
                     "rate_limits": "on (the server's defaults)"},
        "phases": phases,
    }
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(json.dumps(report, indent=2) + "\n")
    _print_table(report)
    click.echo(f"wrote {output}")
    over = [p["phase"] for p in phases if p["ratio_to_quiet"] is None or p["ratio_to_quiet"] > TARGET_RATIO]
    lost = sum(p["checks"]["failures"] for p in phases)
    if over or lost:
        raise click.ClickException(f"other users' /check median over {TARGET_RATIO:g}x quiet in: {', '.join(over)}; "
                                   f"{lost} checks failed" if over else f"{lost} checks failed")


def _owner_tokens(base_url: str, instructors: list[str], locations: list[str]) -> dict[str, str]:
    """Which instructor's token may read each job (uploads went out two per instructor, in any order)."""
    import requests

    owners = {}
    for location in locations:
        for token in instructors:
            if requests.get(base_url + location, headers={"Authorization": f"Bearer {token}"},
                            timeout=30).status_code == 200:
                owners[location] = token
                break
    return owners


def _print_table(report: dict) -> None:
    click.echo(f"\n{'phase':22} {'other users: /check':>20} {'p50 ms':>8} {'p90 ms':>8} {'x quiet':>8}   "
               f"{'meanwhile':<40}")
    for entry in report["phases"]:
        checks = entry["checks"]
        abuse = entry.get("abuse")
        meanwhile = "-"
        if abuse:
            statuses = ", ".join(f"{k}: {v}" for k, v in abuse["statuses"].items())
            meanwhile = f"{abuse['requests']} requests ({statuses}), p50 {abuse['p50_ms']} ms"
        if "jobs_after_phase" in entry:
            jobs = entry["jobs_after_phase"]["statuses"]
            meanwhile += "; jobs " + ", ".join(f"{k}: {v}" for k, v in sorted(jobs.items()))
        click.echo(f"{entry['phase']:22} {checks['requests']:>20} {checks['p50_ms']:>8} {checks['p90_ms']:>8} "
                   f"{entry['ratio_to_quiet']:>7}x   {meanwhile}")
    for entry in report["phases"]:
        for error in entry.get("jobs_after_phase", {}).get("error_examples", [])[:1]:
            click.echo(f"\na failed derivation says: {error}")
    click.echo(f"\ntarget: other users' /check median within {TARGET_RATIO:g}x of the quiet median\n")
