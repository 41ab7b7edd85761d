"""Submitting over the API: 202 + Location at once, graded in the background, retries made safe."""

import pytest


def _submit(client, headers, text="m*g/3", answer="tension", key=None, **extra):
    if key:
        headers = {**headers, "Idempotency-Key": key}
    return client.post("/api/v1/problems/yoyo/submissions", json={"answer": answer, "text": text, **extra},
                       headers=headers)


def test_a_submission_is_accepted_at_once_and_graded_in_the_background(client, make_token, yoyo_version, workers, poll):
    _, student = make_token("student")
    response = _submit(client, student)
    assert response.status_code == 202
    body = response.get_json()
    assert response.headers["Location"] == body["links"]["self"] == f"/api/v1/submissions/{body['id']}"
    assert body["status"] in ("queued", "running", "done") and body["answer"] == "tension"
    graded = poll(response.headers["Location"], student)
    # The yo-yo's string tension is mg/3.
    assert graded["status"] == "done"
    assert (graded["verdict"]["verdict"], graded["verdict"]["score"]) == ("equivalent", 1.0)


def test_a_wrong_answer_gets_its_verdict(client, make_token, yoyo_version, workers, poll):
    _, student = make_token("student")
    graded = poll(_submit(client, student, text="m*g").headers["Location"], student)
    assert graded["verdict"]["verdict"] == "not_equivalent" and graded["verdict"]["score"] == 0.0
    # The feedback speaks to the student; the technical reason stays for instructors and programs.
    assert graded["verdict"]["feedback"] and graded["verdict"]["summary"] is None and graded["verdict"]["reason"]


@pytest.mark.parametrize("text, column, code", [("m g /", 5, "syntax"), ("m*g/(3", 5, "unbalanced"),
                                                ("m*q", 3, "unknown_name")])
def test_an_unreadable_answer_is_refused_and_is_not_an_attempt(client, make_token, yoyo_version, text, column, code):
    _, student = make_token("student")
    response = _submit(client, student, text=text)
    assert response.status_code == 422 and "Location" not in response.headers
    body = response.get_json()
    assert body["type"] == "urn:lagrade:error:unreadable-answer"
    # 1-based, as the caret shows it; the detail says the same place in words.
    assert (body["error"]["code"], body["error"]["column"], body["error"]["position"]) == (code, column, column - 1)
    assert f"at character {column}" in body["detail"]
    assert client.get("/api/v1/submissions/1", headers=student).status_code == 404  # nothing was stored


def test_the_same_text_again_is_the_same_attempt(client, make_token, yoyo_version, workers, poll):
    _, student = make_token("student")
    first = _submit(client, student, text="m*g")
    poll(first.headers["Location"], student)
    again = _submit(client, student, text="m*g")
    assert again.status_code == 200 and again.get_json()["id"] == first.get_json()["id"]
    other = _submit(client, student, text="m*g/2")
    assert other.status_code == 202 and other.get_json()["id"] != first.get_json()["id"]


def test_the_same_idempotency_key_and_body_return_the_same_submission(client, make_token, yoyo_version):
    _, student = make_token("student")
    first = _submit(client, student, key="attempt-1")
    again = _submit(client, student, key="attempt-1")
    assert first.status_code == 202 and again.status_code in (200, 202)
    assert again.get_json()["id"] == first.get_json()["id"]
    assert again.headers["Location"] == first.headers["Location"]


def test_the_same_idempotency_key_with_another_body_is_refused(client, make_token, yoyo_version):
    _, student = make_token("student")
    _submit(client, student, key="attempt-1")
    response = _submit(client, student, key="attempt-1", text="m*g")
    assert response.status_code == 422
    assert response.get_json()["type"] == "urn:lagrade:error:idempotency-key-reused"


def test_an_lms_submits_for_a_student_by_external_id(client, make_token, enrol, yoyo_version):
    lms_id, lms = make_token("lms")
    enrol(lms_id, "MECH", "lms")  # linked to one course: a student it names first is enrolled there
    response = _submit(client, lms, user="canvas-1234")
    assert response.status_code == 202
    submission = response.get_json()
    assert submission["user"]["external_id"] == "canvas-1234"
    # The same student later gets a token of their own and sees that submission.
    again = _submit(client, lms, user="canvas-1234", text="m*g")
    assert again.get_json()["user"]["id"] == submission["user"]["id"]


@pytest.mark.parametrize("body, status, kind", [
    ({"answer": "speed", "text": "1"}, 422, "invalid-submission"),
    ({"answer": "tension"}, 422, "invalid-request"),
    ({"answer": "tension", "text": 3}, 422, "invalid-request"),
    ({"answer": "tension", "text": "m" * 5000}, 422, "invalid-request"),
    ({"answer": "tension", "text": "m", "extra": 1}, 422, "invalid-request"),
])
def test_bad_submissions_are_refused_with_a_problem_document(client, make_token, yoyo_version, body, status, kind):
    _, student = make_token("student")
    response = client.post("/api/v1/problems/yoyo/submissions", json=body, headers=student)
    assert response.status_code == status
    assert response.mimetype == "application/problem+json"
    assert response.get_json()["type"] == f"urn:lagrade:error:{kind}"


def test_a_body_that_is_not_json_is_refused(client, make_token, yoyo_version):
    _, student = make_token("student")
    response = client.post("/api/v1/problems/yoyo/submissions", data="answer=tension", headers=student,
                           content_type="application/x-www-form-urlencoded")
    assert response.status_code == 415


def test_an_lms_must_name_the_student(client, make_token, yoyo_version):
    _, lms = make_token("lms")
    assert _submit(client, lms).status_code == 422


def test_a_submission_to_an_unknown_problem_is_404(client, make_token, yoyo_version):
    _, student = make_token("student")
    response = client.post("/api/v1/problems/nope/submissions", json={"answer": "a", "text": "1"}, headers=student)
    assert response.status_code == 404


def test_a_counterexample_never_shows_the_reference_value(client, make_token, yoyo_version, workers, poll):
    _, student = make_token("student")
    graded = poll(_submit(client, student, text="m*g/2").headers["Location"], student)
    example = graded["verdict"]["counterexample"]
    # Where the answer fails and what it gives there, but not the value of m g/3.
    assert example["values"] and "answer" in example
    assert "reference" not in example and "relative_difference" not in example


def test_an_equation_counterexample_shows_no_value_of_the_reference():
    from grader.answers import check
    from grader.web.api.submissions import _student_counterexample

    # thetaddot*l*3 = -g*sin(theta) is not the pendulum's equation times a state-free factor.
    pendulum = {"g": {"dimension": "acceleration", "domain": "positive"},
                "l": {"dimension": "length", "domain": "positive"},
                "theta": {"dimension": "angle", "domain": "real", "kind": "coordinate"},
                "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}
    v = check("thetaddot = -g*sin(theta)/l", "thetaddot = -g*sin(theta)*theta/l", pendulum, kind="equation")
    assert v.verdict == "not_equivalent" and "reference_there" in v.counterexample
    shown = _student_counterexample(v.counterexample)
    assert shown["values"] and not [k for k in shown if "reference" in k]


def test_an_lms_acts_only_for_students_of_its_own_courses(client, make_token, enrol, yoyo_version):
    # an LMS of one course submitted (and then read the results) for the students of every other one
    moodle_id, moodle = make_token("lms", name="Moodle")
    enrol(moodle_id, "MECH", "lms")
    theirs_id, _ = make_token("student", external_id="other-1")
    enrol(theirs_id, "OTHER", "student")
    ours_id, _ = make_token("student", external_id="mech-1")
    enrol(ours_id, "MECH", "student")
    assert _submit(client, moodle, user="mech-1").status_code == 202
    refused = _submit(client, moodle, user="other-1")
    assert refused.status_code == 422 and "not a student of your courses" in refused.get_json()["detail"]
    # "unknown", "not yours" and "not a student" read the same: nothing tells who exists here
    instructor_id, _ = make_token("instructor", external_id="ine-1")
    enrol(instructor_id, "MECH", "instructor")
    assert _submit(client, moodle, user="ine-1").get_json()["detail"] == \
        refused.get_json()["detail"].replace("other-1", "ine-1")


@pytest.mark.parametrize("courses", [0, 2])
def test_an_lms_of_no_course_or_several_names_no_new_student(client, make_token, enrol, yoyo_version, courses):
    lms_id, lms = make_token("lms")
    for code in ("MECH", "OTHER")[:courses]:
        enrol(lms_id, code, "lms")
    assert _submit(client, lms, user="newcomer").status_code == 422


def test_an_lms_cannot_take_the_id_an_lti_launch_gives(client, make_token, enrol, yoyo_version):
    # anyone computes "lti:" + sha256(issuer, sub); made first here, it locked the person out of LTI
    lms_id, lms = make_token("lms")
    enrol(lms_id, "MECH", "lms")
    assert _submit(client, lms, user="lti:" + "0" * 64).status_code == 422


def test_an_instructor_acts_for_students_of_the_courses_they_teach(client, make_token, enrol, yoyo_version):
    teacher_id, teacher = make_token("instructor")
    enrol(teacher_id, "MECH", "instructor")
    ours_id, _ = make_token("student", external_id="mech-1")
    enrol(ours_id, "MECH", "student")
    theirs_id, _ = make_token("student", external_id="other-1")
    enrol(theirs_id, "OTHER", "student")
    assert _submit(client, teacher, user="mech-1").status_code == 202
    assert _submit(client, teacher, user="other-1").status_code == 422
    assert _submit(client, teacher, user="nobody-yet").status_code == 422
