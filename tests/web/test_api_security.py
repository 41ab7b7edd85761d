"""Students never see references or other students' work; roles, rate limits, CSRF and cookies."""

import pytest
from flask import session

REFERENCE_TEXTS = ("g*m/3", "2*g/3", r"\\frac{g m}{3}", r"\\frac{2 g}{3}")
# The instructor's message for a known wrong answer: shown after such a submission, not before.
FEEDBACK_MESSAGE = "less than the weight"


def _leaks(body: str, *also: str) -> list[str]:
    return [text for text in REFERENCE_TEXTS + also if text in body]


@pytest.mark.parametrize("url", ["/api/v1/problems", "/api/v1/problems/yoyo"])
def test_students_never_see_references(client, make_token, yoyo_version, url):
    _, student = make_token("student")
    response = client.get(url, headers=student)
    assert response.status_code == 200
    assert _leaks(response.get_data(as_text=True), FEEDBACK_MESSAGE) == []


def test_a_students_submission_shows_no_reference(client, make_token, yoyo_version, workers, poll):
    _, student = make_token("student")
    location = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g"},
                           headers=student).headers["Location"]
    graded = poll(location, student)
    assert graded["verdict"]["verdict"] == "not_equivalent"
    assert _leaks(client.get(location, headers=student).get_data(as_text=True)) == []
    assert FEEDBACK_MESSAGE in str(graded["verdict"]["feedback"])  # the instructor's hint for m*g


def test_instructors_do_see_references(client, make_token, yoyo_version):
    _, instructor = make_token("instructor")
    body = client.get("/api/v1/problems/yoyo", headers=instructor).get_json()
    assert {a["name"]: a["reference"] for a in body["answers"]} == {"acceleration": "2*g/3", "tension": "g*m/3"}


def test_students_see_only_their_own_submissions(client, make_token, yoyo_version):
    _, ada = make_token("student", name="Ada")
    _, bob = make_token("student", name="Bob")
    location = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g/3"},
                           headers=ada).headers["Location"]
    assert client.get(location, headers=ada).status_code == 200
    assert client.get(location, headers=bob).status_code == 404  # not even its existence


def test_an_lms_sees_only_what_it_sent(client, make_token, enrol, yoyo_version):
    moodle_id, moodle = make_token("lms", name="Moodle")
    canvas_id, canvas = make_token("lms", name="Canvas")
    enrol(moodle_id, "MECH", "lms")
    enrol(canvas_id, "MECH", "lms")
    location = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g", "user": "s1"},
                           headers=moodle).headers["Location"]
    assert client.get(location, headers=moodle).status_code == 200
    assert client.get(location, headers=canvas).status_code == 404


def test_a_student_cannot_submit_as_someone_else(client, make_token, yoyo_version):
    _, student = make_token("student", external_id="s1")
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "x", "user": "s2"},
                           headers=student)
    assert response.status_code == 403


def test_students_do_not_see_unpublished_problems(app, client, make_token, yoyo):
    from grader.store.problems import save_problem

    with app.extensions["lagrade.db"].write() as s:
        save_problem(s, yoyo, published=False)
    _, student = make_token("student")
    _, instructor = make_token("instructor")
    assert client.get("/api/v1/problems/yoyo", headers=student).status_code == 404
    assert client.get("/api/v1/problems", headers=student).get_json() == {"problems": []}
    assert client.get("/api/v1/problems/yoyo", headers=instructor).status_code == 200


@pytest.mark.parametrize("method, url", [
    ("GET", "/api/v1/problems/yoyo/grades"),
    ("POST", "/api/v1/problems/yoyo/regrade"),
    ("POST", "/api/v1/problems"),
])
@pytest.mark.parametrize("role", ["student", "lms"])
def test_instructor_endpoints_refuse_other_roles(client, make_token, yoyo_version, method, url, role):
    _, headers = make_token(role)
    response = client.open(url, method=method, headers=headers, data=b"x", content_type="application/toml")
    assert response.status_code == 403
    assert response.get_json()["type"] == "urn:lagrade:error:forbidden"


@pytest.mark.parametrize("method, url", [
    ("GET", "/api/v1/problems"), ("GET", "/api/v1/problems/yoyo"), ("POST", "/api/v1/check"),
    ("POST", "/api/v1/problems/yoyo/submissions"), ("GET", "/api/v1/submissions/1"),
    ("GET", "/api/v1/problems/yoyo/grades"),
])
@pytest.mark.parametrize("authorization", [None, "Bearer lg_not-a-token", "Basic dXNlcjpwYXNz"])
def test_every_endpoint_needs_a_valid_token(client, yoyo_version, method, url, authorization):
    headers = {"Authorization": authorization} if authorization else {}
    response = client.open(url, method=method, headers=headers, json={})
    assert response.status_code == 401
    assert response.headers["WWW-Authenticate"].startswith("Bearer")


def test_admins_may_do_what_instructors_may(client, make_token, yoyo_version):
    _, admin = make_token("admin")
    assert client.get("/api/v1/problems/yoyo/grades", headers=admin).status_code == 200


def test_submissions_are_rate_limited_per_user_with_retry_after(app, client, make_token, yoyo_version):
    app.config["RATE_LIMITS"] = {"submit": (6, 3)}
    _, ada = make_token("student", name="Ada")
    _, bob = make_token("student", name="Bob")
    body = {"answer": "tension", "text": "m*g/3"}
    codes = [client.post("/api/v1/problems/yoyo/submissions", json=body, headers=ada).status_code for _ in range(4)]
    assert codes == [202, 202, 202, 429]
    limited = client.post("/api/v1/problems/yoyo/submissions", json=body, headers=ada)
    assert limited.mimetype == "application/problem+json"
    assert 1 <= int(limited.headers["Retry-After"]) <= 30  # the window: 3 in any 30 s (6 a minute)
    # Another student's bucket is untouched.
    assert client.post("/api/v1/problems/yoyo/submissions", json=body, headers=bob).status_code == 202


def test_checks_are_rate_limited(app, client, make_token):
    app.config["RATE_LIMITS"] = {"check": (60, 1)}
    _, student = make_token("student")
    # The bucket is taken before the body is read, so even bad requests count.
    first = client.post("/api/v1/check", json={}, headers=student)
    second = client.post("/api/v1/check", json={}, headers=student)
    assert (first.status_code, second.status_code) == (422, 429)


@pytest.fixture
def form_app(app):
    """A page-style form endpoint, as the HTML blueprints have."""

    @app.post("/form")
    def form():
        return "ok"

    @app.get("/form")
    def form_page():
        from grader.web.security import csrf_token

        return csrf_token()

    return app


def test_a_form_post_without_the_csrf_token_is_refused(form_app):
    client = form_app.test_client()
    assert client.post("/form", data={"x": "1"}).status_code == 400
    token = client.get("/form").get_data(as_text=True)
    assert client.post("/form", data={"x": "1", "csrf_token": "wrong"}).status_code == 400
    assert client.post("/form", data={"x": "1", "csrf_token": token}).status_code == 200
    assert client.post("/form", headers={"X-CSRF-Token": token}).status_code == 200


def test_the_bearer_api_is_exempt_from_csrf(client, make_token, yoyo_version):
    _, student = make_token("student")
    response = client.post("/api/v1/problems/yoyo/submissions", json={"answer": "tension", "text": "m*g"},
                           headers=student)
    assert response.status_code == 202


@pytest.mark.parametrize("secure", [False, True])
def test_session_cookies_are_httponly_lax_and_secure_when_configured(form_app, secure):
    form_app.config["SESSION_COOKIE_SECURE"] = secure
    client = form_app.test_client()
    client.get("/form")
    cookie = client.get_cookie("session")
    assert cookie.http_only and cookie.same_site == "Lax" and cookie.secure is secure


def test_the_csrf_token_is_kept_in_the_session(form_app):
    with form_app.test_request_context("/form"):
        from grader.web.security import csrf_token

        token = csrf_token()
        assert session["_csrf"] == token and csrf_token() == token
