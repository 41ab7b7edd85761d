"""Courses and rosters: creating a course, enrolling people (by e-mail or external id, once each),
and reading a CSV roster that either imports whole or says which lines are wrong."""

from __future__ import annotations

import pytest

from grader.store.courses import CourseError, Member, add_member, create_course, parse_roster, roster
from grader.store.models import User


@pytest.mark.parametrize("text, members", [
    ("email,name,external_id\nada@example.org,Ada,s1\n", [Member("Ada", "ada@example.org", "s1")]),
    ("Name,EMAIL\nBob,bob@example.org\n\n", [Member("Bob", "bob@example.org")]),  # any order and case; blank lines
    ("external_id,name,role\nt1,Tia,TA\n", [Member("Tia", None, "t1", "ta")]),
    ("\ufeffemail,name\ncy@example.org,\"Young, Cy\"\n", [Member("Young, Cy", "cy@example.org")]),  # Excel's BOM
])
def test_a_roster_reads_each_person(text, members):
    assert parse_roster(text) == members


@pytest.mark.parametrize("text, words", [
    ("", "first line names its columns"),
    ("email\nada@example.org\n", "first line names its columns"),
    ("email,name\nada@example.org,Ada,extra\n", "line 2: more fields"),
    ("email,name\nnot an address,Ada\n", "line 2: 'not an address' is not an e-mail address"),
    ("email,name,role\nada@example.org,Ada,dean\n", "line 2: the role is one of"),
    ("email,name\nada@example.org,Ada\n,Nobody\n", "line 3: no email and no external_id"),
])
def test_a_bad_roster_names_its_bad_lines(text, words):
    with pytest.raises(CourseError, match=words):
        parse_roster(text)


def test_members_are_enrolled_once_and_found_by_email_or_external_id(database):
    with database.write() as session:
        teacher = User(role="instructor", name="Ine", email="ine@example.org")
        session.add(teacher)
        session.flush()
        course = create_course(session, code="MECH", title="Mechanics", instructor=teacher)
        _, created = add_member(session, course, Member("Ada", "ada@example.org", "s1"))
        assert created
        _, created = add_member(session, course, Member("Ada again", None, "s1", "ta"))  # the same person
        assert not created
        assert [(e.user.name, e.role) for e in roster(session, course)] == [("Ine", "instructor"), ("Ada", "ta")]
        with pytest.raises(CourseError, match="already a course"):
            create_course(session, code="MECH", title="Again")


@pytest.mark.parametrize("member, words", [
    (Member("Nobody"), "e-mail address or an external id"),
    (Member("Ada", "ada@example.org", role="dean"), "role is one of"),
    (Member("Mallory", None, "lti:" + "0" * 64), "made by LTI launches"),  # would take a person's LTI account
])
def test_a_member_without_an_address_or_with_an_unknown_role_is_refused(database, member, words):
    with database.write() as session:
        course = create_course(session, code="MECH", title="Mechanics")
        with pytest.raises(CourseError, match=words):
            add_member(session, course, member)


BAD_CODES = ["Ω²ǅ", "-x", ".MECH", "", "MECH 2026", "MECH/2026", "MECH\n", "x" * 65]


@pytest.mark.parametrize("code", BAD_CODES)
def test_a_course_code_is_ascii_letters_digits_and_inner_punctuation(database, code):
    with database.write() as session, pytest.raises(CourseError, match="is not a course code"):
        create_course(session, code=code, title="Mechanics")


@pytest.mark.parametrize("taken, again", [("OTHER", "other"), ("mech-1", "MECH-1"), ("Phys", "pHYS")])
def test_codes_that_differ_only_in_case_are_one_code(database, taken, again):
    with database.write() as session:
        create_course(session, code=taken, title="First")
        with pytest.raises(CourseError, match=f"already a course {taken!r}"):
            create_course(session, code=again, title="Second")
