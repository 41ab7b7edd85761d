"""Users, passwords and API tokens.

Passwords are hashed with werkzeug.security (salted, slow). API tokens are random secrets shown
once; the database keeps only their sha256, so a leaked database gives no usable token.
"""

from __future__ import annotations

import functools
import hashlib
import secrets

from sqlalchemy import select
from sqlalchemy.orm import Session
from werkzeug.security import check_password_hash, generate_password_hash

from grader.store.models import ROLES, ApiToken, User, utcnow

__all__ = [
    "MAX_PASSWORD_LENGTH",
    "MIN_PASSWORD_LENGTH",
    "TOKEN_PREFIX",
    "authenticate",
    "create_token",
    "create_user",
    "hash_secret",
    "new_password_problem",
    "set_password",
    "LTI_PREFIX",
    "reserved_external_id",
    "user_for_token",
]

TOKEN_PREFIX = "lg_"
# External ids of people who come in through LTI (`grader.web.lti.accounts.external_id`): made by
# their launch only. Anyone can compute one from an issuer and a sub, so an id given by an LMS
# token, a roster or the command line may not start so (it would take the person's account first).
LTI_PREFIX = "lti:"
MIN_PASSWORD_LENGTH = 10
MAX_PASSWORD_LENGTH = 1024  # what the sign-in form reads of a password


def hash_secret(secret: str) -> str:
    return hashlib.sha256(secret.encode()).hexdigest()


def reserved_external_id(external_id: str | None) -> bool:
    """Whether ``external_id`` is one only an LTI launch may give (see `LTI_PREFIX`).

    >>> reserved_external_id("lti:0f3a"), reserved_external_id("s1234"), reserved_external_id(None)
    (True, False, False)
    """
    return isinstance(external_id, str) and external_id.strip().lower().startswith(LTI_PREFIX)


def create_user(session: Session, *, role: str, name: str, email: str | None = None,
                password: str | None = None, external_id: str | None = None, lti: bool = False) -> User:
    """Add a user (flushed, not committed); ``role`` is one of student, instructor, admin, lms.
    ``lti``: made by an LTI launch or roster sync, the only ones that may use `LTI_PREFIX`."""
    if role not in ROLES:
        raise ValueError(f"unknown role {role!r}; expected one of {', '.join(ROLES)}")
    if reserved_external_id(external_id) and not lti:
        raise ValueError(f"external ids starting with {LTI_PREFIX!r} are made by LTI launches only")
    user = User(role=role, name=name, email=email, external_id=external_id)
    if password is not None:
        set_password(user, password)
    session.add(user)
    session.flush()
    return user


def new_password_problem(password: str) -> str | None:
    """Why ``password`` may not become an account's password (one sentence), or None if it may.

    The one rule for a new password, on the account page and in ``grader db reset-password``.

    >>> new_password_problem("short"), new_password_problem("long enough, surely")
    ('A password needs at least 10 characters.', None)
    """
    if len(password) < MIN_PASSWORD_LENGTH:
        return f"A password needs at least {MIN_PASSWORD_LENGTH} characters."
    if len(password) > MAX_PASSWORD_LENGTH:
        return f"A password may have at most {MAX_PASSWORD_LENGTH} characters."
    return None


def set_password(user: User, password: str) -> None:
    user.password_hash = generate_password_hash(password)


def authenticate(session: Session, email: str, password: str) -> User | None:
    """The user with this email and password, or None (same answer for unknown email and wrong password).

    An unknown email (or an account without a password) still checks the password, against a
    stand-in hash of the same kind and cost, so the answer takes as long as for a wrong password
    and its timing tells nothing about which accounts exist.
    """
    user = session.scalar(select(User).where(User.email == email))
    if user is None or user.password_hash is None:
        check_password_hash(_stand_in_hash(), password)
        return None
    return user if check_password_hash(user.password_hash, password) else None


@functools.lru_cache(maxsize=1)
def _stand_in_hash() -> str:
    """A hash made like :func:`set_password` makes one, of a password nobody knows."""
    return generate_password_hash(secrets.token_urlsafe(32))


def create_token(session: Session, user: User, name: str | None = None) -> str:
    """A new bearer token for ``user`` with the user's role; returns the secret (shown only now)."""
    secret = TOKEN_PREFIX + secrets.token_urlsafe(32)
    session.add(ApiToken(user=user, role=user.role, name=name or user.name, secret_sha256=hash_secret(secret)))
    session.flush()
    return secret


def user_for_token(session: Session, secret: str) -> tuple[User, ApiToken] | None:
    """The user and token for a bearer secret, or None if unknown or revoked."""
    token = session.scalar(select(ApiToken).where(ApiToken.secret_sha256 == hash_secret(secret)))
    if token is None or token.revoked_at is not None:
        return None
    return token.user, token
