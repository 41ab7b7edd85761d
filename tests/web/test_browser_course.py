"""A course from start to finish in a real browser against the real server (``grader serve``).

An instructor starts a course, enrols two students from a CSV file and builds an assignment over a
randomised problem (one attempt per answer, half the score per day late); the two students see
different numbers and hand in, one on time (and then out of attempts), one late; the deadline
passes (the server's clock is a file this test rewrites); the solutions appear; and the gradebook
page, the API and the CSV give every student the same score. axe-core finds no serious or critical
WCAG violation on the filled pages (roster, assignment, solution, gradebook). Screenshots go to /tmp
(lagrade-course-student.png, lagrade-course-gradebook.png).
"""

from __future__ import annotations

import csv
import io
import os
import re
import shutil
import subprocess
import time

import pytest

from tests.web.test_browser_flow import CHROMIUM, CHROMIUM_ARGS, ROOT, _grader, _require_browser, _sign_in, serving
from tests.web.test_pages_in_browser import _audit, _axe_source

pytestmark = [pytest.mark.browser, pytest.mark.server, pytest.mark.slow]

INSTRUCTOR = ("prof@example.org", "prof-pass-1")
STUDENTS = {"ada": ("ada@example.org", "ada-pass-1"), "bob": ("bob@example.org", "bob-pass-1")}
ROSTER = "email,name,external_id\nada@example.org,Ada Lovelace,s-ada\nbob@example.org,Bob Hooke,s-bob\n"
SCENE = ROOT / "tests" / "mechanics" / "randomised" / "yoyo_randomised.toml"
SECRET = "browser-course-secret"  # fixed, so the two students' draws are the same on every run


@pytest.fixture
def sync_playwright():
    return _require_browser()


@pytest.fixture
def course_server(tmp_path):
    """``grader serve`` with the randomised yo-yo, three accounts and a clock file; yields (url, clock, db url)."""
    problems = tmp_path / "problems"
    problems.mkdir()
    shutil.copy(SCENE, problems / SCENE.name)
    clock = tmp_path / "clock"
    clock.write_text("2026-12-05T12:00:00+00:00")
    database_url = f"sqlite:///{tmp_path / 'lagrade.sqlite'}"
    env = dict(os.environ, DATABASE_URL=database_url, PYTHONUNBUFFERED="1", LAGRADE_CLOCK_FILE=str(clock),
               LAGRADE_SECRET_KEY=SECRET)
    accounts = [("instructor", "Prof", *INSTRUCTOR), ("student", "Ada Lovelace", *STUDENTS["ada"]),
                ("student", "Bob Hooke", *STUDENTS["bob"])]
    for role, name, email, password in accounts:
        subprocess.run(_grader("db", "create-user", "--role", role, "--email", email, "--name", name,
                               "--password", password), env=env, cwd=tmp_path, check=True, capture_output=True,
                       timeout=120)
    with serving(env, tmp_path, problems) as base:
        yield base, clock, database_url


def _numbers(page) -> str:
    return page.inner_text("p.parameters")


def _hand_in(page, answer: str, text: str) -> None:
    page.fill(f"#input-yoyo-randomised-{answer}", text)
    page.click("section#problem-yoyo-randomised button[type=submit]")
    page.wait_for_selector(".flash")


def _graded_gradebook(page, base: str) -> str:
    """The gradebook page once nothing is being graded any more."""
    for _ in range(240):
        page.goto(f"{base}/instructor/courses/PHYS/assignments/hw1")
        html = page.content()
        if "grading" not in page.inner_text("table.gradebook"):
            return html
        time.sleep(0.5)
    raise AssertionError("the hand-ins were not graded in time")


def test_a_course_from_roster_to_gradebook(sync_playwright, course_server, tmp_path):
    base, clock, database_url = course_server
    axe, violations = _axe_source(), []

    def audit(page) -> None:  # axe-core: no serious or critical WCAG 2.2 AA violation on a filled page
        violations.extend(f"{page.url}: {v}" for v in _audit(page, axe))

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)

        def new_page():  # bypass_csp only so that axe can be injected; the pages run under their CSP
            return browser.new_context(bypass_csp=True).new_page()

        try:
            prof = new_page()
            _sign_in(prof, base, INSTRUCTOR)
            prof.goto(f"{base}/instructor/courses")
            prof.fill("#course-code", "PHYS")
            prof.fill("#course-title", "Physics")
            prof.click("#new-course button[type=submit]")
            prof.wait_for_url(f"{base}/instructor/courses/PHYS")
            prof.set_input_files("#m-file", files=[{"name": "roster.csv", "mimeType": "text/csv",
                                                    "buffer": ROSTER.encode()}])
            prof.click("#enrol button[type=submit]")
            assert "Enrolled 2 people" in prof.inner_text(".flash")
            assert "Ada Lovelace" in prof.inner_text("table.roster") and "Bob Hooke" in prof.inner_text("table.roster")
            audit(prof)
            prof.fill("#a-id", "hw1")
            prof.fill("#a-title", "Homework 1")
            prof.check("input[name=problems][value=yoyo-randomised]")
            prof.fill("#a-opens", "2026-12-01T09:00:00")
            prof.fill("#a-due", "2026-12-08T17:00:00")
            prof.fill("#a-closes", "2026-12-10T17:00:00")
            prof.fill("#a-penalty", "50")
            prof.fill("#a-attempts", "1")
            prof.click("#new-assignment + form button[type=submit]")
            prof.wait_for_url(f"{base}/instructor/courses/PHYS/assignments/hw1")

            ada = new_page()
            _sign_in(ada, base, STUDENTS["ada"])
            ada.goto(f"{base}/courses")
            ada.click("text=Homework 1")
            assert "This assignment is open." in ada.inner_text("#rules")
            assert "each started day late costs 50% of the score" in ada.inner_text("#rules")
            ada_numbers = _numbers(ada)
            _hand_in(ada, "tension", "m g")  # wrong (a known slip: a quarter of the credit), and her only attempt
            assert "1 attempt used, 0 left" in ada.inner_text("#attempts-yoyo-randomised-tension")
            assert ada.query_selector("#input-yoyo-randomised-tension") is None  # out of attempts
            ada.screenshot(path="/tmp/lagrade-course-student.png", full_page=True)
            audit(ada)

            clock.write_text("2026-12-09T12:00:00+00:00")  # past due: one started day late
            bob = new_page()
            _sign_in(bob, base, STUDENTS["bob"])
            bob.goto(f"{base}/courses/PHYS/assignments/hw1")
            assert "keeps 50% of its score" in bob.inner_text("#rules")
            bob_numbers = _numbers(bob)
            assert bob_numbers != ada_numbers  # each student their own numbers
            _hand_in(bob, "tension", "m*g/3")
            assert "1 day late" in bob.inner_text(".flash")

            clock.write_text("2026-12-10T17:00:01+00:00")  # one second after the close
            ada.goto(f"{base}/courses/PHYS/assignments/hw1")
            assert "This assignment is closed." in ada.inner_text("#rules")
            assert ada.query_selector("details.solution math") is not None  # the worked solution, as MathML
            mine = dict(re.findall(r"(\w+) = ([0-9.]+)", ada_numbers))  # with her own numbers: T = m g / 3
            assert f"{float(mine['m']) * float(mine['g']) / 3:.4g} N" in ada.inner_text("details.solution")
            assert ada.query_selector("#input-yoyo-randomised-acceleration") is None
            audit(ada)

            html = _graded_gradebook(prof, base)
            prof.screenshot(path="/tmp/lagrade-course-gradebook.png", full_page=True)
            audit(prof)
            page_scores = {name: float(score) for name, score in re.findall(
                r'<td>(Ada Lovelace|Bob Hooke)<div.*?<strong class="score">([0-9.]+)</strong>', html, re.S)}
            csv_text = prof.request.get(f"{base}/instructor/courses/PHYS/gradebook.csv").text()
            ada.goto(f"{base}/courses/PHYS/assignments/hw1")  # graded now: her own page says the same
            ada_page = {"Ada Lovelace": float(ada.inner_text("#assignment-score"))}
        finally:
            browser.close()
    assert violations == []
    csv_scores = {r["name"]: float(r["score"]) for r in csv.DictReader(io.StringIO(csv_text))}

    from sqlalchemy import select

    from grader.store.db import Database
    from grader.store.models import ProblemVersion, User
    from grader.store.scores import answer_weight
    from grader.store.users import create_token
    from grader.web import create_app

    database = Database(database_url)
    with database.write() as session:
        token = create_token(session, session.scalar(select(User).where(User.email == INSTRUCTOR[0])))
        weights = {r["name"]: answer_weight(r) for r in session.scalar(select(ProblemVersion.references))}
    database.dispose()
    tension = weights["tension"] / sum(weights.values())  # the tension's share of the problem
    app = create_app({"TESTING": True, "DATABASE_URL": database_url, "SECRET_KEY": SECRET})
    try:
        rows = app.test_client().get("/api/v1/courses/PHYS/gradebook",
                                     headers={"Authorization": f"Bearer {token}"}).get_json()["rows"]
    finally:
        app.extensions["lagrade.checkers"].close()
        app.extensions["lagrade.db"].dispose()
    api_scores = {r["name"]: r["score"] for r in rows}
    # Bob: the tension right but a day late (keeps half), the other answers untried. Ada: her known slip
    # earns the partial credit its feedback gives (a quarter of the tension).
    assert page_scores == csv_scores == api_scores
    assert page_scores == {"Bob Hooke": round(0.5 * tension, 4), "Ada Lovelace": round(0.25 * tension, 4)}
    assert ada_page["Ada Lovelace"] == page_scores["Ada Lovelace"]
