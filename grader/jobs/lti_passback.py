"""LTI score passback: an outbox of scores for the platforms, filled with each verdict, drained by a sender.

A student who opened a problem through an LMS link (an ``LtiLaunch``) has their score on that problem
sent back to the link's AGS line item after every verdict. The guarantees come from the outbox:

- *never lost*: :func:`enqueue_for_verdict` runs inside the transaction that records the verdict
  (``grader.jobs.queue.record``), so a verdict is never committed without its passback row;
- *never sent twice for the same score*: ``UNIQUE(resource_link_id, user_id, score_version)`` and
  "a new row only when the score differs from the last one queued" make each distinct score one
  row; a row is marked sent once the platform accepted it and never sent again;
- *until it succeeds*: a failed delivery is retried with exponential backoff (``BACKOFF_S`` doubling
  up to ``BACKOFF_MAX_S``), without a limit on attempts; an unsent row is superseded (not sent) when
  a newer score for the same link and student is queued, and each score carries the time it was
  computed, so the platform keeps the newest whatever the order of arrival.

The HTTP side (tokens, the AGS call) belongs to the web layer; it is handed to :func:`deliver_due`
and :class:`PassbackSender` as a ``deliver`` function, so this module imports nothing from
``grader.web`` (data flows one way).

>>> backoff_s(1), backoff_s(2), backoff_s(30)
(30.0, 60.0, 3600.0)
"""

from __future__ import annotations

import logging
import threading
from dataclasses import dataclass
from datetime import datetime, timedelta
from typing import Callable

from sqlalchemy import select, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from grader.store.db import Database
from grader.store.lti_models import LtiAccount, LtiContext, LtiLaunch, LtiPlatform, LtiResourceLink, LtiScorePassback
from grader.store.models import Problem, Submission, utcnow
from grader.store.problems import latest_version
from grader.store.scores import practice_score

__all__ = ["BACKOFF_MAX_S", "BACKOFF_S", "DeliveryReport", "PassbackSender", "ScoreToSend", "backoff_s",
           "deliver_due", "enqueue_for_verdict", "problem_score"]

log = logging.getLogger(__name__)

BACKOFF_S = 30.0
BACKOFF_MAX_S = 3600.0
CLAIM_S = 120.0  # a row being delivered is not due again for this long (a sender that died mid-call)


def backoff_s(attempts: int) -> float:
    """Seconds to wait after the ``attempts``-th failed delivery: 30 s, doubling, at most an hour."""
    return min(BACKOFF_MAX_S, BACKOFF_S * 2.0 ** min(max(attempts - 1, 0), 20))


def problem_score(session: Session, user_id: int, problem_id: int) -> tuple[float, float]:
    """(score given, maximum) of ``user_id`` on a problem, out of 1: the one score rule of
    :mod:`grader.store.scores` (best attempt per answer, weighted) against the newest published version."""
    version = latest_version(session, session.get(Problem, problem_id), published_only=True)
    if version is None:
        return 0.0, 1.0
    return practice_score(session, user_id, version).score, 1.0


def enqueue_for_verdict(session: Session, submission_id: int) -> int:
    """Queue the student's new score for every LMS link through which they opened this submission's
    problem; call it in the transaction that records the verdict. Returns the rows queued."""
    session.flush()  # the verdict just added counts in the score
    submission = session.get(Submission, submission_id)
    problem_id = submission.problem_version.problem_id
    links = session.scalars(select(LtiResourceLink.id).join(LtiLaunch, LtiLaunch.resource_link_id == LtiResourceLink.id)
                            .where(LtiLaunch.user_id == submission.user_id,
                                   LtiResourceLink.problem_id == problem_id,
                                   # only links whose launch offered the grade service (AGS)
                                   LtiResourceLink.lineitem_url.is_not(None) | LtiResourceLink.lineitems_url.is_not(None))
                            ).all()
    if not links:
        return 0
    given, maximum = problem_score(session, submission.user_id, problem_id)
    return sum(_queue_score(session, link, submission.user_id, given, maximum) for link in links)


def _queue_score(session: Session, link_id: int, user_id: int, given: float, maximum: float) -> int:
    for _ in range(3):  # a concurrent verdict may take the same version number: read again and retry
        newest = session.scalar(select(LtiScorePassback)
                                .where(LtiScorePassback.resource_link_id == link_id, LtiScorePassback.user_id == user_id)
                                .order_by(LtiScorePassback.score_version.desc()).limit(1))
        if newest is not None and (newest.score_given, newest.score_maximum) == (given, maximum):
            return 0  # this score is queued or sent already
        try:
            with session.begin_nested():
                session.add(LtiScorePassback(resource_link_id=link_id, user_id=user_id,
                                             score_version=(newest.score_version + 1) if newest else 1,
                                             score_given=given, score_maximum=maximum, scored_at=utcnow(),
                                             next_try_at=utcnow()))
        except IntegrityError:
            continue
        if newest is not None:
            session.execute(update(LtiScorePassback)
                            .where(LtiScorePassback.resource_link_id == link_id, LtiScorePassback.user_id == user_id,
                                   LtiScorePassback.sent_at.is_(None),
                                   LtiScorePassback.score_version <= newest.score_version)
                            .values(superseded=True))
        return 1
    raise RuntimeError("could not queue an LTI score: the version number kept being taken")


@dataclass(frozen=True)
class ScoreToSend:
    """One queued score with everything the web layer's AGS client needs (plain data)."""

    passback_id: int
    platform_id: int
    issuer: str
    client_id: str
    token_url: str
    user_sub: str
    resource_link_id: str
    link_title: str
    lineitem_url: str | None
    lineitems_url: str | None
    problem_slug: str | None
    score_given: float
    score_maximum: float
    scored_at: datetime


# deliver(score) sends it and returns the line item URL it used when it had to make one (or None);
# it raises on any failure (the row is then retried later).
Deliver = Callable[[ScoreToSend], "str | None"]


@dataclass
class DeliveryReport:
    sent: int = 0
    failed: int = 0


def _due(session: Session, now: datetime, limit: int) -> list[int]:
    return list(session.scalars(
        select(LtiScorePassback.id)
        .where(LtiScorePassback.sent_at.is_(None), LtiScorePassback.superseded.is_(False),
               LtiScorePassback.next_try_at <= now)
        .order_by(LtiScorePassback.id).limit(limit)))


def _claim(database: Database, passback_id: int, now: datetime) -> ScoreToSend | None:
    with database.write() as session:
        # A conditional UPDATE: of several senders (processes), exactly one moves the row's next try.
        taken = session.execute(
            update(LtiScorePassback)
            .where(LtiScorePassback.id == passback_id, LtiScorePassback.sent_at.is_(None),
                   LtiScorePassback.superseded.is_(False), LtiScorePassback.next_try_at <= now)
            .values(next_try_at=now + timedelta(seconds=CLAIM_S))).rowcount
        if taken != 1:
            return None  # another sender took it, or a newer score replaced it
        row = session.get(LtiScorePassback, passback_id)
        link = row.resource_link
        context = session.get(LtiContext, link.context_id)
        platform = session.get(LtiPlatform, context.platform_id)
        sub = session.scalar(select(LtiAccount.sub).where(LtiAccount.platform_id == platform.id,
                                                          LtiAccount.user_id == row.user_id))
        problem = session.get(Problem, link.problem_id) if link.problem_id else None
        return ScoreToSend(row.id, platform.id, platform.issuer, platform.client_id, platform.token_url, sub or "",
                           link.resource_link_id, link.title, link.lineitem_url, link.lineitems_url,
                           problem.slug if problem else None, row.score_given, row.score_maximum, row.scored_at)


def deliver_due(database: Database, deliver: Deliver, *, now: datetime | None = None, limit: int = 100) -> DeliveryReport:
    """Send every due score once (oldest first); mark each sent or schedule its retry. Returns counts."""
    now = now or utcnow()
    report = DeliveryReport()
    with database.read() as session:
        due = _due(session, now, limit)
    for passback_id in due:
        score = _claim(database, passback_id, now)
        if score is None:
            continue
        try:
            made_lineitem = deliver(score)
        except Exception as error:  # any failure: the platform's, the network's or ours; retry later
            log.warning("LTI score %d for %s not delivered: %s", passback_id, score.issuer, error)
            with database.write() as session:
                row = session.get(LtiScorePassback, passback_id)
                row.attempts += 1
                row.next_try_at = now + timedelta(seconds=backoff_s(row.attempts))
                row.last_error = str(error)[:2000]
            report.failed += 1
            continue
        with database.write() as session:
            row = session.get(LtiScorePassback, passback_id)
            row.attempts += 1
            row.sent_at = utcnow()
            row.last_error = None
            if made_lineitem:
                row.resource_link.lineitem_url = made_lineitem
        report.sent += 1
    return report


class PassbackSender:
    """A background thread of ``grader serve`` that calls :func:`deliver_due` every ``interval_s``."""

    def __init__(self, database: Database, deliver: Deliver, *, interval_s: float = 5.0):
        self.database, self.deliver, self.interval_s = database, deliver, interval_s
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> PassbackSender:
        self._thread = threading.Thread(target=self._run, name="lti-passback", daemon=True)
        self._thread.start()
        return self

    def stop(self, timeout: float = 10.0) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                deliver_due(self.database, self.deliver)
            except Exception:  # the database away for a moment: try again at the next tick
                log.exception("LTI score passback round failed")
            self._stop.wait(self.interval_s)
