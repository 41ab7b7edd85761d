"""Every endpoint and page × every kind of caller → the outcome the access policy promises.

How to read and extend ``ROWS``
-------------------------------
One ``Row`` per request: ``Row(method, rule, url, expect, send)``.

- ``rule`` is the Flask rule exactly as ``app.url_map`` spells it (``/problems/<slug>``); every rule
  and method of the app must have at least one row, and every row must name a real rule, or
  :func:`test_every_route_has_a_row` fails. A new endpoint therefore needs a row here.
- ``url`` is the concrete path; ``{name}`` is filled in from ``world.ids``: ``mech``/``other`` (the
  courses' ids), ``stu``... ``adm`` (users), ``mech_version``, ``submission`` (Ada's, sent by the LMS),
  ``job`` (Ine's queued upload), ``lti_context``. Problems: ``mech`` is published in course MECH,
  ``mech-draft`` a draft in MECH. Course MECH has an assignment ``hw1`` over ``mech``, closed in 2021.
- ``expect`` holds eight outcomes, one per principal, in the order of ``PRINCIPALS``:

  ========== ==========================================================================
  column     who
  ========== ==========================================================================
  anon       nobody signed in, no token
  bad        an unknown bearer token (on pages: nobody signed in)
  stu        Ada, a student enrolled in MECH (signed in, and her token)
  out        Bob, a student enrolled only in OTHER
  ins        Ine, instructor of MECH
  oth        Oth, instructor of OTHER only
  lms        an LMS token linked to MECH, which sent Ada's submission (cannot sign in)
  adm        an admin
  ========== ==========================================================================

  An outcome is ``ok`` (2xx, or a redirect anywhere but the sign-in page), ``login`` (a redirect to
  the sign-in page) or an error status (``401``, ``403``, ``404``, ``422``...). ``404`` means the
  caller may not even learn that the thing exists; ``403`` that they know it exists (or their role
  may never call this endpoint) but may not do this.
- ``send`` is extra keyword arguments for ``client.open`` (a JSON body, form data...). Page POSTs
  carry a valid CSRF token automatically, so the refusals seen are the policy's, not CSRF's.

Every cell runs against a fresh copy of the same database, so a row that changes state (publish,
upload, regrade) cannot change another cell's outcome.
"""

from __future__ import annotations

import dataclasses
import shutil
from datetime import datetime, timezone
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlparse

import pytest
from flask import g
from sqlalchemy import func, select

from grader.jobs import submit
from grader.jobs.derivation_queue import enqueue
from grader.store.db import Database
from grader.store.assignments import create_assignment
from grader.store.migrate import upgrade
from grader.store.models import Course, DerivationJob, Enrolment, ProblemVersion, User
from grader.store.problems import save_problem
from grader.store.users import create_token, create_user
from tests.conftest import YOYO
from tests.web.conftest_pages import InProcessChecker, csrf, form_token

PRINCIPALS = ("anon", "bad", "stu", "out", "ins", "oth", "lms", "adm")
PASSWORD = "matrix password"
SECRET_KEY = "matrix-secret"
SCENE = (Path(__file__).resolve().parents[2] / "problems" / "yoyo.toml").read_text()
MECH_SCENE = SCENE.replace('id = "yoyo"', 'id = "mech"')  # a new version over MECH's problem id


@dataclass(frozen=True)
class Row:
    method: str
    rule: str
    url: str
    expect: str
    send: dict = field(default_factory=dict)

    def outcomes(self) -> dict[str, str]:
        cells = self.expect.split()
        assert len(cells) == len(PRINCIPALS), f"{self.method} {self.url}: {len(cells)} outcomes"
        return dict(zip(PRINCIPALS, cells))


SUBMISSION = {"json": {"answer": "tension", "text": "m*g/3", "user": "ada"}}
CHECK = {"json": {"reference": "m*g", "answer": "g*m", "variables": {
    "m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}}}
UPLOAD = {"data": MECH_SCENE.encode(), "content_type": "application/toml"}
TYPED = {"data": {"answer-tension": "m*g/3"}}
PREVIEW = {"json": {"problem": "mech", "answer": "tension", "text": "m*g/3"}}

ROWS = [
    #   method  rule                                      url                           anon  bad   stu   out   ins   oth   lms   adm
    # --- public -----------------------------------------------------------------------------------------------
    Row("GET", "/api/v1/health", "/api/v1/health",                                     "ok    ok    ok    ok    ok    ok    ok    ok"),
    Row("GET", "/api/v1/openapi.json", "/api/v1/openapi.json",                         "ok    ok    ok    ok    ok    ok    ok    ok"),
    Row("GET", "/static/<path:filename>", "/static/css/lagrade.css",                   "ok    ok    ok    ok    ok    ok    ok    ok"),
    Row("GET", "/", "/",                                                               "login login ok    ok    ok    ok    login ok"),
    Row("GET", "/login", "/login",                                                     "ok    ok    ok    ok    ok    ok    ok    ok"),
    Row("POST", "/login", "/login",                                                    "401   401   401   401   401   401   401   401"),
    Row("POST", "/logout", "/logout",                                                  "login login login login login login login login"),
    Row("GET", "/account", "/account",                                                 "login login ok    ok    ok    ok    login ok"),
    Row("POST", "/account", "/account",                                                "401   401   422   422   422   422   401   422"),
    # --- API: problems --------------------------------------------------------------------------------------
    Row("GET", "/api/v1/problems", "/api/v1/problems",                                 "401   401   ok    ok    ok    ok    ok    ok"),
    Row("GET", "/api/v1/problems/<slug>", "/api/v1/problems/mech",                     "401   401   ok    404   ok    404   ok    ok"),
    Row("GET", "/api/v1/problems/<slug>", "/api/v1/problems/mech-draft",               "401   401   404   404   ok    404   404   ok"),
    Row("GET", "/api/v1/problems/<slug>", "/api/v1/problems/nope",                     "401   401   404   404   404   404   404   404"),
    Row("POST", "/api/v1/problems", "/api/v1/problems",                                "401   401   403   403   ok    403   403   ok", UPLOAD),
    Row("POST", "/api/v1/problems/<slug>/submissions", "/api/v1/problems/mech/submissions",
                                                                                       "401   401   ok    404   ok    404   ok    ok", SUBMISSION),
    Row("POST", "/api/v1/problems/<slug>/submissions", "/api/v1/problems/mech-draft/submissions",
                                                                                       "401   401   404   404   ok    404   404   ok", SUBMISSION),
    Row("GET", "/api/v1/submissions/<int:submission_id>", "/api/v1/submissions/{submission}",
                                                                                       "401   401   ok    404   ok    404   ok    ok"),
    Row("POST", "/api/v1/check", "/api/v1/check",                                      "401   401   ok    ok    ok    ok    ok    ok", CHECK),
    # --- API: grades ------------------------------------------------------------------------------------------
    Row("GET", "/api/v1/problems/<slug>/grades", "/api/v1/problems/mech/grades",       "401   401   403   403   ok    404   ok    ok"),
    Row("GET", "/api/v1/problems/<slug>/grades", "/api/v1/problems/mech/grades?format=csv",
                                                                                       "401   401   403   403   ok    404   403   ok"),
    Row("GET", "/api/v1/problems/<slug>/grades", "/api/v1/problems/mech-draft/grades", "401   401   403   403   ok    404   404   ok"),
    Row("POST", "/api/v1/problems/<slug>/regrade", "/api/v1/problems/mech/regrade",    "401   401   403   403   ok    404   403   ok"),
    # --- API: a problem's life (what the instructor pages do: grader.web.api.versions) ---------------------
    Row("GET", "/api/v1/problems/<slug>/versions", "/api/v1/problems/mech/versions",   "401   401   403   403   ok    404   403   ok"),
    Row("GET", "/api/v1/problems/<slug>/versions", "/api/v1/problems/mech-draft/versions",
                                                                                       "401   401   403   403   ok    404   403   ok"),
    Row("GET", "/api/v1/problems/<slug>/versions", "/api/v1/problems/nope/versions",   "401   401   403   403   404   404   403   404"),
    Row("POST", "/api/v1/problems/<slug>/versions", "/api/v1/problems/mech/versions",  "401   401   403   403   ok    404   403   ok",
        UPLOAD),
    Row("POST", "/api/v1/problems/<slug>/versions/<int:number>/publish",
        "/api/v1/problems/mech-draft/versions/1/publish",                              "401   401   403   403   ok    404   403   ok"),
    Row("POST", "/api/v1/problems/<slug>/versions/<int:number>/publish",
        "/api/v1/problems/mech/versions/9/publish",                                    "401   401   403   403   404   404   403   404"),
    Row("POST", "/api/v1/problems/<slug>/versions/<int:number>/unpublish",
        "/api/v1/problems/mech/versions/1/unpublish",                                  "401   401   403   403   ok    404   403   ok"),
    Row("POST", "/api/v1/problems/<slug>/archive", "/api/v1/problems/mech/archive",    "401   401   403   403   ok    404   403   ok"),
    Row("POST", "/api/v1/problems/<slug>/restore", "/api/v1/problems/mech/restore",    "401   401   403   403   ok    404   403   ok"),
    # --- API: derivation jobs ---------------------------------------------------------------------------------
    Row("GET", "/api/v1/derivations/<int:job_id>", "/api/v1/derivations/{job}",        "401   401   403   403   ok    404   403   ok"),
    # --- student pages (an LMS or a bad token is nobody on a page) --------------------------------------------
    Row("GET", "/problems", "/problems",                                               "login login ok    ok    403   403   login 403"),
    Row("GET", "/problems/<slug>", "/problems/mech",                                   "login login ok    404   403   403   login 403"),
    Row("GET", "/problems/<slug>", "/problems/mech-draft",                             "login login 404   404   403   403   login 403"),
    Row("POST", "/problems/<slug>/preview", "/problems/mech/preview",                  "401   401   ok    404   403   403   401   403", TYPED),
    Row("POST", "/problems/<slug>/submit", "/problems/mech/submit",                    "401   401   ok    404   403   403   401   403", TYPED),
    Row("POST", "/problems/<slug>/submit", "/problems/mech-draft/submit",              "401   401   404   404   403   403   401   403", TYPED),
    Row("POST", "/preview", "/preview",                                                "401   401   ok    404   403   403   401   403", PREVIEW),
    Row("GET", "/submissions/<int:submission_id>", "/submissions/{submission}",        "login login ok    404   403   403   login 403"),
    Row("GET", "/submissions/<int:submission_id>/status", "/submissions/{submission}/status",
                                                                                       "login login ok    404   403   403   login 403"),
    # --- instructor pages -------------------------------------------------------------------------------------
    Row("GET", "/instructor/", "/instructor/",                                         "login login 403   403   ok    ok    login ok"),
    Row("GET", "/instructor/problems/new", "/instructor/problems/new",                 "login login 403   403   ok    ok    login ok"),
    Row("POST", "/instructor/problems/new", "/instructor/problems/new",                "401   401   403   403   ok    422   401   ok",
        {"data": {"source": MECH_SCENE}}),
    Row("GET", "/instructor/derivations/<int:job_id>", "/instructor/derivations/{job}",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>", "/instructor/problems/mech",             "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>/review", "/instructor/problems/mech/review",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>/review", "/instructor/problems/mech-draft/review",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>/submissions.csv", "/instructor/problems/mech/submissions.csv",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("POST", "/instructor/problems/<slug>/versions/<int:number>/publish",
        "/instructor/problems/mech-draft/versions/1/publish",                          "401   401   403   403   ok    404   401   ok"),
    Row("POST", "/instructor/problems/<slug>/regrade", "/instructor/problems/mech/regrade",
                                                                                       "401   401   403   403   ok    404   401   ok"),
    Row("GET", "/instructor/problems/<slug>/regrade", "/instructor/problems/mech/regrade",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>/regrade/progress", "/instructor/problems/mech/regrade/progress",
                                                                                       "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/problems/<slug>/edit", "/instructor/problems/mech/edit",   "login login 403   403   ok    404   login ok"),
    Row("POST", "/instructor/problems/<slug>/edit", "/instructor/problems/mech/edit",  "401   401   403   403   ok    404   401   ok",
        {"data": {"source": MECH_SCENE}}),
    Row("POST", "/instructor/problems/<slug>/versions/<int:number>/unpublish",
        "/instructor/problems/mech/versions/1/unpublish",                              "401   401   403   403   ok    404   401   ok"),
    Row("POST", "/instructor/problems/<slug>/archive", "/instructor/problems/mech/archive",
                                                                                       "401   401   403   403   ok    404   401   ok"),
    Row("GET", "/instructor/problems/<slug>/diff", "/instructor/problems/mech/diff",   "login login 403   403   ok    404   login ok"),
    Row("GET", "/instructor/docs/scene-format", "/instructor/docs/scene-format",       "login login 403   403   ok    ok    login ok"),
    # --- API: courses (H10) -------------------------------------------------------------------------------------
    Row("POST", "/api/v1/courses", "/api/v1/courses",                                  "401   401   403   403   ok    ok    403   ok",
        {"json": {"code": "NEW", "title": "New course"}}),
    Row("GET", "/api/v1/courses", "/api/v1/courses",                                   "401   401   ok    ok    ok    ok    ok    ok"),
    Row("GET", "/api/v1/courses/<code>", "/api/v1/courses/MECH",                       "401   401   ok    404   ok    404   ok    ok"),
    Row("GET", "/api/v1/courses/<code>", "/api/v1/courses/NOPE",                       "401   401   404   404   404   404   404   404"),
    Row("POST", "/api/v1/courses/<code>/members", "/api/v1/courses/MECH/members",      "401   401   403   403   ok    404   403   ok",
        {"json": {"email": "cy@example.org", "name": "Cy"}}),
    Row("POST", "/api/v1/courses/<code>/assignments", "/api/v1/courses/MECH/assignments",
                                                                                       "401   401   403   403   ok    404   403   ok",
        {"json": {"id": "hw2", "title": "Homework 2", "problems": ["mech"], "opens_at": "2026-12-01T09:00:00Z",
                  "due_at": "2026-12-08T17:00:00+01:00"}}),
    Row("GET", "/api/v1/courses/<code>/assignments/<assignment>", "/api/v1/courses/MECH/assignments/hw1",
                                                                                       "401   401   ok    404   ok    404   ok    ok"),
    Row("POST", "/api/v1/courses/<code>/assignments/<assignment>/release", "/api/v1/courses/MECH/assignments/hw1/release",
                                                                                       "401   401   403   403   ok    404   403   ok"),
    Row("POST", "/api/v1/courses/<code>/assignments/<assignment>/submissions",
        "/api/v1/courses/MECH/assignments/hw1/submissions",                            "401   401   409   404   403   404   403   403",
        {"json": {"problem": "mech", "answer": "tension", "text": "m*g/3"}}),
    Row("GET", "/api/v1/courses/<code>/gradebook", "/api/v1/courses/MECH/gradebook",   "401   401   ok    404   ok    404   403   ok"),
    Row("GET", "/api/v1/courses/<code>/gradebook", "/api/v1/courses/MECH/gradebook?format=csv",
                                                                                       "401   401   ok    404   ok    404   403   ok"),
    # --- course pages (H10) -----------------------------------------------------------------------------------
    Row("GET", "/courses", "/courses",                                                 "login login ok    ok    ok    ok    login ok"),
    Row("GET", "/courses/<code>/assignments/<assignment>", "/courses/MECH/assignments/hw1",
                                                                                       "login login ok    404   ok    404   login ok"),
    # hw1 closed in 2021: the student may hand in, and is refused by the deadline (422, the text kept)
    Row("POST", "/courses/<code>/assignments/<assignment>/submit", "/courses/MECH/assignments/hw1/submit",
                                                                                       "401   401   422   404   403   404   401   403",
        {"data": {"problem": "mech", "answer-tension": "m*g/3"}}),
    Row("GET", "/instructor/courses", "/instructor/courses",                           "login login 403   403   ok    ok    login ok"),
    Row("POST", "/instructor/courses", "/instructor/courses",                          "401   401   403   403   ok    ok    401   ok",
        {"data": {"code": "NEW", "title": "New course"}}),
    Row("GET", "/instructor/courses/<code>", "/instructor/courses/MECH",               "login login 403   404   ok    404   login ok"),
    Row("POST", "/instructor/courses/<code>/members", "/instructor/courses/MECH/members",
                                                                                       "401   401   403   403   ok    404   401   ok",
        {"data": {"email": "cy@example.org", "name": "Cy", "role": "student"}}),
    Row("POST", "/instructor/courses/<code>/assignments", "/instructor/courses/MECH/assignments",
                                                                                       "401   401   403   403   ok    404   401   ok",
        {"data": {"id": "hw2", "title": "Homework 2", "problems": "mech", "time_zone": "Europe/Paris",
                  "opens_at": "2026-12-01T09:00", "due_at": "2026-12-08T17:00"}}),
    Row("GET", "/instructor/courses/<code>/assignments/<assignment>", "/instructor/courses/MECH/assignments/hw1",
                                                                                       "login login 403   404   ok    404   login ok"),
    Row("POST", "/instructor/courses/<code>/assignments/<assignment>/release",
        "/instructor/courses/MECH/assignments/hw1/release",                            "401   401   403   403   ok    404   401   ok"),
    Row("GET", "/instructor/courses/<code>/gradebook.csv", "/instructor/courses/MECH/gradebook.csv",
                                                                                       "login login 403   404   ok    404   login ok"),
    # --- LTI 1.3 (an LMS posts to login and launch; without its parameters they are 400 for everyone) -------
    Row("GET", "/lti/jwks", "/lti/jwks",                                               "ok    ok    ok    ok    ok    ok    ok    ok"),
    Row("GET", "/lti/login", "/lti/login",                                             "400   400   400   400   400   400   400   400"),
    Row("POST", "/lti/login", "/lti/login",                                            "400   400   400   400   400   400   400   400"),
    Row("POST", "/lti/launch", "/lti/launch",                                          "400   400   400   400   400   400   400   400"),
    Row("GET", "/lti/deep-link", "/lti/deep-link",                                     "login login 403   403   400   400   login 400"),
    Row("POST", "/lti/deep-link", "/lti/deep-link",                                    "401   401   403   403   400   400   401   400",
        {"data": {"problem": "mech"}}),
    Row("GET", "/lti/config", "/lti/config",                                           "login login 403   403   ok    ok    login ok"),
    Row("POST", "/lti/contexts/<int:context_id>/roster", "/lti/contexts/{lti_context}/roster",
                                                                                       "401   401   403   403   409   404   401   409"),
]


# --- the world: one database made once, copied for every cell ----------------------------------------------

@dataclass
class World:
    path: Path  # the template database file
    ids: dict[str, int]
    tokens: dict[str, str]  # principal -> bearer secret
    cookies: dict[str, str]  # principal -> signed session cookie


def _app(database_path: Path, **config):
    from grader.web import create_app

    app = create_app({"TESTING": True, "DATABASE_URL": f"sqlite:///{database_path}", "SECRET_KEY": SECRET_KEY,
                      **config})
    app.extensions["lagrade.checkers"].factory = InProcessChecker
    return app


def _close(app) -> None:
    app.extensions["lagrade.checkers"].close()
    app.extensions["lagrade.db"].dispose()


@pytest.fixture(scope="module")
def world(tmp_path_factory) -> World:
    path = tmp_path_factory.mktemp("matrix") / "world.sqlite"
    upgrade(f"sqlite:///{path}")
    database = Database(f"sqlite:///{path}")
    ids, tokens = {}, {"bad": "lg_not-a-token"}
    people = {"stu": ("student", "ada"), "out": ("student", "bob"), "ins": ("instructor", "ine"),
              "oth": ("instructor", "oth"), "lms": ("lms", None), "adm": ("admin", "adm")}
    with database.write() as session:
        users = {}
        for key, (role, login) in people.items():
            users[key] = create_user(session, role=role, name=key, email=f"{login}@example.org" if login else None,
                                     password=PASSWORD if login else None, external_id=login)
            tokens[key] = create_token(session, users[key])
        mech, other = Course(code="MECH", title="Mechanics"), Course(code="OTHER", title="Other")
        session.add_all([mech, other])
        session.flush()
        session.add_all([Enrolment(user_id=users["stu"].id, course_id=mech.id, role="student"),
                         Enrolment(user_id=users["out"].id, course_id=other.id, role="student"),
                         Enrolment(user_id=users["ins"].id, course_id=mech.id, role="instructor"),
                         Enrolment(user_id=users["oth"].id, course_id=other.id, role="instructor"),
                         Enrolment(user_id=users["lms"].id, course_id=mech.id, role="lms")])
        for slug, published in (("mech", True), ("mech-draft", False)):
            derived = dataclasses.replace(YOYO, slug=slug, title=slug, source=f'id = "{slug}"\n')
            version, _ = save_problem(session, derived, published=published)
            version.problem.course_id = mech.id
            ids[f"{slug}_version"] = version.id  # ids["mech"] is the course MECH
        session.flush()
        # MECH's homework hw1 over the problem mech, closed long ago: mech is open to practice again,
        # and a hand-in for hw1 gets past the policy to the deadline (409).
        create_assignment(session, mech, slug="hw1", title="Homework 1", problems=["mech"],
                          opens_at=datetime(2020, 1, 1, tzinfo=timezone.utc),
                          due_at=datetime(2021, 1, 1, tzinfo=timezone.utc))
        ids.update({key: user.id for key, user in users.items()}, mech=mech.id, other=other.id)
    with database.read() as session:
        mech_version = session.get(ProblemVersion, ids["mech_version"])
        ada, lms = session.get(User, ids["stu"]), session.get(User, ids["lms"])
        session.expunge_all()
    ids["submission"], _ = submit(database, user=ada, requester=lms, version=mech_version, answer="tension",
                                  text="m*g/2")
    ids["job"] = enqueue(database, requester_id=ids["ins"], source=MECH_SCENE, course_id=ids["mech"])
    with database.write() as session:  # an LMS course linked to MECH, launched without a roster service
        from grader.store.lti_models import LtiContext
        from grader.web.lti.platforms import register_platform

        platform = register_platform(session, name="LMS", issuer="https://lms.example.org", client_id="lagrade",
                                     auth_url="https://lms.example.org/auth", token_url="https://lms.example.org/token",
                                     jwks_url="https://lms.example.org/jwks", deployment_ids=["1"])
        context = LtiContext(platform_id=platform.id, context_id="mech-lms", title="Mechanics", course_id=ids["mech"])
        session.add(context)
        session.flush()
        ids["lti_context"] = context.id
    database.dispose()

    app, cookies = _app(path, RATE_LIMITS_ENABLED=False), {}  # five sign-ins in a row from one address
    for key, (_, login) in people.items():
        if login is None:
            continue
        client = app.test_client()
        token = form_token(client.get("/login").get_data(as_text=True))
        signed = client.post("/login", data={"username": f"{login}@example.org", "password": PASSWORD,
                                             "csrf_token": token})
        assert signed.status_code == 302, signed.get_data(as_text=True)
        cookies[key] = client.get_cookie("session").value
    _close(app)
    return World(path, ids, tokens, cookies)


@pytest.fixture
def cell_app(world, tmp_path):
    """A fresh copy of the world's database, and the app on it."""
    copy = tmp_path / "cell.sqlite"
    shutil.copyfile(world.path, copy)
    app = _app(copy)
    app.extensions["matrix.asked"] = asked = []

    @app.after_request
    def _record(response):  # did this request ask the access policy who the caller is?
        asked.append("_principal" in g)
        return response

    yield app
    _close(app)


def client_for(app, world: World, principal: str):
    """A test client acting as ``principal``: its session cookie (if it can sign in) and its token."""
    client = app.test_client()
    if principal in world.cookies:
        client.set_cookie("session", world.cookies[principal])
    headers = {"X-CSRF-Token": csrf(client)}
    if principal in world.tokens:
        headers["Authorization"] = f"Bearer {world.tokens[principal]}"
    return client, headers


def outcome(response) -> str:
    if response.status_code in (301, 302, 303, 307) and urlparse(response.headers["Location"]).path == "/login":
        return "login"
    return "ok" if response.status_code < 400 else str(response.status_code)


# --- the tests ---------------------------------------------------------------------------------------------

def test_every_route_has_a_row(world):
    app = _app(world.path)
    try:
        routes = {(method, rule.rule) for rule in app.url_map.iter_rules()
                  for method in rule.methods - {"HEAD", "OPTIONS"}}
    finally:
        _close(app)
    rows = {(row.method, row.rule) for row in ROWS}
    assert sorted(routes - rows) == [], "routes without a row in ROWS: add one (see the top of this file)"
    assert sorted(rows - routes) == [], "rows naming no route of the app"


# Signed in or not, these only redirect (to the sign-in page or to one's home page).
NOT_GUARDED = {("GET", "/"), ("POST", "/logout")}


def _guarded(row: Row) -> bool:
    """Whether the row's endpoint is closed to anonymous callers: then it must ask the policy."""
    return row.outcomes()["anon"] != "ok" and (row.method, row.rule) not in NOT_GUARDED


CELLS = [pytest.param(row, principal, expected, id=f"{row.method} {row.url} as {principal}")
         for row in ROWS for principal, expected in row.outcomes().items()]


@pytest.mark.parametrize("row, principal, expected", CELLS)
def test_access(world, cell_app, row, principal, expected):
    client, headers = client_for(cell_app, world, principal)
    url = row.url.format(**world.ids)
    response = client.open(url, method=row.method, headers=headers, **row.send)
    assert outcome(response) == expected, (response.status_code, response.get_data(as_text=True)[:300])
    if expected == "ok" and _guarded(row):
        assert cell_app.extensions["matrix.asked"] == [True], "let the caller through without asking grader.web.policy"
    if response.mimetype.endswith("json") and url.startswith("/api/") and response.status_code >= 400:
        assert response.mimetype == "application/problem+json"  # refusals are problem documents too


# --- what the statuses alone do not show -------------------------------------------------------------------

@pytest.mark.parametrize("principal, listed", [
    ("stu", ["mech"]), ("out", []), ("ins", ["mech", "mech-draft"]), ("oth", []), ("lms", ["mech"]),
    ("adm", ["mech", "mech-draft"]),
])
def test_the_problem_list_holds_what_the_caller_may_see(world, cell_app, principal, listed):
    client, headers = client_for(cell_app, world, principal)
    body = client.get("/api/v1/problems", headers=headers).get_json()
    assert [p["id"] for p in body["problems"]] == listed


@pytest.mark.parametrize("principal, listed", [("stu", True), ("out", False)])
def test_the_student_page_lists_what_the_student_may_see(world, cell_app, principal, listed):
    client, _ = client_for(cell_app, world, principal)
    assert ('href="/problems/mech"' in client.get("/problems").get_data(as_text=True)) is listed


@pytest.mark.parametrize("path, send", [
    ("/api/v1/problems", UPLOAD),
    ("/instructor/problems/new", {"data": {"source": MECH_SCENE}}),
])
def test_an_upload_over_another_courses_problem_id_stores_nothing(world, cell_app, path, send):
    client, headers = client_for(cell_app, world, "oth")
    database = cell_app.extensions["lagrade.db"]
    with database.read() as session:
        before = (session.scalar(select(func.count()).select_from(ProblemVersion)),
                  session.scalar(select(func.count()).select_from(DerivationJob)))
    response = client.post(path, headers=headers, **send)
    assert response.status_code in (403, 422)
    assert "another course" in response.get_data(as_text=True) or "do not teach" in response.get_data(as_text=True)
    with database.read() as session:
        after = (session.scalar(select(func.count()).select_from(ProblemVersion)),
                 session.scalar(select(func.count()).select_from(DerivationJob)))
    assert after == before


@pytest.mark.parametrize("principal, shown", [("ins", True), ("oth", False), ("stu", False)])
def test_references_are_shown_only_to_those_who_manage_the_problem(world, cell_app, principal, shown):
    client, headers = client_for(cell_app, world, principal)
    response = client.get("/api/v1/problems/mech", headers=headers)
    body = response.get_json()
    references = response.status_code == 200 and any("reference" in a for a in body["answers"])
    assert references is shown
