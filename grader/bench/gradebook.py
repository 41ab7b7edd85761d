"""``grader bench gradebook``: what a course's gradebook costs to serve.

A throwaway SQLite database gets a course of ``--students`` students, one assignment of
``--problems`` problems with two answers each, and ``--attempts`` graded attempts per answer (the
last one a day late, so the penalty is computed too). Then ``GET /api/v1/courses/{code}/gradebook``
(JSON and CSV) is timed through the app, as an instructor; every score comes from
:mod:`grader.store.scores`. Figures go to ``bench-results/gradebook.json``.
"""

from __future__ import annotations

import json
import statistics
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

import click

__all__ = ["bench_gradebook"]

_REFERENCES = [{"name": name, "prompt": name, "kind": "expression", "reference": reference, "latex": reference,
                "variables": {"g": {"dimension": "acceleration", "domain": "positive"},
                              "m": {"dimension": "mass", "domain": "positive"}},
                "dimension": dimension, "feedback": []}
               for name, reference, dimension in (("tension", "g*m/3", "force"),
                                                  ("acceleration", "2*g/3", "acceleration"))]


def _fill(url: str, students: int, problems: int, attempts: int) -> tuple[str, int]:
    """The course BENCH; returns (an instructor's token, submissions stored)."""
    from grader.store.assignments import create_assignment
    from grader.store.courses import create_course
    from grader.store.db import Database
    from grader.store.migrate import upgrade
    from grader.store.models import Enrolment, Submission, User, Verdict
    from grader.store.problems import DerivedProblem, save_problem
    from grader.store.users import create_token

    upgrade(url)
    database = Database(url)
    stored = 0
    with database.write() as session:
        teacher = User(role="instructor", name="Teacher")
        session.add(teacher)
        session.flush()
        course = create_course(session, code="BENCH", title="Bench", instructor=teacher)
        for i in range(problems):
            save_problem(session, DerivedProblem(slug=f"p{i}", title=f"Problem {i}", statement="", source=f"p{i}",
                                                 derivation={}, references=_REFERENCES, engine_version="bench"))
        assignment = create_assignment(
            session, course, slug="hw", title="Homework", problems=[f"p{i}" for i in range(problems)],
            opens_at=datetime(2026, 1, 1, tzinfo=timezone.utc), due_at=datetime(2026, 2, 1, tzinfo=timezone.utc),
            closes_at=datetime(2026, 2, 5, tzinfo=timezone.utc), late_penalty_per_day=0.1)
        people = [User(role="student", name=f"Student {i:04d}", email=f"s{i}@bench.example") for i in range(students)]
        session.add_all(people)
        session.flush()
        session.add_all(Enrolment(user_id=u.id, course_id=course.id, role="student") for u in people)
        for user in people:
            for item in assignment.problems:
                for answer in ("tension", "acceleration"):
                    for k in range(attempts):
                        late = k == attempts - 1
                        submission = Submission(
                            user_id=user.id, requester_id=user.id, problem_version_id=item.problem_version_id,
                            grading_version_id=item.problem_version_id, answer_name=answer, text="m*g",
                            status="done", assignment_id=assignment.id,
                            received_at=datetime(2026, 2, 2 if late else 1, 12))
                        submission.verdicts = [Verdict(grading_round=1, problem_version_id=item.problem_version_id,
                                                       verdict="equivalent", score=(k + 1) / attempts)]
                        session.add(submission)
                        stored += 1
        token = create_token(session, teacher)
    database.dispose()
    return token, stored


@click.command("gradebook")
@click.option("--students", default=300, show_default=True, type=click.IntRange(1, 5000))
@click.option("--problems", default=5, show_default=True, type=click.IntRange(1, 50))
@click.option("--attempts", default=3, show_default=True, type=click.IntRange(1, 20), help="Per answer.")
@click.option("--repeat", default=5, show_default=True, type=click.IntRange(1, 100))
@click.option("--out", default="bench-results/gradebook.json", show_default=True, type=click.Path(dir_okay=False))
def bench_gradebook(students: int, problems: int, attempts: int, repeat: int, out: str) -> None:
    """Time a course's gradebook (JSON and CSV) over the API."""
    from grader.web import create_app

    with tempfile.TemporaryDirectory() as folder:
        url = f"sqlite:///{Path(folder) / 'bench.sqlite'}"
        token, stored = _fill(url, students, problems, attempts)
        app = create_app({"TESTING": True, "DATABASE_URL": url, "SECRET_KEY": "bench", "RATE_LIMITS_ENABLED": False})
        client, headers = app.test_client(), {"Authorization": f"Bearer {token}"}
        rows = []
        try:
            for name, query in (("json", ""), ("csv", "?format=csv")):
                times = []
                for _ in range(repeat):
                    start = time.perf_counter()
                    response = client.get(f"/api/v1/courses/BENCH/gradebook{query}", headers=headers)
                    times.append((time.perf_counter() - start) * 1000)
                    if response.status_code != 200:
                        raise click.ClickException(f"gradebook {name}: {response.status_code}")
                rows.append({"format": name, "students": students, "problems": problems, "submissions": stored,
                             "rows": students * problems, "median_ms": statistics.median(times),
                             "min_ms": min(times)})
        finally:
            app.extensions["lagrade.checkers"].close()
            app.extensions["lagrade.db"].dispose()
    click.echo(f"{'format':8}{'students':>10}{'problems':>10}{'submissions':>13}{'rows':>8}"
               f"{'median ms':>11}{'min ms':>9}")
    for r in rows:
        click.echo(f"{r['format']:8}{r['students']:>10}{r['problems']:>10}{r['submissions']:>13}{r['rows']:>8}"
                   f"{r['median_ms']:>11.0f}{r['min_ms']:>9.0f}")
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps(rows, indent=1))
