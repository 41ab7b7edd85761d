"""Course pages: an instructor starts a course, enrols a CSV roster, builds an assignment; students
see what is open, due when, their attempts left and the late cost, hand in, and see the solutions
after the close; the gradebook page, the student's page, the API and the CSV show the same scores."""

from __future__ import annotations

import csv
import io
import re
from datetime import datetime, timedelta, timezone
from zoneinfo import ZoneInfo

import pytest
from sqlalchemy import select

from grader.store.models import Course, Submission, User
from grader.store.users import create_token, set_password
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    PASSWORD, Account, Clock, accounts, as_instructor, csrf, grade_all, sign_in,
)

PARIS = "Europe/Paris"
OPENS = datetime(2026, 12, 1, 9, 0, tzinfo=timezone.utc)
DUE = datetime(2026, 12, 8, 17, 0, tzinfo=timezone.utc)  # 18:00 in Paris
CLOSES = DUE + timedelta(days=2)
ROSTER = b"email,name,external_id\ncy@example.org,Cy Young,s-cy\ndee@example.org,Dee Dirac,s-dee\n"


@pytest.fixture
def clock(app):
    app.config["CLOCK"] = clock = Clock(OPENS)
    return clock


def _paris(moment: datetime) -> str:
    """A datetime-local form value, in Paris time."""
    return moment.astimezone(ZoneInfo(PARIS)).strftime("%Y-%m-%dT%H:%M:%S")


def _post(client, url, **data):
    return client.post(url, data=dict(data, csrf_token=csrf(client)))


@pytest.fixture
def course(app, as_instructor, yoyo_version, clock):
    """PHYS by Ine: Cy and Dee from a CSV file; homework hw1 over the yo-yo, 2 attempts, 10 %/day late."""
    assert _post(as_instructor, "/instructor/courses", code="PHYS", title="Physics").status_code == 302
    enrolled = as_instructor.post("/instructor/courses/PHYS/members", data={
        "csrf_token": csrf(as_instructor), "roster": (io.BytesIO(ROSTER), "roster.csv")},
        content_type="multipart/form-data")
    assert enrolled.status_code == 302
    made = _post(as_instructor, "/instructor/courses/PHYS/assignments", id="hw1", title="Homework 1",
                 problems="yoyo", time_zone=PARIS, opens_at=_paris(OPENS), due_at=_paris(DUE),
                 closes_at=_paris(CLOSES), late_penalty_percent="10", max_attempts="2", score_policy="best")
    assert made.headers["Location"].endswith("/instructor/courses/PHYS/assignments/hw1"), made.headers["Location"]
    return as_instructor


def _student(app, email: str):
    """A signed-in client for a rostered student (their account had no password: give it one)."""
    with app.extensions["lagrade.db"].write() as session:
        user = session.scalar(select(User).where(User.email == email))
        set_password(user, PASSWORD)
        user_id = user.id
    client = app.test_client()
    assert sign_in(client, Account(user_id, email, "student")).status_code == 302
    return client


# The page once took codes the API refuses (its own test was str.isalnum, true of Ω²ǅ) and a code
# beside one that differs only in case.
@pytest.mark.parametrize("code, words", [
    ("Ω²ǅ", "is not a course code"),
    ("-x", "is not a course code"),
    ("MECH 2026", "is not a course code"),
    ("phys", "There is already a course &#39;PHYS&#39;"),
])
def test_the_page_refuses_the_course_codes_the_api_refuses(app, as_instructor, code, words):
    assert _post(as_instructor, "/instructor/courses", code="PHYS", title="Physics").status_code == 302
    refused = _post(as_instructor, "/instructor/courses", code=code, title="Again")
    assert refused.status_code == 422 and words in refused.get_data(as_text=True)
    with app.extensions["lagrade.db"].read() as session:
        assert session.scalar(select(Course).where(Course.title == "Again")) is None


def test_the_roster_page_lists_everyone_enrolled_from_the_csv(course):
    page = course.get("/instructor/courses/PHYS").get_data(as_text=True)
    assert "Cy Young" in page and "Dee Dirac" in page and "s-dee" in page
    assert "Homework 1" in page


def test_the_student_page_says_what_is_open_due_when_and_what_late_costs(app, course, clock):
    cy = _student(app, "cy@example.org")
    assert "Homework 1" in cy.get("/courses").get_data(as_text=True)
    page = cy.get("/courses/PHYS/assignments/hw1").get_data(as_text=True)
    assert "This assignment is open." in page
    assert "Due Tue 08 Dec 2026, 18:00:00 (Europe/Paris)" in page  # 17:00 UTC, said in the course's zone
    assert "each started day late costs 10% of the score" in page
    assert "Each answer gets 2 attempts." in page and "Your score for an answer is your best attempt" in page


def test_attempts_run_out_and_the_page_says_so(app, course, clock):
    cy = _student(app, "cy@example.org")
    for wrong in ("m*g", "m*g/2"):  # two different answers: the same text again would not count
        assert _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo",
                     **{"answer-tension": wrong}).status_code == 302
    page = cy.get("/courses/PHYS/assignments/hw1").get_data(as_text=True)
    assert re.search(r"2 attempts used, 0 left", page)
    assert 'name="answer-tension"' not in page and 'name="answer-acceleration"' in page
    refused = _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo", **{"answer-tension": "m*g/3"})
    assert refused.status_code == 422 and "No attempts left" in refused.get_data(as_text=True)


def test_after_the_close_nothing_is_accepted_and_the_solution_is_shown(app, course, clock):
    cy = _student(app, "cy@example.org")
    clock.now = CLOSES
    assert 'class="card derivation solution"' not in cy.get("/courses/PHYS/assignments/hw1").get_data(as_text=True)
    clock.now = CLOSES + timedelta(seconds=1)
    refused = _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo", **{"answer-tension": "m*g/3"})
    assert refused.status_code == 422 and "no more submissions are accepted" in refused.get_data(as_text=True)
    page = cy.get("/courses/PHYS/assignments/hw1").get_data(as_text=True)
    assert "This assignment is closed." in page
    assert 'class="card derivation solution"' in page and "<math" in page  # rendered as MathML


def test_scores_agree_on_the_student_page_the_gradebook_page_the_api_and_the_csv(app, course, clock):
    cy, dee = _student(app, "cy@example.org"), _student(app, "dee@example.org")
    clock.now = DUE - timedelta(hours=1)
    _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo",
          **{"answer-tension": "m*g/3", "answer-acceleration": "g"})
    clock.now = DUE + timedelta(hours=30)  # 2 started days late: keeps 80 %
    _post(dee, "/courses/PHYS/assignments/hw1/submit", problem="yoyo", **{"answer-tension": "g*m/3"})
    assert grade_all(app) == 3
    # Cy: tension 1, acceleration 0 -> 0.5; Dee: tension 0.8, acceleration untried -> 0.4.
    expected = {"s-cy": 0.5, "s-dee": 0.4}
    gradebook = course.get("/instructor/courses/PHYS/assignments/hw1").get_data(as_text=True)
    for name, score in (("Cy Young", "0.5"), ("Dee Dirac", "0.4")):
        row = gradebook[gradebook.index(name):]
        assert re.search(r'<strong class="score">([0-9.]+)</strong>', row).group(1) == score
    assert "2 days late" in gradebook
    with app.extensions["lagrade.db"].write() as session:
        ine = session.scalar(select(User).where(User.email == "ine@example.org"))
        token = {"Authorization": f"Bearer {create_token(session, ine)}"}
    api = app.test_client().get("/api/v1/courses/PHYS/gradebook", headers=token).get_json()["rows"]
    assert {r["external_id"]: r["score"] for r in api} == expected
    text = course.get("/instructor/courses/PHYS/gradebook.csv").get_data(as_text=True)
    assert {r["external_id"]: float(r["score"]) for r in csv.DictReader(io.StringIO(text))} == expected
    for client, key in ((cy, "s-cy"), (dee, "s-dee")):
        page = client.get("/courses/PHYS/assignments/hw1").get_data(as_text=True)
        assert re.search(r'id="assignment-score">([0-9.]+)<', page).group(1) == str(expected[key])


def test_the_practice_page_sends_a_student_to_the_open_assignment(app, course, clock):
    cy = _student(app, "cy@example.org")
    response = _post(cy, "/problems/yoyo/submit", **{"answer-tension": "m*g/3"})
    assert response.headers["Location"].endswith("/courses/PHYS/assignments/hw1")
    assert "hand it in there" in cy.get(response.headers["Location"]).get_data(as_text=True)


# As on the practice page: a refused answer is marked at its input with its text kept, the others
# are stored, and a rate limit partway names what it held back.
def test_a_refused_hand_in_keeps_its_text_and_the_others_are_handed_in(app, course, clock):
    cy = _student(app, "cy@example.org")
    too_long = "m*g+" * 1125  # 4500 characters
    refused = _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo",
                    **{"answer-tension": too_long, "answer-acceleration": "2*g/3"})
    html = refused.get_data(as_text=True)
    assert refused.status_code == 422 and "Submitted 1 answer for grading" in html
    assert "Not submitted:</strong> the answer is 4500 characters long" in html and f'value="{too_long}"' in html
    with app.extensions["lagrade.db"].read() as session:
        assert session.scalars(select(Submission.answer_name)).all() == ["acceleration"]


def test_a_rate_limit_partway_through_a_hand_in_keeps_the_rest(app, course, clock):
    app.config.update(RATE_LIMITS_ENABLED=True, RATE_LIMITS={**app.config["RATE_LIMITS"], "submit": (1, 1)})
    cy = _student(app, "cy@example.org")
    typed = {"tension": "m*g/3", "acceleration": "2*g/3"}
    held = _post(cy, "/courses/PHYS/assignments/hw1/submit", problem="yoyo",
                 **{f"answer-{name}": text for name, text in typed.items()})
    html = held.get_data(as_text=True)
    with app.extensions["lagrade.db"].read() as session:
        [sent] = session.scalars(select(Submission.answer_name)).all()
    [rest] = {"tension", "acceleration"} - {sent}
    assert held.status_code == 429 and f"Not submitted (too many submissions in a short time): {rest}." in html
    assert f'value="{typed[rest]}"' in html
