"""LMS people as lagrade users: one user per (platform, ``sub``), their role, and their enrolments.

Used by both launches and roster syncs (NRPS), so a person gets the same account either way.
LMS users have no password (they come in through their LMS) and no stored email: an email is
unique here and may belong to a local account already.
"""

from __future__ import annotations

import hashlib
from typing import Iterable

from sqlalchemy import select
from sqlalchemy.orm import Session

from grader.store.lti_models import LtiAccount, LtiPlatform
from grader.store.models import Enrolment, User
from grader.store.users import create_user

__all__ = ["AccountTaken", "course_role", "external_id", "lti_user", "enrol"]


class AccountTaken(ValueError):
    """The id an LTI person gets here is held by an account that is not theirs."""

# LIS roles (full URIs or short names) that make someone a teacher of the course here. Teaching
# assistants and content developers prepare and grade problems, so they count as instructors.
TEACHING = {"Instructor", "ContentDeveloper", "TeachingAssistant", "Administrator"}


def course_role(roles: Iterable[str]) -> str:
    """``"instructor"`` for a teaching role, else ``"student"``.

    >>> course_role(["http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"])
    'student'
    >>> course_role(["http://purl.imsglobal.org/vocab/lis/v2/membership/Instructor#TeachingAssistant"])
    'instructor'
    >>> course_role(["Instructor"])
    'instructor'
    """
    for role in roles:
        if not isinstance(role, str):
            continue
        name = role.rsplit("#", 1)[-1].rsplit("/", 1)[-1]
        if name in TEACHING and "institution" not in role:  # an institution's admin is not this course's
            return "instructor"
    return "student"


def external_id(issuer: str, sub: str) -> str:
    """The ``users.external_id`` of an LMS person: the issuer and sub, hashed to a bounded length.

    >>> external_id("https://lms.example.org", "42")[:4]
    'lti:'
    """
    return "lti:" + hashlib.sha256(f"{issuer}\n{sub}".encode()).hexdigest()


def lti_user(session: Session, platform: LtiPlatform, sub: str, name: str, role: str) -> User:
    """The user of ``sub`` on ``platform``, made on first sight; a teacher's account becomes an
    instructor's (never the other way: a teacher may take another course as a learner)."""
    account = session.scalar(select(LtiAccount).where(LtiAccount.platform_id == platform.id, LtiAccount.sub == sub))
    if account is None:
        taken = session.scalar(select(User).where(User.external_id == external_id(platform.issuer, sub)))
        if taken is not None:
            # made outside LTI before such ids were reserved: never handed to whoever launches
            raise AccountTaken("This LMS account's id on lagrade is held by another account. Ask the "
                               "administrator of lagrade to remove or rename it, then launch again.")
        user = create_user(session, role=role, name=(name or "LMS user")[:200],
                           external_id=external_id(platform.issuer, sub), lti=True)
        session.add(LtiAccount(platform_id=platform.id, sub=sub, user_id=user.id))
        session.flush()
        return user
    user = account.user
    if name:
        user.name = name[:200]
    if role == "instructor" and user.role == "student":
        user.role = "instructor"
    return user


def enrol(session: Session, user: User, course_id: int, role: str) -> None:
    """Enrol ``user`` in ``course_id`` as ``role``, or change their role there to it."""
    enrolment = session.scalar(select(Enrolment).where(Enrolment.user_id == user.id, Enrolment.course_id == course_id))
    if enrolment is None:
        session.add(Enrolment(user_id=user.id, course_id=course_id, role=role))
    else:
        enrolment.role = role
    session.flush()
