"""Uploading scene files (instructors) and reading problems."""

from pathlib import Path

import pytest

YOYO_SOURCE = (Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml").read_text()


def _upload(client, headers, source=YOYO_SOURCE, content_type="application/toml", query=""):
    return client.post(f"/api/v1/problems{query}", data=source.encode(), headers=headers, content_type=content_type)


def _derived(client, poll, headers, source=YOYO_SOURCE, query="") -> dict:
    """Upload, check the 202, and poll the job until it is done or failed."""
    response = _upload(client, headers, source, query=query)
    assert response.status_code == 202, response.get_data(as_text=True)
    assert response.headers["Location"] == response.get_json()["links"]["self"]
    return poll(response.headers["Location"], headers)


def test_an_upload_is_accepted_at_once_and_queued_for_derivation(client, make_token):
    _, instructor = make_token("instructor")
    response = _upload(client, instructor)  # no derivation workers run: the job waits
    body = response.get_json()
    assert response.status_code == 202 and response.headers["Location"] == f"/api/v1/derivations/{body['id']}"
    assert (body["status"], body["queued_ahead"], body["problem"], body["error"]) == ("queued", 0, None, None)
    assert client.get(response.headers["Location"], headers=instructor).get_json()["status"] == "queued"


def test_an_uploaded_scene_becomes_a_problem_with_derived_answers(client, make_token, derivers, poll):
    _, instructor = make_token("instructor")
    job = _derived(client, poll, instructor)
    assert job["status"] == "done" and job["problem"] == {"id": "yoyo", "version": 1, "new_version": True}
    assert job["links"]["problem"] == "/api/v1/problems/yoyo" and job["finished_at"]
    body = client.get(job["links"]["problem"], headers=instructor).get_json()
    # The engine derived the yo-yo: a = 2g/3, T = mg/3.
    references = {a["name"]: a["reference"] for a in body["answers"]}
    assert references["acceleration"] == "2*g/3" and references["tension"] == "g*m/3"
    assert body["version"] == 1 and body["derivation"]["id"] == "yoyo"


def test_the_same_id_again_is_a_new_version_only_if_the_source_changed(client, make_token, derivers, poll):
    _, instructor = make_token("instructor")
    assert _derived(client, poll, instructor)["problem"]["new_version"] is True
    assert _derived(client, poll, instructor)["problem"] == {"id": "yoyo", "version": 1, "new_version": False}
    edited = _derived(client, poll, instructor, YOYO_SOURCE + "\n# a typo fixed\n")
    assert edited["problem"] == {"id": "yoyo", "version": 2, "new_version": True}


def test_an_unpublished_upload_is_hidden_from_students(client, make_token, derivers, poll):
    _, instructor = make_token("instructor")
    _, student = make_token("student")
    assert _derived(client, poll, instructor, query="?published=false")["status"] == "done"
    assert client.get("/api/v1/problems/yoyo", headers=student).status_code == 404


@pytest.mark.parametrize("source, content_type, status, kind", [
    ('id = "x"\n[energy\n', "application/toml", 422, "invalid-scene"),
    (YOYO_SOURCE, "application/json", 415, "unsupported-media-type"),
    ("x" * (300 * 1024), "application/toml", 413, "too-large"),
    (b"\xff\xfe".decode("latin-1"), "application/toml", 400, "invalid-scene"),
])
def test_uploads_that_are_not_scene_files_are_refused_at_once(client, make_token, source, content_type, status, kind):
    _, instructor = make_token("instructor")
    data = source.encode("latin-1") if status == 400 else source.encode()
    response = client.post("/api/v1/problems", data=data, headers=instructor, content_type=content_type)
    assert response.status_code == status
    assert response.mimetype == "application/problem+json"
    assert response.get_json()["type"] == f"urn:lagrade:error:{kind}"


# A NUL (TOML's "\u0000") anywhere in the scene once passed the upload, failed in the worker as
# "interrupted" minutes later, and two such uploads locked the instructor out with a 429.
@pytest.mark.parametrize("source, where", [
    (YOYO_SOURCE.replace('title = "Yo-yo', 'title = "\\u0000Yo-yo'), "title"),
    (YOYO_SOURCE.replace('id = "yoyo"', 'id = "yoyo\\u0000"'), "id"),
    (YOYO_SOURCE + '\n[[answers]]\nname = "x"\nprompt = "\\u0000"\n', "answers[3].prompt"),
])
def test_a_scene_holding_a_nul_character_is_refused_at_upload_naming_where(app, client, make_token, source, where):
    from sqlalchemy import func, select

    from grader.store.models import DerivationJob

    _, instructor = make_token("instructor")
    for _ in range(3):  # never queued, so never "too many derivations"
        response = _upload(client, instructor, source)
        assert response.status_code == 422 and response.mimetype == "application/problem+json"
        problem = response.get_json()
        assert problem["type"] == "urn:lagrade:error:invalid-scene"
        assert f"upload.toml: {where} holds a NUL character" in problem["detail"]
    with app.extensions["lagrade.db"].read() as session:
        assert session.scalar(select(func.count(DerivationJob.id))) == 0


def test_a_new_version_holding_a_nul_character_is_refused_at_upload(client, make_token, yoyo_version):
    _, instructor = make_token("instructor")
    source = YOYO_SOURCE.replace('title = "Yo-yo', 'title = "\\u0000Yo-yo')
    response = client.post("/api/v1/problems/yoyo/versions", data=source.encode(), headers=instructor,
                           content_type="application/toml")
    assert response.status_code == 422 and "title holds a NUL character" in response.get_json()["detail"]


@pytest.mark.parametrize("source, message", [
    (YOYO_SOURCE.replace('potential = "-m*g*s"', 'potential = "-m*g*tehta"'), "tehta"),
    (YOYO_SOURCE.replace("m*g*s", "m*g*sss"), "not an energy"),
])
def test_a_scene_the_engine_refuses_fails_its_job_with_the_reason(client, make_token, derivers, poll, source, message):
    _, instructor = make_token("instructor")
    job = _derived(client, poll, instructor, source)
    assert job["status"] == "failed" and message in job["error"] and job["problem"] is None
    assert "Traceback" not in job["error"]


def test_an_instructor_has_at_most_two_derivations_waiting(client, make_token):
    _, instructor = make_token("instructor")
    _, colleague = make_token("instructor")
    assert [_upload(client, instructor).status_code for _ in range(2)] == [202, 202]
    refused = _upload(client, instructor)
    assert refused.status_code == 429 and int(refused.headers["Retry-After"]) > 0
    assert refused.get_json()["type"] == "urn:lagrade:error:too-many-derivations"
    assert _upload(client, colleague).status_code == 202  # the limit is per instructor


def test_a_job_is_seen_only_by_its_requester_and_admins(client, make_token):
    _, instructor = make_token("instructor")
    _, colleague = make_token("instructor")
    _, admin = make_token("admin")
    _, student = make_token("student")
    location = _upload(client, instructor).headers["Location"]
    assert client.get(location, headers=instructor).status_code == 200
    assert client.get(location, headers=admin).status_code == 200
    assert client.get(location, headers=colleague).status_code == 404  # no course shared: not even its existence
    assert client.get(location, headers=student).status_code == 403  # the role may not follow derivations
    assert client.get("/api/v1/derivations/999", headers=instructor).status_code == 404


def test_students_read_statement_and_prompts(client, make_token, yoyo_version):
    _, student = make_token("student")
    body = client.get("/api/v1/problems/yoyo", headers=student).get_json()
    assert body["statement"].startswith("A light string")
    assert [a["prompt"] for a in body["answers"]] == ["Acceleration of the axis", "Tension in the string"]
    assert all(set(a) == {"name", "prompt", "kind", "dimension", "variables"} for a in body["answers"])
    assert "derivation" not in body and "engine_version" not in body


def test_problems_are_listed_with_their_newest_version(client, make_token, yoyo_version):
    _, student = make_token("student")
    assert client.get("/api/v1/problems", headers=student).get_json() == {"problems": [
        {"id": "yoyo", "title": "Yo-yo", "version": 1, "links": {"self": "/api/v1/problems/yoyo"}}]}


def test_an_unknown_problem_is_404(client, make_token):
    _, student = make_token("student")
    response = client.get("/api/v1/problems/nope", headers=student)
    assert response.status_code == 404 and response.get_json()["title"] == "Not Found"
