"""Assignment and Grade Services: send a score to a link's line item (making the line item if needed).

:func:`deliverer` gives the ``deliver`` function the score outbox (``grader.jobs.lti_passback``)
calls; it raises on any failure, and the outbox retries.
"""

from __future__ import annotations

from datetime import timezone
from urllib.parse import urlencode, urlsplit, urlunsplit

from grader.jobs.lti_passback import ScoreToSend
from grader.store.db import Database
from grader.web.lti.http import PlatformUnreachable, get_json, post
from grader.web.lti.tokens import PlatformAccess, access_token, forget_tokens

__all__ = ["LINEITEM_SCOPE", "SCORE_SCOPE", "deliverer", "score_body", "scores_url"]

SCORE_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
LINEITEM_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/lineitem"
SCORE_TYPE = "application/vnd.ims.lis.v1.score+json"
LINEITEM_TYPE = "application/vnd.ims.lis.v2.lineitem+json"
LINEITEMS_TYPE = "application/vnd.ims.lis.v2.lineitemcontainer+json"


def scores_url(lineitem_url: str) -> str:
    """The scores endpoint of a line item: ``/scores`` after its path, before its query.

    >>> scores_url("https://lms.example.org/lineitems/7?type=x")
    'https://lms.example.org/lineitems/7/scores?type=x'
    """
    parts = urlsplit(lineitem_url)
    return urlunsplit(parts._replace(path=parts.path.rstrip("/") + "/scores"))


def score_body(score: ScoreToSend) -> dict:
    """The AGS score document: the student's total on the problem, final, stamped with when it was computed."""
    stamp = score.scored_at.replace(tzinfo=timezone.utc).isoformat(timespec="milliseconds").replace("+00:00", "Z")
    return {"userId": score.user_sub, "scoreGiven": score.score_given, "scoreMaximum": score.score_maximum,
            "activityProgress": "Completed", "gradingProgress": "FullyGraded", "timestamp": stamp}


def _line_item(score: ScoreToSend, headers: dict[str, str]) -> str:
    """The line item of the score's link, found by its resource link id, or made."""
    parts = urlsplit(score.lineitems_url)
    query = "&".join(q for q in (parts.query, urlencode({"resource_link_id": score.resource_link_id})) if q)
    found = get_json(urlunsplit(parts._replace(query=query)), headers={**headers, "Accept": LINEITEMS_TYPE})
    for item in found if isinstance(found, list) else []:
        if isinstance(item, dict) and item.get("resourceLinkId") == score.resource_link_id and isinstance(item.get("id"), str):
            return item["id"]
    made = post(score.lineitems_url, headers={**headers, "Content-Type": LINEITEM_TYPE, "Accept": LINEITEM_TYPE},
                json_body={"scoreMaximum": score.score_maximum, "label": score.link_title or score.problem_slug or "lagrade",
                           "resourceLinkId": score.resource_link_id, "resourceId": score.problem_slug or "",
                           "tag": "lagrade"})
    if not isinstance(made, dict) or not isinstance(made.get("id"), str):
        raise PlatformUnreachable("the platform made a line item but did not say its URL")
    return made["id"]


def deliverer(database: Database):
    """``deliver(score)`` for the outbox: an access token, the line item, then ``POST .../scores``."""

    def deliver(score: ScoreToSend) -> str | None:
        if not score.user_sub:
            raise PlatformUnreachable("the student has no account on this platform")
        platform = PlatformAccess(score.platform_id, score.issuer, score.client_id, score.token_url)
        scopes = {SCORE_SCOPE} | ({LINEITEM_SCOPE} if not score.lineitem_url else set())
        headers = {"Authorization": f"Bearer {access_token(database, platform, scopes)}"}
        try:
            made = None
            lineitem = score.lineitem_url
            if not lineitem:
                lineitem = made = _line_item(score, headers)
            post(scores_url(lineitem), headers={**headers, "Content-Type": SCORE_TYPE}, json_body=score_body(score))
        except PlatformUnreachable as error:
            if error.status == 401:
                forget_tokens()  # revoked or expired early: the next try asks for a new one
            raise
        return made

    return deliver
