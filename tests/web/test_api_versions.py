"""A problem's life over the API: list versions, a new version, (un)publish, archive and restore.

The same people as the page tests (``tests/web/conftest_pages.py``): Ada studies MECH, Ine teaches it,
Oth teaches OTHER only; each also has a bearer token here, so one test can ask the API and the pages.
"""

import dataclasses
from pathlib import Path

import pytest
from sqlalchemy import func, select

from grader.store.models import DerivationJob, User
from grader.store.problems import save_problem
from grader.store.users import create_token
from tests.web.conftest_pages import (  # noqa: F401  (fixtures)
    accounts, as_instructor, as_student, csrf, problems, submit_answers,
)

SCENE = (Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml").read_text()
MECH_SCENE = SCENE.replace('id = "yoyo"', 'id = "mech"')  # the real yo-yo, as a new version of "mech"
TOML = "application/toml"


@pytest.fixture
def tokens(app, accounts, make_token) -> dict[str, dict[str, str]]:
    """Authorization headers of Ada, Ine and Oth (the page accounts), an LMS linked to nothing, an admin."""
    made = {}
    with app.extensions["lagrade.db"].write() as session:
        for key in ("ada", "ine", "oth"):
            made[key] = {"Authorization": f"Bearer {create_token(session, session.get(User, accounts[key].id))}"}
    made["lms"], made["adm"] = make_token("lms")[1], make_token("admin")[1]
    return made


def _jobs(app) -> int:
    with app.extensions["lagrade.db"].read() as session:
        return session.scalar(select(func.count()).select_from(DerivationJob))


def _versions(client, headers, slug="mech") -> dict:
    response = client.get(f"/api/v1/problems/{slug}/versions", headers=headers)
    assert response.status_code == 200, response.get_data(as_text=True)
    return response.get_json()


# --- list ----------------------------------------------------------------------------------------------

def test_the_versions_are_listed_with_the_one_students_see(client, tokens, problems):
    body = _versions(client, tokens["ine"])
    assert (body["id"], body["archived"], body["archived_at"], body["published_version"]) == ("mech", False, None, 1)
    [version] = body["versions"]
    assert (version["version"], version["title"], version["published"]) == (1, "Mech problem", True)
    assert version["links"] == {"publish": "/api/v1/problems/mech/versions/1/publish",
                                "unpublish": "/api/v1/problems/mech/versions/1/unpublish"}
    assert body["links"]["archive"] == "/api/v1/problems/mech/archive"
    assert _versions(client, tokens["ine"], "draft")["published_version"] is None  # a draft only: students see nothing


def test_an_instructor_finds_the_versions_from_the_problem(client, tokens, problems):
    body = client.get("/api/v1/problems/mech", headers=tokens["ine"]).get_json()
    assert body["links"]["versions"] == "/api/v1/problems/mech/versions"
    assert "versions" not in client.get("/api/v1/problems/mech", headers=tokens["ada"]).get_json()["links"]


# --- a new version ---------------------------------------------------------------------------------------

def test_a_new_version_is_derived_as_a_draft_and_students_keep_the_published_one(
        app, client, tokens, problems, derivers, poll, as_student):
    response = client.post("/api/v1/problems/mech/versions", data=MECH_SCENE.encode(), content_type=TOML,
                           headers=tokens["ine"])
    assert response.status_code == 202 and response.headers["Location"] == response.get_json()["links"]["self"]
    job = poll(response.headers["Location"], tokens["ine"])
    assert job["status"] == "done" and job["problem"] == {"id": "mech", "version": 2, "new_version": True}
    body = _versions(client, tokens["ine"])
    assert [(v["version"], v["published"]) for v in body["versions"]] == [(1, True), (2, False)]
    assert body["published_version"] == 1
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).get_json()["version"] == 1
    assert "Mech problem" in as_student.get("/problems/mech").get_data(as_text=True)
    # Published, it is what students see, through the API and the pages.
    published = client.post("/api/v1/problems/mech/versions/2/publish", headers=tokens["ine"]).get_json()
    assert published["changed"] is True and published["problem"]["published_version"] == 2
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).get_json()["title"].startswith("Yo-yo")
    assert "Mech problem" not in as_student.get("/problems/mech").get_data(as_text=True)


def test_the_newest_scene_file_again_is_not_derived(app, client, tokens, problems):
    response = client.post("/api/v1/problems/mech/versions", data=b'id = "mech"\n', content_type=TOML,
                           headers=tokens["ine"])
    body = response.get_json()
    assert response.status_code == 200 and body["changed"] is False and "same as version 1" in body["detail"]
    assert _jobs(app) == 0 and len(body["problem"]["versions"]) == 1


def test_the_job_of_a_new_version_is_followed_by_the_courses_instructors(app, client, tokens, problems, accounts):
    location = client.post("/api/v1/problems/mech/versions", data=MECH_SCENE.encode(), content_type=TOML,
                           headers=tokens["adm"]).headers["Location"]
    # The job joins the problem's course, so the course's instructor sees it, another course's does not.
    assert client.get(location, headers=tokens["ine"]).status_code == 200
    assert client.get(location, headers=tokens["oth"]).status_code == 404


@pytest.mark.parametrize("data, content_type, status, kind", [
    (SCENE.encode(), TOML, 422, "wrong-scene-id"),  # another id would be another problem
    (b'id = "mech"\n[energy\n', TOML, 422, "invalid-scene"),
    (b"  \n", TOML, 422, "invalid-scene"),
    (b"", TOML, 422, "invalid-scene"),
    (MECH_SCENE.encode(), "application/json", 415, "unsupported-media-type"),
    (MECH_SCENE.encode(), "text/plain", 415, "unsupported-media-type"),
    (b"#" * (300 * 1024), TOML, 413, "too-large"),
    (b'id = "mech"\n# \xff\xfe\n', TOML, 400, "invalid-scene"),
])
def test_a_body_that_cannot_be_a_new_version_is_refused_and_nothing_is_queued(
        app, client, tokens, problems, data, content_type, status, kind):
    response = client.post("/api/v1/problems/mech/versions", data=data, content_type=content_type,
                           headers=tokens["ine"])
    assert response.status_code == status and response.mimetype == "application/problem+json"
    assert response.get_json()["type"] == f"urn:lagrade:error:{kind}" and response.get_json()["detail"]
    assert _jobs(app) == 0


def test_a_third_new_version_while_two_wait_is_refused_with_retry_after(app, client, tokens, problems):
    sources = [MECH_SCENE + f"\n# edit {n}\n" for n in range(3)]
    statuses = [client.post("/api/v1/problems/mech/versions", data=s.encode(), content_type=TOML,
                            headers=tokens["ine"]) for s in sources]
    assert [r.status_code for r in statuses] == [202, 202, 429]
    assert int(statuses[2].headers["Retry-After"]) > 0
    assert statuses[2].get_json()["type"] == "urn:lagrade:error:too-many-derivations" and _jobs(app) == 2


# --- unpublish, publish ------------------------------------------------------------------------------------

def test_unpublishing_hides_the_version_from_students_through_the_api_and_the_pages(
        client, tokens, problems, as_student):
    response = client.post("/api/v1/problems/mech/versions/1/unpublish", headers=tokens["ine"])
    body = response.get_json()
    assert response.status_code == 200 and body["changed"] is True
    assert "students now see nothing" in body["detail"] and body["problem"]["published_version"] is None
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).status_code == 404
    assert "mech" not in [p["id"] for p in client.get("/api/v1/problems", headers=tokens["ada"]).get_json()["problems"]]
    assert client.post("/api/v1/problems/mech/submissions", json={"answer": "tension", "text": "m*g/3"},
                       headers=tokens["ada"]).status_code == 404
    assert as_student.get("/problems/mech").status_code == 404
    assert "Mech problem" not in as_student.get("/problems").get_data(as_text=True)
    # Its managers still see it, and publishing it again shows it to students again.
    assert client.get("/api/v1/problems/mech", headers=tokens["ine"]).get_json()["published"] is False
    assert client.post("/api/v1/problems/mech/versions/1/publish", headers=tokens["ine"]).get_json()["changed"] is True
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).status_code == 200
    assert as_student.get("/problems/mech").status_code == 200


def test_unpublishing_the_newest_shows_students_the_published_one_before_it(app, client, tokens, problems, yoyo):
    with app.extensions["lagrade.db"].write() as session:  # version 2 of mech, published
        save_problem(session, dataclasses.replace(yoyo, slug="mech", title="Mech v2", source='id = "mech"\n# 2\n'))
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).get_json()["version"] == 2
    body = client.post("/api/v1/problems/mech/versions/2/unpublish", headers=tokens["ine"]).get_json()
    assert "students now see version 1" in body["detail"] and body["problem"]["published_version"] == 1
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).get_json()["version"] == 1


@pytest.mark.parametrize("action, slug, number, detail", [
    ("publish", "mech", 1, "Version 1 is already published."),
    ("unpublish", "draft", 1, "Version 1 is not published."),
])
def test_doing_it_again_changes_nothing_and_says_so(client, tokens, problems, action, slug, number, detail):
    response = client.post(f"/api/v1/problems/{slug}/versions/{number}/{action}", headers=tokens["ine"])
    assert response.status_code == 200 and response.get_json()["changed"] is False
    assert response.get_json()["detail"] == detail


@pytest.mark.parametrize("action", ["publish", "unpublish"])
@pytest.mark.parametrize("number", [2, 0, 2**31 - 1])
def test_a_version_that_does_not_exist_is_not_found(client, tokens, problems, action, number):
    response = client.post(f"/api/v1/problems/mech/versions/{number}/{action}", headers=tokens["ine"])
    assert response.status_code == 404 and response.mimetype == "application/problem+json"


# --- archive, restore --------------------------------------------------------------------------------------

def test_an_archived_problem_vanishes_for_students_everywhere_and_comes_back(app, client, tokens, problems,
                                                                             as_student):
    response = client.post("/api/v1/problems/mech/archive", headers=tokens["ine"])
    body = response.get_json()
    assert response.status_code == 200 and body["changed"] is True and body["problem"]["archived"] is True
    archived_at = body["problem"]["archived_at"]
    assert archived_at.endswith("Z")
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).status_code == 404
    assert "mech" not in [p["id"] for p in client.get("/api/v1/problems", headers=tokens["ada"]).get_json()["problems"]]
    assert client.post("/api/v1/problems/mech/submissions", json={"answer": "tension", "text": "m*g/3"},
                       headers=tokens["ada"]).status_code == 404
    assert as_student.get("/problems/mech").status_code == 404
    assert submit_answers(as_student, "mech", tension="m*g/3").status_code == 404
    assert _versions(client, tokens["ine"])["archived"] is True  # its managers keep it
    # Archiving twice is a no-op, as on the page: the first date stays.
    again = client.post("/api/v1/problems/mech/archive", headers=tokens["ine"]).get_json()
    assert (again["changed"], again["detail"]) == (False, "The problem is archived already.")
    assert again["problem"]["archived_at"] == archived_at
    restored = client.post("/api/v1/problems/mech/restore", headers=tokens["ine"]).get_json()
    assert restored["changed"] is True and restored["problem"]["archived"] is False
    assert client.get("/api/v1/problems/mech", headers=tokens["ada"]).status_code == 200
    assert as_student.get("/problems/mech").status_code == 200
    twice = client.post("/api/v1/problems/mech/restore", headers=tokens["ine"]).get_json()
    assert (twice["changed"], twice["detail"]) == (False, "The problem is not archived.")


@pytest.mark.parametrize("page, form, api", [
    ("/instructor/problems/mech/archive", {}, "/api/v1/problems/mech/archive"),
    ("/instructor/problems/mech/versions/1/unpublish", {}, "/api/v1/problems/mech/versions/1/unpublish"),
])
def test_the_page_and_the_api_change_the_same_state(client, tokens, problems, as_instructor, page, form, api):
    assert as_instructor.post(page, data=dict(form, csrf_token=csrf(as_instructor))).status_code == 302
    assert client.post(api, headers=tokens["ine"]).get_json()["changed"] is False  # done already, by the page


# --- who may --------------------------------------------------------------------------------------------

OPERATIONS = [
    ("GET", "/api/v1/problems/{slug}/versions", {}),
    ("POST", "/api/v1/problems/{slug}/versions", {"data": MECH_SCENE.encode(), "content_type": TOML}),
    ("POST", "/api/v1/problems/{slug}/versions/1/publish", {}),
    ("POST", "/api/v1/problems/{slug}/versions/1/unpublish", {}),
    ("POST", "/api/v1/problems/{slug}/archive", {}),
    ("POST", "/api/v1/problems/{slug}/restore", {}),
]


@pytest.mark.parametrize("method, url, send", OPERATIONS, ids=[f"{m} {u}" for m, u, _ in OPERATIONS])
@pytest.mark.parametrize("who, slug, status", [
    ("ada", "mech", 403),  # a student's token may never manage problems
    ("lms", "mech", 403),  # nor may an LMS's
    ("oth", "mech", 404),  # another course's instructor may not learn it exists
    ("ine", "nope", 404),
    (None, "mech", 401),
])
def test_only_those_who_manage_the_problem_may(app, client, tokens, problems, method, url, send, who, slug, status):
    headers = tokens[who] if who else {}
    before = _versions(client, tokens["ine"])
    response = client.open(url.format(slug=slug), method=method, headers=headers, **send)
    assert response.status_code == status and response.mimetype == "application/problem+json"
    assert _versions(client, tokens["ine"]) == before and _jobs(app) == 0


def test_an_instructor_of_another_course_with_a_bad_body_still_learns_nothing(client, tokens, problems):
    response = client.post("/api/v1/problems/mech/versions", data=b"not toml [", content_type="text/plain",
                           headers=tokens["oth"])
    assert response.status_code == 404


# --- the document ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("path, method, operation_id", [
    ("/problems/{slug}/versions", "get", "list_versions"),
    ("/problems/{slug}/versions", "post", "create_version"),
    ("/problems/{slug}/versions/{number}/publish", "post", "publish_version"),
    ("/problems/{slug}/versions/{number}/unpublish", "post", "unpublish_version"),
    ("/problems/{slug}/archive", "post", "archive_problem"),
    ("/problems/{slug}/restore", "post", "restore_problem"),
])
def test_the_openapi_document_lists_the_operations(client, path, method, operation_id):
    document = client.get("/api/v1/openapi.json").get_json()
    operation = document["paths"][path][method]
    assert operation["operationId"] == operation_id and operation["security"] == [{"bearer": []}]
    assert "Roles: admin, instructor." in operation["description"]
    assert {"401", "403", "404", "500"} <= set(operation["responses"])
    success = operation["responses"]["202" if operation_id == "create_version" else "200"]
    assert success["content"]["application/json"]["schema"]["$ref"].startswith("#/components/schemas/")
    if operation_id == "create_version":
        assert "application/toml" in operation["requestBody"]["content"]
        assert {"413", "415", "422", "429"} <= set(operation["responses"])
        assert "Location" in success["headers"]


def test_the_schemas_of_the_answers_are_published(client):
    schemas = client.get("/api/v1/openapi.json").get_json()["components"]["schemas"]
    assert {"ProblemVersions", "ProblemChange"} <= set(schemas)
    assert schemas["ProblemChange"]["properties"]["problem"] == {"$ref": "#/components/schemas/ProblemVersions"}
