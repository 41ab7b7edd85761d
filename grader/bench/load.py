"""``grader bench load``: how grading and accepting scale with processes, on this machine.

Two tables, each measured in one run on a throwaway PostgreSQL cluster (``.ci/postgres``) and a
throwaway Redis server (Debian's ``redis-server``), both on free loopback ports:

- **graded per second**: ``N`` submissions of the yo-yo's tension are committed as queued, then
  graded by the embedded default (``grader serve``'s two worker threads, in-process), and by 1 and 2
  Celery worker processes (``--pool solo``, each with its own sandbox child). The clock runs from the
  moment the workers are ready and the work is announced until the last verdict is committed.
- **accepted per second**: ``POST /api/v1/problems/yoyo/submissions`` from 16 client threads for a
  fixed time against ``gunicorn grader.web.wsgi:app`` with 1 and 2 worker processes (grading handed
  to the broker, so the web processes only accept).

The scaling ratio is each row's rate over its one-process row's rate. Figures go to
``bench-results/load.json``.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import click

__all__ = ["bench_load"]

ROOT = Path(__file__).resolve().parents[2]
POSTGRES = ROOT / ".ci" / "postgres"


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _wait_port(port: int, timeout: float = 20.0) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            return
        except OSError:
            time.sleep(0.05)
    raise click.ClickException(f"nothing listens on port {port}")


class _Services:
    """PostgreSQL and Redis for the run, stopped and removed at the end."""

    def __enter__(self):
        if shutil.which("redis-server") is None:
            raise click.ClickException("redis-server is not installed (apt-get install redis-server)")
        started = subprocess.run([str(POSTGRES)], capture_output=True, text=True)
        if started.returncode != 0:
            raise click.ClickException(f"could not start PostgreSQL: {started.stderr.strip()}")
        self.admin_url, self.postgres_dir = started.stdout.split()
        self.redis_dir = tempfile.mkdtemp(prefix="lagrade-redis-")
        port = _free_port()
        self.redis = subprocess.Popen(["redis-server", "--port", str(port), "--bind", "127.0.0.1", "--save", "",
                                       "--appendonly", "no", "--dir", self.redis_dir],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
        _wait_port(port)
        self.redis_url = f"redis://127.0.0.1:{port}/0"
        return self

    def database(self, name: str) -> str:
        """A new, migrated database ``name`` with the yo-yo problem and a student; its URL."""
        from sqlalchemy import create_engine
        from sqlalchemy.engine import make_url

        from grader.jobs.derivation import load_problem_files
        from grader.store.db import Database
        from grader.store.migrate import upgrade

        admin = create_engine(self.admin_url, isolation_level="AUTOCOMMIT")
        with admin.connect() as connection:
            connection.exec_driver_sql(f"CREATE DATABASE {name}")
        admin.dispose()
        url = make_url(self.admin_url).set(database=name).render_as_string(hide_password=False)
        upgrade(url)
        database = Database(url)
        load_problem_files(database, [ROOT / "problems" / "yoyo.toml"])
        database.dispose()
        return url

    def __exit__(self, *_exc):
        self.redis.kill()
        self.redis.wait()
        shutil.rmtree(self.redis_dir, ignore_errors=True)
        subprocess.run([str(POSTGRES), "stop", self.postgres_dir], check=False)


def _student(database):
    from grader.store.users import create_token, create_user

    with database.write() as session:
        user = create_user(session, role="student", name="Bench student")
        return user.id, create_token(session, user)


def _queue_submissions(url: str, count: int) -> list[int]:
    from grader.bench.http import submission_bodies
    from grader.jobs import queue
    from grader.store.db import Database
    from grader.store.models import ProblemVersion, User
    from grader.store.problems import latest_version, problem_by_slug

    database = Database(url)
    student_id, _ = _student(database)
    with database.read() as session:
        version = latest_version(session, problem_by_slug(session, "yoyo"))
        version = session.get(ProblemVersion, version.id)
        student = session.get(User, student_id)
        _ = version.references
    ids = [queue.submit(database, user=student, version=version, **body)[0] for body in submission_bodies(count)]
    database.dispose()
    return ids


def _wait_graded(url: str, ids: list[int], timeout: float) -> float:
    """Seconds until every submission in ``ids`` is done (or failed); raises on time-out."""
    from sqlalchemy import func, select

    from grader.store.db import Database
    from grader.store.models import Submission

    database = Database(url)
    start = time.perf_counter()
    try:
        while time.perf_counter() - start < timeout:
            with database.read() as session:
                pending = session.scalar(select(func.count()).select_from(Submission)
                                         .where(Submission.id.in_(ids), Submission.status.in_(("queued", "running"))))
            if not pending:
                return time.perf_counter() - start
            time.sleep(0.05)
    finally:
        database.dispose()
    raise click.ClickException(f"grading did not finish in {timeout:.0f} s")


def _embedded_rate(url: str, count: int) -> float:
    from grader.jobs import WorkerPool
    from grader.store.db import Database

    ids = _queue_submissions(url, count)
    database = Database(url)
    pool = WorkerPool(database, workers=2, poll_s=0.05)
    # The sandbox children start before the clock, as they would in a running server.
    pool.start(recover=False)
    try:
        seconds = _wait_graded(url, ids, timeout=600)
    finally:
        pool.stop()
        database.dispose()
    return count / seconds


def _celery_rate(services: _Services, url: str, count: int, processes: int, workdir: Path) -> float:
    env = {**os.environ, "GRADER_BROKER_URL": services.redis_url, "DATABASE_URL": url, "GRADER_SWEEP_S": "3600"}
    workers = []
    for number in range(processes):
        log = open(workdir / f"celery-{processes}-{number}.log", "wb")
        workers.append(subprocess.Popen(
            [sys.executable, "-m", "celery", "-A", "grader.jobs.celery_worker", "worker", "--pool", "solo",
             "--loglevel", "WARNING", "-n", f"bench{number}@%h", "--without-gossip", "--without-mingle",
             "--without-heartbeat"], cwd=workdir, env=env, stdout=log, stderr=subprocess.STDOUT,
            start_new_session=True))
    try:
        ids = _queue_submissions(url, count)  # committed, not yet announced
        warm = _queue_submissions(url, 2 * processes)
        from grader.jobs import celery_worker

        celery_worker.app.conf.broker_url = services.redis_url
        celery_worker.publish([(i, 1) for i in warm])  # each worker's sandbox child starts here
        _wait_graded(url, warm, timeout=120)
        start = time.perf_counter()
        celery_worker.publish([(i, 1) for i in ids])
        _wait_graded(url, ids, timeout=600)
        return count / (time.perf_counter() - start)
    finally:
        for worker in workers:
            os.killpg(worker.pid, signal.SIGKILL)
            worker.wait()


def _accept_rate(services: _Services, url: str, processes: int, seconds: float, clients: int,
                 workdir: Path) -> tuple[float, int]:
    import requests

    from grader.store.db import Database

    database = Database(url)
    tokens = [_student(database)[1] for _ in range(clients)]
    database.dispose()
    port = _free_port()
    env = {**os.environ, "DATABASE_URL": url, "GRADER_BROKER_URL": services.redis_url,
           "LAGRADE_RATE_LIMITS_ENABLED": "false", "LAGRADE_SECRET_KEY": "bench"}
    log = open(workdir / f"gunicorn-{processes}.log", "wb")
    web = subprocess.Popen([sys.executable, "-m", "gunicorn", "-w", str(processes), "--threads", "4", "-b",
                            f"127.0.0.1:{port}", "grader.web.wsgi:app"], cwd=workdir, env=env, stdout=log,
                           stderr=subprocess.STDOUT, start_new_session=True)
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            try:
                if requests.get(f"{base}/api/v1/health", timeout=1).ok:
                    break
            except requests.RequestException:
                time.sleep(0.2)
        accepted, errors = [0] * clients, [0] * clients
        stop_at = time.monotonic() + seconds

        def client(number: int) -> None:
            with requests.Session() as http:
                headers = {"Authorization": f"Bearer {tokens[number]}"}
                sent = 0
                while time.monotonic() < stop_at and sent < 100_000:
                    sent += 1
                    answer = {"answer": "tension", "text": f"m*g/3 + {number}*{sent}*0"}
                    try:
                        status = http.post(f"{base}/api/v1/problems/yoyo/submissions", json=answer,
                                           headers=headers, timeout=30).status_code
                    except requests.RequestException:
                        status = 0
                    if status == 202:
                        accepted[number] += 1
                    else:
                        errors[number] += 1

        threads = [threading.Thread(target=client, args=(n,)) for n in range(clients)]
        start = time.perf_counter()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return sum(accepted) / (time.perf_counter() - start), sum(errors)
    finally:
        os.killpg(web.pid, signal.SIGKILL)
        web.wait()


@click.command("load")
@click.option("--submissions", default=400, show_default=True, help="Submissions graded per configuration.")
@click.option("--seconds", default=15.0, show_default=True, help="Length of each accepting phase.")
@click.option("--clients", default=16, show_default=True, help="Client threads of each accepting phase.")
@click.option("--out", default="bench-results/load.json", show_default=True, type=click.Path())
def bench_load(submissions: int, seconds: float, clients: int, out: str) -> None:
    """Submissions graded per second (embedded, 1 and 2 Celery workers) and accepted per second
    (1 and 2 gunicorn workers), with the scaling ratios."""
    rows = []
    with _Services() as services, tempfile.TemporaryDirectory(prefix="lagrade-load-") as workdir:
        work = Path(workdir)
        click.echo(f"{'grading':34} {'submissions':>11} {'graded/s':>9} {'ratio':>6}")
        embedded = _embedded_rate(services.database("load_embedded"), submissions)
        rows.append({"phase": "graded", "setup": "embedded (grader serve, 2 threads)", "rate": embedded})
        click.echo(f"{rows[-1]['setup']:34} {submissions:11} {embedded:9.1f} {'':>6}")
        base = None
        for processes in (1, 2):
            rate = _celery_rate(services, services.database(f"load_celery{processes}"), submissions, processes, work)
            base = base or rate
            rows.append({"phase": "graded", "setup": f"Celery, {processes} worker process(es)", "rate": rate,
                         "ratio": rate / base})
            click.echo(f"{rows[-1]['setup']:34} {submissions:11} {rate:9.1f} {rate / base:5.2f}x")
        click.echo("")
        click.echo(f"{'accepting':34} {'clients':>11} {'accepted/s':>10} {'errors':>6} {'ratio':>6}")
        base = None
        for processes in (1, 2):
            rate, errors = _accept_rate(services, services.database(f"load_web{processes}"), processes, seconds,
                                        clients, work)
            base = base or rate
            rows.append({"phase": "accepted", "setup": f"gunicorn, {processes} worker process(es)", "rate": rate,
                         "errors": errors, "ratio": rate / base})
            click.echo(f"{rows[-1]['setup']:34} {clients:11} {rate:10.1f} {errors:6} {rate / base:5.2f}x")
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps({"cores": os.cpu_count(), "submissions": submissions, "seconds": seconds,
                                     "clients": clients, "rows": rows}, indent=2))
    click.echo(f"figures written to {out}")
