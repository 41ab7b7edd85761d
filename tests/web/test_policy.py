"""The access policy as a table: for each resource and action, who may (Y) and who may not (N).

Columns are the principals of ``PRINCIPALS``, in order. Course 1 is MECH, course 2 OTHER.
"""

from __future__ import annotations

import pytest
from werkzeug.exceptions import Forbidden, NotFound

from grader.store.models import DerivationJob, Problem, ProblemVersion, Submission
from grader.web.errors import ApiProblem
from grader.web.policy import (Action, Principal, allowed, find_version, managed_courses, may_update, require,
                               visible_versions)
from tests.web.conftest_pages import accounts, problems  # noqa: F401  (fixtures)

MECH, OTHER = 1, 2
PRINCIPALS = {
    "anon": Principal(),
    "stu_in": Principal(1, "student", enrolled=frozenset({MECH})),
    "stu_out": Principal(2, "student", enrolled=frozenset({OTHER})),
    "ins_in": Principal(3, "instructor", enrolled=frozenset({MECH}), taught=frozenset({MECH})),
    "ins_oth": Principal(4, "instructor", enrolled=frozenset({OTHER}), taught=frozenset({OTHER})),
    # An instructor who takes MECH as a student: sees its published problems, manages none of them.
    "ins_taking": Principal(5, "instructor", enrolled=frozenset({MECH})),
    "lms_in": Principal(6, "lms", enrolled=frozenset({MECH})),  # an LMS linked to MECH
    "lms_out": Principal(7, "lms"),
    "adm": Principal(8, "admin"),
}


def _version(course: int | None, published: bool) -> ProblemVersion:
    return ProblemVersion(number=1, published=published, problem=Problem(slug="p", course_id=course))


RESOURCES = {
    "mech": lambda: _version(MECH, True),
    "mech_draft": lambda: _version(MECH, False),
    "open": lambda: _version(None, True),  # a published problem in no course
    "open_draft": lambda: _version(None, False),
    # Ada's (user 1) attempt at MECH's problem, sent for her by the LMS linked to MECH (user 6).
    "submission": lambda: Submission(user_id=1, requester_id=6, problem_version=_version(MECH, True)),
    # A scene uploaded by Ine (user 3) for MECH, still being derived.
    "job": lambda: DerivationJob(requester_id=3, course_id=MECH),
    "nothing": lambda: None,
}

TABLE = [
    #  resource      action                          anon stu_in stu_out ins_in ins_oth ins_taking lms_in lms_out adm
    ("mech",         Action.SEE,                     "N    Y      N       Y      N       Y          Y      N       Y"),
    ("mech",         Action.SUBMIT,                  "N    Y      N       Y      N       Y          Y      N       Y"),
    ("mech",         Action.SUBMIT_FOR_OTHERS,       "N    N      N       Y      N       N          Y      N       Y"),
    ("mech",         Action.MANAGE,                  "N    N      N       Y      N       N          N      N       Y"),
    ("mech",         Action.READ_GRADES,             "N    N      N       Y      N       N          Y      N       Y"),
    ("mech",         Action.REGRADE,                 "N    N      N       Y      N       N          N      N       Y"),
    ("mech",         Action.EXPORT,                  "N    N      N       Y      N       N          N      N       Y"),
    ("mech_draft",   Action.SEE,                     "N    N      N       Y      N       N          N      N       Y"),
    ("mech_draft",   Action.SUBMIT,                  "N    N      N       Y      N       N          N      N       Y"),
    ("mech_draft",   Action.SUBMIT_FOR_OTHERS,       "N    N      N       Y      N       N          N      N       Y"),
    ("mech_draft",   Action.MANAGE,                  "N    N      N       Y      N       N          N      N       Y"),
    ("mech_draft",   Action.READ_GRADES,             "N    N      N       Y      N       N          N      N       Y"),
    ("open",         Action.SEE,                     "N    Y      Y       Y      Y       Y          Y      Y       Y"),
    ("open",         Action.SUBMIT,                  "N    Y      Y       Y      Y       Y          Y      Y       Y"),
    ("open",         Action.SUBMIT_FOR_OTHERS,       "N    N      N       Y      Y       Y          Y      Y       Y"),
    ("open",         Action.MANAGE,                  "N    N      N       Y      Y       Y          N      N       Y"),
    # No LMS reads grades of a problem in no course: every LMS's students may answer it.
    ("open",         Action.READ_GRADES,             "N    N      N       Y      Y       Y          N      N       Y"),
    ("open",         Action.EXPORT,                  "N    N      N       Y      Y       Y          N      N       Y"),
    ("open_draft",   Action.SEE,                     "N    N      N       Y      Y       Y          N      N       Y"),
    ("open_draft",   Action.SUBMIT,                  "N    N      N       Y      Y       Y          N      N       Y"),
    ("open_draft",   Action.READ_GRADES,             "N    N      N       Y      Y       Y          N      N       Y"),
    ("submission",   Action.VIEW_SUBMISSION,         "N    Y      N       Y      N       N          Y      N       Y"),
    ("mech",         Action.VIEW_SUBMISSION,         "N    N      N       N      N       N          N      N       Y"),
    ("job",          Action.VIEW_DERIVATION,         "N    N      N       Y      N       N          N      N       Y"),
    ("nothing",      Action.CREATE,                  "N    N      N       Y      Y       Y          N      N       Y"),
    ("nothing",      Action.CHECK,                   "N    Y      Y       Y      Y       Y          Y      Y       Y"),
    ("nothing",      Action.SEE,                     "N    N      N       N      N       N          N      N       N"),
]

CASES = [pytest.param(resource, action, principal, cell == "Y", id=f"{principal} {action.value} {resource}")
         for resource, action, row in TABLE
         for principal, cell in zip(PRINCIPALS, row.split(), strict=True)]


@pytest.mark.parametrize("resource, action, principal, expected", CASES)
def test_allowed(resource, action, principal, expected):
    assert allowed(PRINCIPALS[principal], action, RESOURCES[resource]()) is expected


@pytest.mark.parametrize("action", [Action.SEE, Action.MANAGE, Action.READ_GRADES, Action.SUBMIT_FOR_OTHERS])
def test_a_problem_counts_as_published_if_any_version_is(action):
    problem = Problem(slug="p", course_id=MECH)
    ProblemVersion(number=1, published=True, problem=problem)
    ProblemVersion(number=2, published=False, problem=problem)
    assert allowed(PRINCIPALS["lms_in"], action, problem) is (action in (Action.SEE, Action.READ_GRADES,
                                                                         Action.SUBMIT_FOR_OTHERS))


# Whoever may do the first may do the second: so a refusal of the second can never reveal more
# (404) than the first allows, and every grader of a problem can also see it.
IMPLICATIONS = [(Action.SUBMIT, Action.SEE), (Action.SUBMIT_FOR_OTHERS, Action.SUBMIT),
                (Action.MANAGE, Action.SUBMIT_FOR_OTHERS), (Action.READ_GRADES, Action.SEE),
                (Action.REGRADE, Action.READ_GRADES), (Action.EXPORT, Action.READ_GRADES), (Action.MANAGE, Action.EXPORT)]


@pytest.mark.parametrize("stronger, weaker", IMPLICATIONS, ids=lambda a: a.value)
@pytest.mark.parametrize("resource", ["mech", "mech_draft", "open", "open_draft"])
def test_a_stronger_permission_implies_the_weaker(stronger, weaker, resource):
    for name, principal in PRINCIPALS.items():
        if allowed(principal, stronger, RESOURCES[resource]()):
            assert allowed(principal, weaker, RESOURCES[resource]()), name


def test_actions_are_named_by_their_value():
    assert allowed(PRINCIPALS["stu_in"], "see", RESOURCES["mech"]()) is True
    with pytest.raises(ValueError):
        allowed(PRINCIPALS["stu_in"], "peek", RESOURCES["mech"]())


# --- refusals: 404 where the caller may not know the thing exists, 403 where they may -------------------

@pytest.mark.parametrize("path, errors", [
    ("/api/v1/problems/p", {404: ApiProblem, 403: ApiProblem}),
    ("/problems/p", {404: NotFound, 403: Forbidden}),
])
@pytest.mark.parametrize("principal, action, resource, status", [
    ("stu_out", Action.SEE, "mech", 404),  # not in her course: not even there
    ("stu_in", Action.SEE, "mech_draft", 404),  # a draft: not even there
    ("stu_in", Action.READ_GRADES, "mech", 403),  # she sees it, but grades are not hers to read
    ("lms_in", Action.EXPORT, "mech", 403),
    ("ins_oth", Action.REGRADE, "mech", 404),
    ("stu_out", Action.VIEW_SUBMISSION, "submission", 404),
])
def test_require_refuses_with_404_or_403_the_same_way_on_api_and_pages(app, path, errors, principal, action,
                                                                        resource, status):
    with app.test_request_context(path), pytest.raises(errors[status]) as refused:
        require(PRINCIPALS[principal], action, RESOURCES[resource]())
    assert getattr(refused.value, "status", None) == status or getattr(refused.value, "code", None) == status


def test_require_lets_through_what_is_allowed(app):
    with app.test_request_context("/api/v1/problems/p"):
        assert require(PRINCIPALS["ins_in"], Action.REGRADE, RESOURCES["mech"]()) is None


# --- principals and lists from the database ---------------------------------------------------------------

def test_a_principal_knows_the_courses_its_user_takes_and_teaches(app, accounts):
    from grader.store.models import User

    with app.extensions["lagrade.db"].read() as session:
        ine = Principal.of(session, session.get(User, accounts["ine"].id))
        ada = Principal.of(session, session.get(User, accounts["ada"].id))
        assert (ine.role, ine.taught, ine.enrolled) == ("instructor", {accounts["course"]}, {accounts["course"]})
        assert (ada.role, ada.taught, ada.enrolled) == ("student", frozenset(), {accounts["course"]})
        assert [c.code for c in managed_courses(session, ine)] == ["MECH"]
        assert [c.code for c in managed_courses(session, Principal(99, "admin"))] == ["MECH", "OTHER"]


@pytest.mark.parametrize("who, slugs", [
    ("ada", ["mech", "yoyo"]),  # MECH's published problem and the open yo-yo
    ("ine", ["draft", "mech", "yoyo"]),  # the draft in no course is hers to manage, so she sees it
    ("oth", ["draft", "other", "yoyo"]),
])
def test_visible_versions_are_what_find_version_finds(app, accounts, problems, who, slugs):
    from grader.store.models import User

    with app.extensions["lagrade.db"].read() as session:
        me = Principal.of(session, session.get(User, accounts[who].id))
        visible = visible_versions(session, me)
        assert sorted(v.problem.slug for v in visible) == slugs
        with app.test_request_context("/api/v1/problems"):
            assert all(find_version(session, me, v.problem.slug).id == v.id for v in visible)


@pytest.mark.parametrize("who, slug, expected", [("ine", "mech", True), ("oth", "mech", False),
                                                 ("oth", "other", True), ("ada", "yoyo", False)])
def test_may_update_is_the_manage_rule_for_derivation_workers(app, accounts, problems, who, slug, expected):
    from grader.store.models import User
    from grader.store.problems import problem_by_slug

    with app.extensions["lagrade.db"].read() as session:
        assert may_update(session, session.get(User, accounts[who].id), problem_by_slug(session, slug)) is expected
