"""How many failed sign-ins the server accepts before it asks a browser to wait.

Two token buckets, both counting **failed** attempts only (a class signing in at the start of a lecture
from one campus address costs nothing):

- ``login``: per (account, address), strict (``RATE_LIMITS["login"]``): guessing one student's
  password from one place is slow. An attacker behind the campus NAT who guesses at Bob's password
  empties only the (bob, NAT) bucket; Ada, behind the same NAT, still signs in.
- ``login_address``: per address, looser (``RATE_LIMITS["login_address"]``): one address trying many
  accounts (password spraying) is slowed down too, without a single typo locking out a campus.

A refusal looks the same whichever bucket is empty, and the password is not checked while refused,
so a refused attempt tells nothing about the password either.
"""

from __future__ import annotations

from grader.web.errors import ApiProblem
from grader.web.security import limiter

__all__ = ["account_key", "record_failed_sign_in", "refuse_if_throttled"]


def account_key(username: str) -> str:
    """The bucket name of a typed account: case and surrounding space do not make a new bucket.

    >>> account_key("  Ada@Example.org ")
    'ada@example.org'
    """
    return username.strip().casefold()


def refuse_if_throttled(username: str, address: str | None) -> None:
    """Raise the 429 problem if this account from this address, or this address, failed too often."""
    try:
        limiter.check("login_address", address)
        limiter.check("login", (account_key(username), address))
    except ApiProblem as problem:  # one wording for both buckets
        wait = problem.headers.get("Retry-After", "60")
        raise ApiProblem(429, f"Too many failed sign-ins from here. Try again in {wait} s.", kind="rate-limited",
                         headers={"Retry-After": wait}) from None


def record_failed_sign_in(username: str, address: str | None) -> None:
    """Count one failed attempt in both buckets (a bucket already empty stays empty; no error here)."""
    for action, key in (("login", (account_key(username), address)), ("login_address", address)):
        try:
            limiter.hit(action, key)
        except ApiProblem:  # already empty: the refusal comes with the next attempt
            pass
