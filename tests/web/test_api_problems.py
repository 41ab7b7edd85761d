"""Uploading scene files (instructors) and reading problems."""

from pathlib import Path

import pytest

YOYO_SOURCE = (Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml").read_text()


def _upload(client, headers, source=YOYO_SOURCE, content_type="application/toml", query=""):
    return client.post(f"/api/v1/problems{query}", data=source.encode(), headers=headers, content_type=content_type)


def test_an_uploaded_scene_becomes_a_problem_with_derived_answers(client, make_token):
    _, instructor = make_token("instructor")
    response = _upload(client, instructor)
    assert response.status_code == 201 and response.headers["Location"] == "/api/v1/problems/yoyo"
    body = response.get_json()
    # The engine derived the yo-yo: a = 2g/3, T = mg/3.
    references = {a["name"]: a["reference"] for a in body["answers"]}
    assert references["acceleration"] == "2*g/3" and references["tension"] == "g*m/3"
    assert body["version"] == 1 and body["derivation"]["id"] == "yoyo"


def test_the_same_id_again_is_a_new_version_only_if_the_source_changed(client, make_token):
    _, instructor = make_token("instructor")
    assert _upload(client, instructor).status_code == 201
    same = _upload(client, instructor)
    assert same.status_code == 200 and same.get_json()["version"] == 1
    edited = _upload(client, instructor, YOYO_SOURCE + "\n# a typo fixed\n")
    assert edited.status_code == 201 and edited.get_json()["version"] == 2


def test_an_unpublished_upload_is_hidden_from_students(client, make_token):
    _, instructor = make_token("instructor")
    _, student = make_token("student")
    assert _upload(client, instructor, query="?published=false").status_code == 201
    assert client.get("/api/v1/problems/yoyo", headers=student).status_code == 404


@pytest.mark.parametrize("source, content_type, status, kind", [
    ('id = "x"\n[energy\n', "application/toml", 422, "invalid-scene"),
    (YOYO_SOURCE.replace("m*g*s", "m*g*sss"), "application/toml", 422, "invalid-scene"),
    (YOYO_SOURCE, "application/json", 415, "unsupported-media-type"),
    ("x" * (300 * 1024), "application/toml", 413, "too-large"),
])
def test_bad_uploads_are_refused_with_the_reason(client, make_token, source, content_type, status, kind):
    _, instructor = make_token("instructor")
    response = _upload(client, instructor, source, content_type)
    assert response.status_code == status
    assert response.mimetype == "application/problem+json"
    assert response.get_json()["type"] == f"urn:lagrade:error:{kind}"


def test_a_scene_error_names_the_problem(client, make_token):
    _, instructor = make_token("instructor")
    response = _upload(client, instructor, YOYO_SOURCE.replace('potential = "-m*g*s"', 'potential = "-m*g*tehta"'))
    assert response.status_code == 422 and "tehta" in response.get_json()["detail"]


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
