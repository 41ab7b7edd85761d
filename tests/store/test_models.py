"""What the schema guarantees: one verdict per grading round, idempotency keys, versions, tokens."""

import dataclasses

import pytest
from sqlalchemy import select
from sqlalchemy.exc import IntegrityError

from grader.store.models import ApiToken, Submission, Verdict
from grader.store.problems import latest_version, problem_by_slug, save_problem
from grader.store.users import (
    authenticate,
    create_token,
    create_user,
    hash_secret,
    user_for_token,
)


@pytest.fixture
def stored(database, yoyo):
    """A student and a queued submission to the yo-yo, as ids."""
    with database.write() as session:
        version, _ = save_problem(session, yoyo)
        student = create_user(session, role="student", name="Ada")
        submission = Submission(user=student, requester=student, problem_version=version, grading_version=version,
                                answer_name="tension", text="m*g/3", idempotency_key="k1")
        session.add(submission)
        session.flush()
        return {"student": student.id, "version": version.id, "submission": submission.id}


def test_a_grading_round_has_at_most_one_verdict(database, stored):
    def verdict(outcome: str) -> Verdict:
        return Verdict(submission_id=stored["submission"], grading_round=1, problem_version_id=stored["version"],
                       verdict=outcome, score=1.0)

    with database.write() as session:
        session.add(verdict("correct"))
    with pytest.raises(IntegrityError):
        with database.write() as session:
            session.add(verdict("incorrect"))
    with database.read() as session:
        submission = session.get(Submission, stored["submission"])
        assert [v.verdict for v in submission.verdicts] == ["correct"]


def test_the_verdict_in_effect_is_the_current_rounds(database, stored):
    with database.write() as session:
        for round_, outcome in ((1, "incorrect"), (2, "correct")):
            session.add(Verdict(submission_id=stored["submission"], grading_round=round_,
                                problem_version_id=stored["version"], verdict=outcome, score=0.0))
    with database.write() as session:
        submission = session.get(Submission, stored["submission"])
        assert submission.verdict.verdict == "incorrect"
        submission.grading_round = 2
        assert submission.verdict.verdict == "correct"


def test_an_idempotency_key_is_unique_per_requester(database, stored, yoyo):
    with database.write() as session:
        other = create_user(session, role="student", name="Bob")
        version = latest_version(session, problem_by_slug(session, "yoyo"))
        # The same key from another requester is a different request.
        session.add(Submission(user=other, requester=other, problem_version=version, grading_version=version,
                               answer_name="tension", text="x", idempotency_key="k1"))
    with pytest.raises(IntegrityError):
        with database.write() as session:
            version = latest_version(session, problem_by_slug(session, "yoyo"))
            student = session.get(Submission, stored["submission"]).user
            session.add(Submission(user=student, requester=student, problem_version=version,
                                   grading_version=version, answer_name="tension", text="y", idempotency_key="k1"))


@pytest.mark.parametrize("change, new_version", [(None, False), ("# a comment\n", True)])
def test_a_changed_source_makes_a_new_version(database, yoyo, change, new_version):
    with database.write() as session:
        first, created = save_problem(session, yoyo)
        assert created and first.number == 1
    edited = dataclasses.replace(yoyo, source=yoyo.source + change) if change else yoyo
    with database.write() as session:
        version, created = save_problem(session, edited)
        assert created is new_version
        assert version.number == (2 if new_version else 1)
        assert [v.number for v in problem_by_slug(session, "yoyo").versions] == ([1, 2] if new_version else [1])


def test_students_see_only_published_versions(database, yoyo):
    with database.write() as session:
        save_problem(session, yoyo)
        save_problem(session, dataclasses.replace(yoyo, source=yoyo.source + "# draft\n"), published=False)
        problem = problem_by_slug(session, "yoyo")
        assert latest_version(session, problem).number == 2
        assert latest_version(session, problem, published_only=True).number == 1


def test_tokens_are_stored_as_hashes_and_resolve_to_their_user(database):
    with database.write() as session:
        user = create_user(session, role="lms", name="Moodle")
        secret = create_token(session, user)
    with database.read() as session:
        stored = session.scalars(select(ApiToken.secret_sha256)).all()
        assert stored == [hash_secret(secret)] and secret not in stored
        found, token = user_for_token(session, secret)
        assert (found.name, token.role) == ("Moodle", "lms")
        assert user_for_token(session, secret + "x") is None


def test_a_revoked_token_no_longer_resolves(database):
    from grader.store.models import utcnow

    with database.write() as session:
        secret = create_token(session, create_user(session, role="student", name="Ada"))
    with database.write() as session:
        session.scalar(select(ApiToken)).revoked_at = utcnow()
    with database.read() as session:
        assert user_for_token(session, secret) is None


@pytest.mark.parametrize("email, password, ok", [
    ("ada@example.org", "correct horse", True),
    ("ada@example.org", "wrong", False),
    ("nobody@example.org", "correct horse", False),
])
def test_sign_in_checks_the_password_hash(database, email, password, ok):
    with database.write() as session:
        user = create_user(session, role="student", name="Ada", email="ada@example.org", password="correct horse")
        assert user.password_hash and "correct horse" not in user.password_hash
    with database.read() as session:
        assert (authenticate(session, email, password) is not None) is ok


@pytest.mark.parametrize("external_id", ["lti:0123abcd", "LTI:0123abcd", " lti:x"])
def test_an_id_only_an_lti_launch_gives_is_refused_anywhere_else(database, external_id):
    # anyone can compute a person's LTI id: made first by a token or a roster, it took their account
    with database.write() as session, pytest.raises(ValueError, match="LTI launches only"):
        create_user(session, role="student", name="Mallory", external_id=external_id)


def test_unknown_roles_are_refused(database):
    with database.write() as session, pytest.raises(ValueError, match="unknown role"):
        create_user(session, role="superuser", name="Eve")
