"""The OpenAPI document is generated from the routes: every API route is in it, with its schemas."""

import pytest


@pytest.fixture
def document(client):
    response = client.get("/api/v1/openapi.json")
    assert response.status_code == 200
    return response.get_json()


def test_the_document_is_valid_openapi_3(document):
    validator = pytest.importorskip("openapi_spec_validator")
    validator.validate(document)
    assert document["openapi"].startswith("3.")


def test_every_api_route_is_documented_and_nothing_else(app, document):
    routes = {
        (rule.rule.removeprefix("/api/v1").replace("<int:", "<").replace("<", "{").replace(">", "}"), method.lower())
        for rule in app.url_map.iter_rules() if rule.endpoint.startswith("api.")
        for method in rule.methods - {"HEAD", "OPTIONS"}
    }
    documented = {(path, method) for path, item in document["paths"].items() for method in item}
    assert documented == routes


def test_operations_carry_their_docstring_roles_and_schemas(document):
    submit = document["paths"]["/problems/{slug}/submissions"]["post"]
    assert submit["summary"] == "Submit an answer for grading."
    assert "Roles:" in submit["description"] and submit["security"] == [{"bearer": []}]
    assert submit["requestBody"]["content"]["application/json"]["schema"] == {
        "$ref": "#/components/schemas/SubmissionRequest"}
    assert "Location" in submit["responses"]["202"]["headers"]
    assert {p["name"] for p in submit["parameters"]} == {"slug", "Idempotency-Key"}
    upload = document["paths"]["/problems"]["post"]
    assert "application/toml" in upload["requestBody"]["content"]
    # An upload is derived in the background: 202 with the job to poll, 429 beyond an instructor's limit.
    assert set(upload["responses"]) >= {"202", "429"} and "Location" in upload["responses"]["202"]["headers"]
    assert upload["responses"]["202"]["content"]["application/json"]["schema"] == {
        "$ref": "#/components/schemas/Derivation"}
    assert "404" in document["paths"]["/derivations/{job_id}"]["get"]["responses"]
    assert document["paths"]["/openapi.json"]["get"]["security"] == []


def test_errors_are_documented_as_problem_json(document):
    check = document["paths"]["/check"]["post"]["responses"]
    assert check["429"] == {"$ref": "#/components/responses/429"}
    assert "application/problem+json" in document["components"]["responses"]["429"]["content"]


def test_the_published_request_schema_is_the_one_enforced(client, make_token, document):
    """A field the document does not list is refused: the schema is not just documentation."""
    schema = document["components"]["schemas"]["CheckRequest"]
    assert schema["additionalProperties"] is False and "bogus" not in schema["properties"]
    _, student = make_token("student")
    body = {"reference": "m", "answer": "m", "variables": {}, "bogus": 1}
    response = client.post("/api/v1/check", json=body, headers=student)
    assert response.status_code == 422 and "bogus" in response.get_json()["detail"]
