"""Grades as JSON and CSV, and regrading a problem after a fix (instructors)."""

import csv
import dataclasses
import io

import pytest

from grader.store.problems import save_problem


def _submit(client, headers, text):
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": text},
                           headers=headers)
    return response.headers["Location"]


@pytest.fixture
def graded(client, make_token, yoyo_version, workers, poll):
    """Ada answers wrong then right; Bob answers wrong once. All graded."""
    ada_id, ada = make_token("student", external_id="ada")
    bob_id, bob = make_token("student", external_id="bob")
    for headers, text in ((ada, "m*g"), (ada, "m*g/3"), (bob, "2*m*g")):
        poll(_submit(client, headers, text), headers)
    return {"ada": ada_id, "bob": bob_id}


def test_grades_as_json_show_latest_and_best(client, make_token, graded):
    _, instructor = make_token("instructor")
    body = client.get("/api/v1/problems/yoyo/grades", headers=instructor).get_json()
    rows = {row["external_id"]: row for row in body["grades"]}
    assert (rows["ada"]["submissions"], rows["ada"]["latest_verdict"], rows["ada"]["best_score"]) == (2, "equivalent", 1.0)
    assert (rows["bob"]["submissions"], rows["bob"]["latest_verdict"], rows["bob"]["best_score"]) == (1, "not_equivalent", 0.0)


@pytest.mark.parametrize("query, headers", [("?format=csv", {}), ("", {"Accept": "text/csv"})])
def test_grades_as_csv(client, make_token, graded, query, headers):
    _, instructor = make_token("instructor")
    response = client.get(f"/api/v1/problems/yoyo/grades{query}", headers={**instructor, **headers})
    assert response.mimetype == "text/csv"
    rows = list(csv.DictReader(io.StringIO(response.get_data(as_text=True))))
    assert {(r["external_id"], r["answer"], r["best_score"]) for r in rows} == {("ada", "tension", "1.0"),
                                                                               ("bob", "tension", "0.0")}


def test_regrade_grades_everything_again_against_the_newest_version(app, client, make_token, graded, yoyo, poll):
    _, instructor = make_token("instructor")
    # The instructor "fixes" the reference (here: says the tension is 2mg, so Bob becomes right).
    fixed = dataclasses.replace(yoyo, source=yoyo.source + "# fixed\n",
                                references=[dict(r, reference="2*g*m") if r["name"] == "tension" else r
                                            for r in yoyo.references])
    with app.extensions["lagrade.db"].write() as session:
        save_problem(session, fixed)
    response = client.post("/api/v1/problems/yoyo/regrade", headers=instructor)
    assert response.status_code == 202 and response.get_json() == {
        "queued": 3, "version": 2, "links": {"grades": "/api/v1/problems/yoyo/grades"}}
    for submission_id in range(1, 4):
        poll(f"/api/v1/submissions/{submission_id}", instructor)
    rows = {r["external_id"]: r for r in client.get("/api/v1/problems/yoyo/grades", headers=instructor).get_json()["grades"]}
    assert rows["bob"]["latest_verdict"] == "equivalent" and rows["ada"]["latest_verdict"] == "not_equivalent"
    submission = client.get("/api/v1/submissions/3", headers=instructor).get_json()
    assert submission["grading_round"] == 2 and submission["verdict"]["version"] == 2


@pytest.mark.parametrize("teaches, sees", [
    # yoyo is in no course, shared: each instructor sees the students of their own courses and those in no
    # course, never another course's (an instructor of OTHER read MECH's names and scores through it)
    ("MECH", {"ada", "cyd"}), ("OTHER", {"bob", "cyd"}), (None, {"cyd"}),
])
def test_a_shared_problems_grades_show_an_instructor_only_their_own_students(
        client, make_token, enrol, yoyo_version, workers, poll, teaches, sees):
    people = {}
    for name, course in (("ada", "MECH"), ("bob", "OTHER"), ("cyd", None)):
        user_id, headers = make_token("student", external_id=name)
        if course:
            enrol(user_id, course, "student")
        poll(_submit(client, headers, "m*g/3"), headers)
        people[name] = user_id
    teacher_id, teacher = make_token("instructor")
    if teaches:
        enrol(teacher_id, teaches, "instructor")
    for query in ("", "?format=csv"):
        response = client.get(f"/api/v1/problems/yoyo/grades{query}", headers=teacher)
        rows = response.get_json()["grades"] if not query else list(csv.DictReader(io.StringIO(response.get_data(as_text=True))))
        assert {row["external_id"] for row in rows} == sees
    _, admin = make_token("admin")
    assert {row["external_id"] for row in client.get("/api/v1/problems/yoyo/grades", headers=admin).get_json()["grades"]} \
        == {"ada", "bob", "cyd"}


def test_a_shared_problems_submission_is_seen_by_its_students_instructors_only(client, make_token, enrol, yoyo_version):
    ada_id, ada = make_token("student", external_id="ada")
    enrol(ada_id, "MECH", "student")
    location = _submit(client, ada, "m*g/3")
    ours_id, ours = make_token("instructor")
    enrol(ours_id, "MECH", "instructor")
    theirs_id, theirs = make_token("instructor")
    enrol(theirs_id, "OTHER", "instructor")
    assert client.get(location, headers=ours).status_code == 200
    assert client.get(location, headers=theirs).status_code == 404  # as if it did not exist
