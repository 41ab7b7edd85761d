"""Courses over the API: enrolment (one by one and from a CSV roster), assignments whose deadlines
and attempt limits the server enforces to the second, and a gradebook whose JSON and CSV agree."""

from __future__ import annotations

import csv
import io
from datetime import datetime, timedelta, timezone

import pytest

from tests.web.conftest_pages import Clock

OPENS = datetime(2026, 12, 1, 9, 0, tzinfo=timezone.utc)
DUE = datetime(2026, 12, 8, 17, 0, tzinfo=timezone.utc)
CLOSES = DUE + timedelta(days=3)
SECOND = timedelta(seconds=1)
ROSTER = "email,name,external_id\nada@example.org,Ada Lovelace,s-ada\nbob@example.org,Bob Hooke,s-bob\n"


@pytest.fixture
def clock(app):
    app.config["CLOCK"] = clock = Clock(OPENS)
    return clock


def _assignment(**overrides):
    body = {"id": "hw1", "title": "Homework 1", "problems": ["yoyo"], "opens_at": OPENS.isoformat(),
            "due_at": DUE.isoformat(), "closes_at": CLOSES.isoformat(), "time_zone": "Europe/Paris",
            "max_attempts": 2, "late_penalty_per_day": 0.25, "score_policy": "best"}
    return {**body, **overrides}


@pytest.fixture
def course(client, make_token, yoyo_version, clock):
    """MECH, taught by Ine, with Ada and Bob from a roster and homework 1 over the yo-yo."""
    _, ine = make_token("instructor", name="Ine")
    assert client.post("/api/v1/courses", json={"code": "MECH", "title": "Mechanics"}, headers=ine).status_code == 201
    added = client.post("/api/v1/courses/MECH/members", data=ROSTER, content_type="text/csv", headers=ine)
    assert added.status_code == 201, added.get_json()
    made = client.post("/api/v1/courses/MECH/assignments", json=_assignment(), headers=ine)
    assert made.status_code == 201, made.get_json()
    return {"ine": ine}


@pytest.fixture
def student(app, course):
    """``student("s-ada") -> headers``: a token for a student of the roster."""
    from grader.store.models import User
    from grader.store.users import create_token
    from sqlalchemy import select

    def token(external_id: str) -> dict:
        with app.extensions["lagrade.db"].write() as session:
            user = session.scalar(select(User).where(User.external_id == external_id))
            return {"Authorization": f"Bearer {create_token(session, user)}"}

    return token


def _hand_in(client, headers, text="m*g/3", answer="tension", problem="yoyo"):
    return client.post("/api/v1/courses/MECH/assignments/hw1/submissions",
                       json={"problem": problem, "answer": answer, "text": text}, headers=headers)


def test_an_instructor_creates_a_course_and_enrols_a_roster(client, course):
    body = client.get("/api/v1/courses/MECH", headers=course["ine"]).get_json()
    assert body["role"] == "instructor"
    assert [(m["name"], m["role"]) for m in body["members"]] == [
        ("Ine", "instructor"), ("Ada Lovelace", "student"), ("Bob Hooke", "student")]
    assert [a["id"] for a in body["assignments"]] == ["hw1"]


def test_a_course_code_is_taken_once_and_students_create_none(client, make_token, course):
    assert client.post("/api/v1/courses", json={"code": "MECH", "title": "Again"},
                       headers=course["ine"]).status_code == 409
    _, someone = make_token("student")
    assert client.post("/api/v1/courses", json={"code": "MINE", "title": "Mine"}, headers=someone).status_code == 403


@pytest.mark.parametrize("code, status, detail", [
    ("mech", 409, "already a course 'MECH'"),     # one code in any case
    ("MECH\n", 422, "is not a course code"),       # the schema's pattern ends at a newline; the rule does not
    ("Ω²ǅ", 422, "must match the pattern"),
    ("-x", 422, "must match the pattern"),
])
def test_a_course_code_follows_the_one_rule_in_any_case(client, course, code, status, detail):
    response = client.post("/api/v1/courses", json={"code": code, "title": "Again"}, headers=course["ine"])
    assert response.status_code == status and detail in response.get_json()["detail"]
    assert response.mimetype == "application/problem+json"


def test_a_student_sees_only_their_courses_and_no_roster(client, make_token, course, student):
    ada = student("s-ada")
    assert [c["code"] for c in client.get("/api/v1/courses", headers=ada).get_json()["courses"]] == ["MECH"]
    assert "members" not in client.get("/api/v1/courses/MECH", headers=ada).get_json()
    _, outsider = make_token("student")
    assert client.get("/api/v1/courses", headers=outsider).get_json()["courses"] == []
    assert client.get("/api/v1/courses/MECH", headers=outsider).status_code == 404
    assert client.get("/api/v1/courses/MECH/assignments/hw1", headers=outsider).status_code == 404


@pytest.mark.parametrize("roster, where", [
    ("email,name\nada@example.org,Ada\nnot-an-email,Bob\n", "line 3"),
    ("email,name,external_id\n,Nobody,\n", "line 2"),
    ("who,what\nx,y\n", "first line"),
    ("email,name,role\ncy@example.org,Cy,dean\n", "line 2"),
])
def test_a_roster_with_a_bad_line_adds_nobody_and_names_the_line(client, course, roster, where):
    response = client.post("/api/v1/courses/MECH/members", data=roster, content_type="text/csv", headers=course["ine"])
    assert response.status_code == 422 and where in response.get_json()["detail"]
    members = client.get("/api/v1/courses/MECH", headers=course["ine"]).get_json()["members"]
    assert len(members) == 3


def test_one_member_by_external_id_and_a_ta_who_grades_but_does_not_manage(client, course, student):
    added = client.post("/api/v1/courses/MECH/members", json={"external_id": "s-ta", "name": "Tia", "role": "ta"},
                        headers=course["ine"])
    assert added.status_code == 201 and added.get_json()["members"][0]["role"] == "ta"
    tia = student("s-ta")
    assert client.get("/api/v1/courses/MECH/gradebook", headers=tia).status_code == 200
    assert "members" in client.get("/api/v1/courses/MECH", headers=tia).get_json()
    assert client.post("/api/v1/courses/MECH/members", json={"email": "x@example.org", "name": "X"},
                       headers=tia).status_code == 403
    assert client.post("/api/v1/courses/MECH/assignments/hw1/release", headers=tia).status_code == 403


@pytest.mark.parametrize("overrides, detail", [
    ({"due_at": OPENS.isoformat()}, "opens before it is due"),
    ({"closes_at": (DUE - SECOND).isoformat()}, "closes at or after"),
    ({"closes_at": None}, "late penalty needs a closing time"),
    ({"problems": ["nope"]}, "no problem 'nope'"),
    ({"time_zone": "Mars/Olympus"}, "not a time zone"),
])
def test_an_assignment_that_makes_no_sense_is_refused(client, course, overrides, detail):
    response = client.post("/api/v1/courses/MECH/assignments", json=_assignment(id="hw2", **overrides),
                           headers=course["ine"])
    assert response.status_code == 422 and detail in response.get_json()["detail"]


def test_a_time_without_an_offset_is_refused_by_the_schema(client, course):
    response = client.post("/api/v1/courses/MECH/assignments", json=_assignment(id="hw2", due_at="2026-12-08T17:00:00"),
                           headers=course["ine"])
    assert response.status_code == 422 and response.get_json()["errors"][0]["pointer"] == "/due_at"


@pytest.mark.parametrize("now, status, late_days", [
    (OPENS - SECOND, 409, None),  # not open yet
    (OPENS, 202, 0),
    (DUE, 202, 0),  # the due second itself is on time
    (DUE + SECOND, 202, 1),  # one second late is one started day
    (DUE + timedelta(days=1), 202, 1),
    (DUE + timedelta(days=1) + SECOND, 202, 2),
    (CLOSES, 202, 3),  # the closing second is still accepted
    (CLOSES + SECOND, 409, None),  # after it, nothing
])
def test_the_deadlines_hold_to_the_second(client, clock, student, now, status, late_days):
    clock.now = now
    response = _hand_in(client, student("s-ada"))
    assert response.status_code == status, response.get_json()
    if status == 202:
        assert response.get_json()["late_days"] == late_days
    else:
        assert response.get_json()["type"] in ("urn:lagrade:error:not-open", "urn:lagrade:error:closed")


def test_each_answer_gets_its_attempts_and_no_more(client, clock, student):
    clock.now = OPENS + timedelta(hours=1)
    ada = student("s-ada")
    assert [_hand_in(client, ada, text=t).status_code for t in ("m*g/3", "m*g/2", "m*g/4")] == [202, 202, 409]
    assert _hand_in(client, ada, answer="acceleration", text="2*g/3").status_code == 202  # another answer
    assert _hand_in(client, student("s-bob")).status_code == 202  # another student
    view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()
    answers = {a["name"]: a for a in view["problems"][0]["answers"]}
    assert (answers["tension"]["attempts_used"], answers["tension"]["attempts_left"]) == (2, 0)
    assert (answers["acceleration"]["attempts_used"], answers["acceleration"]["attempts_left"]) == (1, 1)


def test_the_page_states_times_in_the_assignments_zone_and_the_late_cost(client, clock, student):
    view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=student("s-ada")).get_json()
    assert view["due_at"] == "2026-12-08T18:00:00+01:00"  # 17:00 UTC in Paris
    assert any("25%" in rule and "started day" in rule for rule in view["rules"])
    assert view["state"] == "open" and view["score"] == 0.0


def test_solutions_appear_once_the_assignment_closes_or_is_released(client, clock, course, student):
    ada = student("s-ada")
    clock.now = CLOSES
    assert "solution" not in client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()["problems"][0]
    clock.now = CLOSES + SECOND
    closed = client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()
    solution = closed["problems"][0]["solution"]
    assert closed["solutions_available"] and solution["answers"][1]["latex"] == r"\frac{g m}{3}"
    clock.now = OPENS
    assert client.post("/api/v1/courses/MECH/assignments/hw1/release", headers=course["ine"]).status_code == 200
    assert "solution" in client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()["problems"][0]


def test_the_gradebook_json_csv_and_the_students_view_agree(client, clock, course, student, workers, poll):
    ada, bob = student("s-ada"), student("s-bob")
    clock.now = DUE - timedelta(hours=1)
    poll(_hand_in(client, ada, text="m*g").headers["Location"], ada)  # wrong
    poll(_hand_in(client, ada, answer="acceleration", text="2*g/3").headers["Location"], ada)  # right, on time
    clock.now = DUE + timedelta(hours=2)  # one started day late: keeps 75%
    poll(_hand_in(client, ada, text="g*m/3").headers["Location"], ada)
    poll(_hand_in(client, bob, text="g*m/3").headers["Location"], bob)
    body = client.get("/api/v1/courses/MECH/gradebook", headers=course["ine"]).get_json()
    scores = {r["external_id"]: (r["score"], r["attempts"], r["late_days"]) for r in body["rows"]}
    # Ada: acceleration 1, tension 0.75 (late) -> mean 0.875; Bob: tension 0.75, acceleration never tried -> 0.375.
    assert scores == {"s-ada": (0.875, 3, 1), "s-bob": (0.375, 1, 1)}
    text = client.get("/api/v1/courses/MECH/gradebook?format=csv", headers=course["ine"]).get_data(as_text=True)
    assert {r["external_id"]: float(r["score"]) for r in csv.DictReader(io.StringIO(text))} == {
        "s-ada": 0.875, "s-bob": 0.375}
    for who, headers in (("s-ada", ada), ("s-bob", bob)):
        view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=headers).get_json()
        assert view["problems"][0]["score"] == view["score"] == scores[who][0]
        own = client.get("/api/v1/courses/MECH/gradebook", headers=headers).get_json()["rows"]
        assert [r["external_id"] for r in own] == [who]


def test_a_retry_with_the_same_idempotency_key_uses_no_attempt_even_after_the_close(client, clock, student):
    ada = student("s-ada")
    keyed = {**ada, "Idempotency-Key": "hw1-tension-1"}
    first = _hand_in(client, keyed)
    assert first.status_code == 202
    clock.now = CLOSES + SECOND  # the answer to the first request was lost; the retry comes late
    again = _hand_in(client, keyed)
    assert again.status_code in (200, 202) and again.get_json()["id"] == first.get_json()["id"]
    assert _hand_in(client, keyed, text="m*g").status_code == 422  # the same key for another answer
    view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()
    assert {a["name"]: a["attempts_used"] for a in view["problems"][0]["answers"]}["tension"] == 1


# Before the opening the problem is hidden from the course's students altogether (404, as for any
# problem they may not see: tests/web/test_unopened_assignments.py); then it is answered in the assignment.
@pytest.mark.parametrize("now, status", [(OPENS - SECOND, 404), (DUE, 409), (CLOSES, 409), (CLOSES + SECOND, 202)])
def test_a_problem_in_an_assignment_is_not_practised_until_it_closes(client, clock, student, now, status):
    """Practice verdicts would get round the attempt limit: the problem is answered in the assignment."""
    clock.now = now
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g/3"},
                           headers=student("s-ada"))
    assert response.status_code == status
    if status == 409:
        assert "/api/v1/courses/MECH/assignments/hw1/submissions" in response.get_json()["detail"]


def test_students_outside_the_course_still_practise_the_problem(client, make_token, course):
    _, outsider = make_token("student")
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g/3"},
                           headers=outsider)
    assert response.status_code == 202


def test_an_unreadable_text_or_the_same_text_again_uses_no_attempt(client, clock, student):
    clock.now = OPENS + timedelta(hours=1)
    ada = student("s-ada")
    unreadable = _hand_in(client, ada, text="m*g/")
    assert unreadable.status_code == 422 and unreadable.get_json()["type"].endswith("unreadable-answer")
    first, again = _hand_in(client, ada, text="m*g/2"), _hand_in(client, ada, text="m*g/2")
    assert first.status_code == 202 and again.status_code in (200, 202)
    assert again.get_json()["id"] == first.get_json()["id"]
    view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=ada).get_json()
    tension = next(a for a in view["problems"][0]["answers"] if a["name"] == "tension")
    assert tension["attempts_used"] == 1
