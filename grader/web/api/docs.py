"""``GET /openapi.json`` (the OpenAPI 3 document, generated from the route registry) and ``GET /health``."""

from flask import request

from grader.web.api import bp, spec


@spec.route("/openapi.json", "GET", roles=None,
            responses={200: ("The OpenAPI 3 description of this API.", {"application/json": {"type": "object"}})})
def openapi():
    """This API's OpenAPI 3 document."""
    return spec.openapi(server_url=request.host_url.rstrip("/") + bp.url_prefix)


@spec.route("/health", "GET", roles=None,
            responses={200: ("The server is up.", {"application/json": {"type": "object", "properties": {
                "status": {"type": "string"}}}})})
def health():
    """Liveness: answers without touching the database."""
    return {"status": "ok"}
