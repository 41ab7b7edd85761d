"""Names and Role Provisioning: fill a course's roster from its LMS course's members.

:func:`fetch_roster` reads every page of the context's membership container (following ``Link:
rel="next"``) and :func:`apply_roster` gives each active member an account (the same one their launch would give) and an
enrolment in the mapped course in their LMS role. Members no longer active are left as they are: a
student's work is never removed by a roster sync.
"""

from __future__ import annotations

from dataclasses import dataclass

from sqlalchemy.orm import Session

from grader.store.db import Database
from grader.store.lti_models import LtiContext, LtiPlatform
from grader.store.models import utcnow
from grader.web.lti.accounts import AccountTaken, course_role, enrol, lti_user
from grader.web.lti.http import PlatformUnreachable, get_page
from grader.web.lti.tokens import PlatformAccess, access_token

__all__ = ["MEMBERSHIP_SCOPE", "RosterResult", "apply_roster", "fetch_members", "fetch_roster"]

MEMBERSHIP_SCOPE = "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly"
MEMBERSHIP_TYPE = "application/vnd.ims.lti-nrps.v2.membershipcontainer+json"
MAX_PAGES = 200


@dataclass
class RosterResult:
    members: int = 0
    students: int = 0
    instructors: int = 0
    skipped: int = 0


def fetch_members(url: str, token: str) -> list[dict]:
    """Every member of the membership container at ``url``, page after page."""
    members: list[dict] = []
    for _ in range(MAX_PAGES):
        page, following = get_page(url, headers={"Authorization": f"Bearer {token}", "Accept": MEMBERSHIP_TYPE})
        found = page.get("members") if isinstance(page, dict) else None
        if isinstance(found, list):
            members.extend(m for m in found if isinstance(m, dict))
        if not following:
            return members
        url = following
    raise PlatformUnreachable(f"the roster has more than {MAX_PAGES} pages")


def fetch_roster(database: Database, context_id: int) -> list[dict]:
    """The members of LMS course ``context_id`` (our row id), from its roster service.

    Reads what it needs in a short session and calls the LMS with no transaction open.
    """
    with database.read() as session:
        context = session.get(LtiContext, context_id)
        platform = session.get(LtiPlatform, context.platform_id)
        url = context.memberships_url
        access = PlatformAccess(platform.id, platform.issuer, platform.client_id, platform.token_url)
    if not url:
        raise PlatformUnreachable("this LMS course offered no roster service at its launches")
    return fetch_members(url, access_token(database, access, {MEMBERSHIP_SCOPE}))


def apply_roster(session: Session, context_id: int, members: list[dict]) -> RosterResult:
    """Give every active member an account and an enrolment in the course in their LMS role (in ``session``)."""
    context = session.get(LtiContext, context_id)
    platform = session.get(LtiPlatform, context.platform_id)
    result = RosterResult()
    for member in members:
        sub, roles = member.get("user_id"), member.get("roles")
        if not isinstance(sub, str) or not sub or len(sub) > 255 or member.get("status", "Active") != "Active":
            result.skipped += 1
            continue
        role = course_role(roles if isinstance(roles, list) else [])
        name = member.get("name") or " ".join(str(member.get(k, "")) for k in ("given_name", "family_name")).strip()
        try:
            user = lti_user(session, platform, sub, name if isinstance(name, str) else "", role)
        except AccountTaken:  # its id is held by an account that is not theirs: never enrolled as them
            result.skipped += 1
            continue
        enrol(session, user, context.course_id, role)
        result.members += 1
        if role == "instructor":
            result.instructors += 1
        else:
            result.students += 1
    context.roster_synced_at = utcnow()
    session.flush()
    return result
