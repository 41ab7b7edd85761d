"""``grader bench http``: throughput and latency of the HTTP API under concurrent clients.

It starts its own ``grader serve`` on 127.0.0.1 (a free port, a temporary SQLite file, the yo-yo
problem), makes one student token per client, then runs three phases, each for a bounded time and
request count: ``GET /health`` (the same-run baseline: the server stack's floor under the same
load), ``POST /check`` and ``POST /problems/yoyo/submissions``. After the submission phase
it waits for the grading workers and checks that every accepted (202) submission has exactly one
verdict in effect. It prints a table and writes ``bench-results/http.json``.

Per-user rate limits are switched off in the server it starts (``LAGRADE_RATE_LIMITS_ENABLED=false``):
the bench measures capacity, not the limiter.
"""

from __future__ import annotations

import json
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import click

__all__ = ["LoadResult", "Server", "accounted", "bench_http", "make_tokens", "run_load", "submission_bodies"]

ROOT = Path(__file__).resolve().parents[2]
YOYO = ROOT / "problems" / "yoyo.toml"
# Answers to the yo-yo's tension (T = mg/3): right and wrong, in rotation. (An unreadable answer is
# refused with 422 before it is stored: it is no submission to grade.)
ANSWERS = ["m*g/3", "m g / 3", "m*g", "(m*g)/3 + 0", "2*m*g/3", "m*g*(1/3)", "m*g/2", "g*m/3"]


def submission_bodies(count: int = len(ANSWERS) * 3990) -> list[dict]:
    """``count`` submission bodies, each a new attempt: the same text again would be the same attempt
    (answered 200 with the stored submission), so the rotation of :data:`ANSWERS` is made distinct
    by trailing spaces, which the parser ignores: every body is graded like its answer."""
    return [{"answer": "tension", "text": ANSWERS[i % len(ANSWERS)] + " " * (i // len(ANSWERS))}
            for i in range(count)]
CHECK_BODY = {"reference": "m*g*(3*cos(theta) - 2)", "variables": {
    "m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
    "theta": {"dimension": "angle", "domain": "real"}}, "kind": "expression"}
CHECK_ANSWERS = ["mg(3cos θ - 2)", "3*m*g*cos(theta) - 2*m*g", "m*g*(2*cos(theta) - 3)", "m*g*(3*cos(theta) - 2"]


class Server:
    """``grader serve`` in a child process (its own process group), on a free loopback port.

    Used by the bench and by the server tests; ``kill()`` is a SIGKILL of the whole group, as a
    crash would be.
    """

    def __init__(self, workdir: Path, *, database_url: str, problems: Path, workers: int = 2, threads: int = 16,
                 env: dict[str, str] | None = None, log_name: str = "server.log"):
        self.workdir, self.database_url, self.problems = workdir, database_url, problems
        self.workers, self.threads = workers, threads
        self.env = dict(os.environ, DATABASE_URL=database_url, PYTHONUNBUFFERED="1", **(env or {}))
        self.log_path = workdir / log_name
        self.process: subprocess.Popen | None = None
        self.base_url = ""

    def start(self, timeout: float = 120.0) -> Server:
        command = [sys.executable, "-c", "from grader.cli import main; main()", "serve", "--host", "127.0.0.1",
                   "--port", "0", "--workers", str(self.workers), "--threads", str(self.threads),
                   "--problems", str(self.problems), "--no-demo"]
        log = open(self.log_path, "ab")
        self.process = subprocess.Popen(command, cwd=self.workdir, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                        start_new_session=True)
        log.close()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            match = re.search(rb"serving on (http://127\.0\.0\.1:\d+)/", self.log_path.read_bytes())
            if match:
                self.base_url = match.group(1).decode()
                return self
            if self.process.poll() is not None:
                raise RuntimeError(f"grader serve exited with {self.process.returncode}:\n{self.log()}")
            time.sleep(0.05)
        self.kill()
        raise RuntimeError(f"grader serve did not start within {timeout:g} s:\n{self.log()}")

    def log(self) -> str:
        return self.log_path.read_text(errors="replace")[-4000:]

    def kill(self) -> None:
        """SIGKILL the server and everything in its process group: a crash, not a shutdown."""
        if self.process is not None and self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()

    def stop(self, timeout: float = 20.0) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.kill()

    def __enter__(self) -> Server:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()


def make_tokens(database_url: str, role: str, count: int) -> list[str]:
    """``count`` users with ``role`` and a bearer token each, straight into the database."""
    from grader.store.db import Database
    from grader.store.migrate import upgrade
    from grader.store.users import create_token, create_user

    upgrade(database_url)
    database = Database(database_url)
    try:
        with database.write() as session:
            return [create_token(session, create_user(session, role=role, name=f"bench {role} {n}"))
                    for n in range(count)]
    finally:
        database.dispose()


@dataclass
class LoadResult:
    name: str
    clients: int
    seconds: float = 0.0
    latencies_ms: list[float] = field(default_factory=list)
    statuses: dict[int, int] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)  # transport failures and unexpected statuses
    accepted: list[int] = field(default_factory=list)  # submission ids answered 202

    @property
    def requests(self) -> int:
        return len(self.latencies_ms)

    def percentile(self, q: float) -> float:
        ordered = sorted(self.latencies_ms)
        return ordered[min(len(ordered) - 1, int(q / 100 * len(ordered)))] if ordered else float("nan")

    def summary(self) -> dict:
        return {"name": self.name, "clients": self.clients, "seconds": round(self.seconds, 2),
                "requests": self.requests, "throughput_per_s": round(self.requests / self.seconds, 1) if self.seconds else 0,
                "p50_ms": round(self.percentile(50), 2), "p99_ms": round(self.percentile(99), 2),
                "max_ms": round(max(self.latencies_ms, default=float("nan")), 2),
                "statuses": {str(k): v for k, v in sorted(self.statuses.items())},
                "errors": len(self.errors), "error_examples": self.errors[:5], "accepted": len(self.accepted)}


def run_load(name: str, base_url: str, tokens: list[str], *, path: str, bodies: list[dict], ok: set[int],
             duration_s: float, max_requests: int, stop: threading.Event | None = None,
             method: str = "POST") -> LoadResult:
    """One client thread per token, each sending ``bodies`` in rotation until the time or count runs out."""
    import requests

    result = LoadResult(name, len(tokens))
    lock = threading.Lock()
    budget = iter(range(max_requests))
    stop = stop or threading.Event()
    deadline = time.monotonic() + duration_s

    def client(number: int, token: str) -> None:
        http = requests.Session()
        headers = {"Authorization": f"Bearer {token}"}
        sent = 0
        while time.monotonic() < deadline and not stop.is_set():
            with lock:
                if next(budget, None) is None:
                    return
            body = bodies[(number + sent) % len(bodies)]
            sent += 1
            start = time.perf_counter()
            try:
                response = http.request(method, base_url + path, json=body, headers=headers, timeout=60)
            except requests.RequestException as error:
                with lock:
                    result.errors.append(f"{type(error).__name__}: {error}"[:200])
                continue
            elapsed = (time.perf_counter() - start) * 1000
            with lock:
                result.latencies_ms.append(elapsed)
                result.statuses[response.status_code] = result.statuses.get(response.status_code, 0) + 1
                if response.status_code not in ok:
                    result.errors.append(f"{response.status_code}: {response.text[:200]}")
                elif response.status_code == 202:
                    result.accepted.append(response.json()["id"])
        http.close()

    threads = [threading.Thread(target=client, args=(n, t), daemon=True) for n, t in enumerate(tokens)]
    started = time.monotonic()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    result.seconds = time.monotonic() - started
    return result


def accounted(database_url: str, ids: list[int], timeout_s: float) -> dict:
    """Wait until every submission in ``ids`` is graded; then count verdicts in effect per submission."""
    from sqlalchemy import and_, func, select

    from grader.store.db import Database
    from grader.store.models import Submission, Verdict

    database = Database(database_url)
    wanted = set(ids)
    started = time.monotonic()
    try:
        while True:
            with database.read() as session:
                pending = session.scalar(select(func.count()).select_from(Submission)
                                         .where(Submission.status.in_(("queued", "running"))))
            if pending == 0 or time.monotonic() - started > timeout_s:
                break
            time.sleep(0.2)
        drained_s = time.monotonic() - started
        with database.read() as session:
            rows = session.execute(
                select(Submission.id, Submission.status, func.count(Verdict.id))
                .outerjoin(Verdict, and_(Verdict.submission_id == Submission.id,
                                         Verdict.grading_round == Submission.grading_round))
                .group_by(Submission.id)).all()
    finally:
        database.dispose()
    stored = {row[0]: (row[1], row[2]) for row in rows}
    return {
        "accepted": len(wanted),
        "missing": sorted(wanted - set(stored)),
        "not_graded": sorted(i for i in wanted & set(stored) if stored[i][0] not in ("done", "failed")),
        "verdicts_in_effect": {i: stored[i][1] for i in wanted if i in stored},
        "drained_after_s": round(drained_s, 2),
    }


@click.command("http")
@click.option("--clients", default=16, show_default=True, help="Concurrent clients (threads), one student each.")
@click.option("--duration", default=30.0, show_default=True, help="Seconds per phase.")
@click.option("--max-requests", default=100_000, show_default=True, help="Request cap per phase.")
@click.option("--workers", default=2, show_default=True, help="Grading workers of the server.")
@click.option("--threads", default=16, show_default=True, help="HTTP threads of the server.")
@click.option("--output", default="bench-results/http.json", show_default=True, type=click.Path(path_type=Path))
def bench_http(clients: int, duration: float, max_requests: int, workers: int, threads: int, output: Path) -> None:
    """Load the API with concurrent clients: POST /check, then submissions; report and check nothing was lost."""
    if not YOYO.exists():
        raise click.ClickException(f"{YOYO} is missing: the bench needs the yo-yo problem")
    workdir = Path(tempfile.mkdtemp(prefix="lagrade-bench-"))
    problems = workdir / "problems"
    problems.mkdir()
    shutil.copy(YOYO, problems / "yoyo.toml")
    database_url = f"sqlite:///{workdir / 'bench.sqlite'}"
    tokens = make_tokens(database_url, "student", clients)
    server = Server(workdir, database_url=database_url, problems=problems, workers=workers, threads=threads,
                    env={"LAGRADE_RATE_LIMITS_ENABLED": "false"})
    click.echo(f"starting grader serve in {workdir} ...")
    with server:
        # The same-run baseline: the cheapest request the server answers, under the same load.
        floor = run_load("GET /health (baseline)", server.base_url, tokens, path="/api/v1/health",
                         bodies=[None], ok={200}, duration_s=duration, max_requests=max_requests, method="GET")
        check = run_load("POST /check", server.base_url, tokens, path="/api/v1/check",
                         bodies=[dict(CHECK_BODY, answer=a) for a in CHECK_ANSWERS], ok={200},
                         duration_s=duration, max_requests=max_requests)
        submit = run_load("POST /problems/yoyo/submissions", server.base_url, tokens,
                          path="/api/v1/problems/yoyo/submissions",
                          bodies=submission_bodies(), ok={202},
                          duration_s=duration, max_requests=max_requests)
        grading = accounted(database_url, submit.accepted, timeout_s=max(120.0, duration * 4))
    lost = len(grading["missing"]) + len(grading["not_graded"])
    not_one = sum(1 for n in grading["verdicts_in_effect"].values() if n != 1)
    report = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()},
        "server": {"workers": workers, "threads": threads, "database": "sqlite (WAL)", "rate_limits": "off"},
        "phases": [floor.summary(), check.summary(), submit.summary()],
        "grading": {"accepted": grading["accepted"], "lost": lost, "without_exactly_one_verdict": not_one,
                    "drained_after_s": grading["drained_after_s"],
                    "graded_per_s": round(grading["accepted"] / (submit.seconds + grading["drained_after_s"]), 1)
                    if grading["accepted"] else 0},
    }
    shutil.rmtree(workdir, ignore_errors=True)
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(json.dumps(report, indent=2) + "\n")
    _print_table(report)
    click.echo(f"wrote {output}")
    if lost or not_one or floor.errors or check.errors or submit.errors:
        raise click.ClickException(f"{len(floor.errors) + len(check.errors) + len(submit.errors)} errors, "
                                   f"{lost} lost submissions, "
                                   f"{not_one} without exactly one verdict")


def _print_table(report: dict) -> None:
    click.echo(f"\n{'phase':34} {'clients':>7} {'requests':>9} {'req/s':>8} {'p50 ms':>8} {'p99 ms':>8} "
               f"{'errors':>7} {'p50 / baseline':>15}")
    floor = report["phases"][0]["p50_ms"]
    for p in report["phases"]:
        ratio = f"{p['p50_ms'] / floor:.1f}x" if floor else "-"
        click.echo(f"{p['name']:34} {p['clients']:>7} {p['requests']:>9} {p['throughput_per_s']:>8} "
                   f"{p['p50_ms']:>8} {p['p99_ms']:>8} {p['errors']:>7} {ratio:>15}")
    g = report["grading"]
    click.echo(f"\ngrading: {g['accepted']} accepted, {g['lost']} lost, {g['without_exactly_one_verdict']} without "
               f"exactly one verdict; queue drained {g['drained_after_s']} s after the last submission "
               f"({g['graded_per_s']} graded/s overall)\n")
