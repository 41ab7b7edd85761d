"""The access policy's course actions: who may see a course, grade it (instructors and TAs) and
manage it (instructors only: TAs grade but never publish), and the same for its assignments."""

from __future__ import annotations

import pytest

from grader.store.models import Assignment, Course
from grader.web.policy import Action, Principal, allowed

MECH = Course(id=1, code="MECH", title="Mechanics")
HW1 = Assignment(id=5, course_id=1, slug="hw1")
WHO = {
    "student": Principal(user_id=1, role="student", enrolled=frozenset({1})),
    "ta": Principal(user_id=2, role="student", enrolled=frozenset({1}), assisted=frozenset({1})),
    "instructor": Principal(user_id=3, role="instructor", enrolled=frozenset({1}), taught=frozenset({1})),
    "other instructor": Principal(user_id=4, role="instructor", enrolled=frozenset({2}), taught=frozenset({2})),
    "outsider": Principal(user_id=5, role="student", enrolled=frozenset({2})),
    "lms": Principal(user_id=6, role="lms", enrolled=frozenset({1})),
    "admin": Principal(user_id=7, role="admin"),
    "anonymous": Principal(),
}
#            view   grade  manage
EXPECTED = {
    "student": (True, False, False),
    "ta": (True, True, False),
    "instructor": (True, True, True),
    "other instructor": (False, False, False),
    "outsider": (False, False, False),
    "lms": (True, False, False),
    "admin": (True, True, True),
    "anonymous": (False, False, False),
}


@pytest.mark.parametrize("resource", [MECH, HW1], ids=["course", "assignment"])
@pytest.mark.parametrize("who", list(WHO))
def test_course_actions(who, resource):
    actions = (Action.VIEW_COURSE, Action.GRADE_COURSE, Action.MANAGE_COURSE)
    assert tuple(allowed(WHO[who], a, resource) for a in actions) == EXPECTED[who]


@pytest.mark.parametrize("who, may", [("instructor", True), ("other instructor", True), ("ta", False),
                                      ("student", False), ("lms", False), ("anonymous", False)])
def test_creating_a_course_is_for_instructors(who, may):
    assert allowed(WHO[who], Action.CREATE_COURSE) is may


def test_course_actions_name_no_problem():
    from grader.store.models import Problem

    assert not allowed(WHO["instructor"], Action.MANAGE_COURSE, Problem(slug="x", course_id=1, versions=[]))
