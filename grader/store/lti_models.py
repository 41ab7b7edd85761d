"""The tables of the LTI 1.3 tool: platforms (LMSs), what their ids map to here, and the score outbox.

- ``LtiToolKey``: the tool's own RSA key pair (its private key in PEM): the tool signs its client
  assertions and deep-linking responses with it and publishes the public half as its JWKS.
- ``LtiPlatform`` and ``LtiDeployment``: an LMS registered by an administrator (issuer, client id,
  its OIDC authorisation, token and JWKS URLs) and the deployment ids it may launch with.
- ``LtiAccount``: the platform's user id (``sub``) of a lagrade user (AGS and NRPS name people by it).
- ``LtiContext``: an LMS course, mapped to a lagrade ``Course`` (made on its first launch, or set by
  an administrator), with its roster (NRPS) URL.
- ``LtiResourceLink``: an LMS link (an assignment or resource in the LMS) and what it opens here:
  a problem today. The target is resolved in one place (``grader.web.lti.launch``) so that an
  ``assignment_id`` column can join ``problem_id`` later without touching the rest; its AGS line
  item URL is kept for score passback.
- ``LtiLaunch``: a user launched a resource link: their score on its problem goes back to it.
- ``LtiNonce``: a launch's ``nonce``, kept until it expires so that a replayed id_token is refused.
- ``LtiScorePassback``: the outbox of scores to send to a platform. ``UNIQUE(resource_link_id,
  user_id, score_version)``: one row per distinct score, so a score is never queued (or sent) twice;
  a row is retried with backoff until the platform accepts it, unless a newer score supersedes it.
"""

from __future__ import annotations

from datetime import datetime

from sqlalchemy import ForeignKey, Index, String, Text, UniqueConstraint
from sqlalchemy.orm import Mapped, mapped_column, relationship

from grader.store.models import Base, Course, Problem, User, utcnow

__all__ = ["LtiAccount", "LtiContext", "LtiDeployment", "LtiLaunch", "LtiNonce", "LtiPlatform",
           "LtiResourceLink", "LtiScorePassback", "LtiToolKey"]

# LTI ids (issuer, client id, deployment id, sub, context id, resource link id) are at most 255
# characters by the LTI 1.3 specification; URLs are stored as text.
LTI_ID = 255


class LtiToolKey(Base):
    __tablename__ = "lti_tool_keys"

    id: Mapped[int] = mapped_column(primary_key=True)
    kid: Mapped[str] = mapped_column(String(64), unique=True)
    private_pem: Mapped[str] = mapped_column(Text)
    active: Mapped[bool] = mapped_column(default=True)  # signs new tokens; inactive keys stay in the JWKS a while
    created_at: Mapped[datetime] = mapped_column(default=utcnow)


class LtiPlatform(Base):
    __tablename__ = "lti_platforms"
    __table_args__ = (UniqueConstraint("issuer", "client_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    issuer: Mapped[str] = mapped_column(String(LTI_ID))
    client_id: Mapped[str] = mapped_column(String(LTI_ID))
    auth_url: Mapped[str] = mapped_column(Text)  # OIDC authorisation endpoint (the launch's second leg)
    token_url: Mapped[str] = mapped_column(Text)  # OAuth 2 token endpoint (AGS, NRPS access tokens)
    jwks_url: Mapped[str] = mapped_column(Text)  # the platform's public keys
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    deployments: Mapped[list[LtiDeployment]] = relationship(back_populates="platform", cascade="all, delete-orphan")


class LtiDeployment(Base):
    __tablename__ = "lti_deployments"
    __table_args__ = (UniqueConstraint("platform_id", "deployment_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    platform_id: Mapped[int] = mapped_column(ForeignKey("lti_platforms.id", ondelete="CASCADE"))
    deployment_id: Mapped[str] = mapped_column(String(LTI_ID))

    platform: Mapped[LtiPlatform] = relationship(back_populates="deployments")


class LtiAccount(Base):
    __tablename__ = "lti_accounts"
    __table_args__ = (UniqueConstraint("platform_id", "sub"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    platform_id: Mapped[int] = mapped_column(ForeignKey("lti_platforms.id", ondelete="CASCADE"))
    sub: Mapped[str] = mapped_column(String(LTI_ID))
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)

    user: Mapped[User] = relationship()


class LtiContext(Base):
    __tablename__ = "lti_contexts"
    __table_args__ = (UniqueConstraint("platform_id", "context_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    platform_id: Mapped[int] = mapped_column(ForeignKey("lti_platforms.id", ondelete="CASCADE"))
    context_id: Mapped[str] = mapped_column(String(LTI_ID))
    title: Mapped[str] = mapped_column(String(200), default="")
    course_id: Mapped[int] = mapped_column(ForeignKey("courses.id", ondelete="CASCADE"), index=True)
    memberships_url: Mapped[str | None] = mapped_column(Text)  # NRPS, from the last launch that named it
    roster_synced_at: Mapped[datetime | None]
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    platform: Mapped[LtiPlatform] = relationship()
    course: Mapped[Course] = relationship()


class LtiResourceLink(Base):
    __tablename__ = "lti_resource_links"
    __table_args__ = (UniqueConstraint("context_id", "resource_link_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    context_id: Mapped[int] = mapped_column(ForeignKey("lti_contexts.id", ondelete="CASCADE"))
    resource_link_id: Mapped[str] = mapped_column(String(LTI_ID))
    title: Mapped[str] = mapped_column(String(200), default="")
    # What the link opens: a problem (None until the link names one). Assignments join as another
    # nullable target column; grader.web.lti.launch.link_target is the one place that resolves it.
    problem_id: Mapped[int | None] = mapped_column(ForeignKey("problems.id", ondelete="SET NULL"))
    lineitem_url: Mapped[str | None] = mapped_column(Text)  # AGS: where this link's scores go
    lineitems_url: Mapped[str | None] = mapped_column(Text)  # AGS: the context's line items (to make one)
    created_at: Mapped[datetime] = mapped_column(default=utcnow)

    context: Mapped[LtiContext] = relationship()
    problem: Mapped[Problem | None] = relationship()


class LtiLaunch(Base):
    __tablename__ = "lti_launches"
    __table_args__ = (UniqueConstraint("resource_link_id", "user_id"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    resource_link_id: Mapped[int] = mapped_column(ForeignKey("lti_resource_links.id", ondelete="CASCADE"))
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    last_launched_at: Mapped[datetime] = mapped_column(default=utcnow)

    resource_link: Mapped[LtiResourceLink] = relationship()


class LtiNonce(Base):
    __tablename__ = "lti_nonces"
    __table_args__ = (UniqueConstraint("platform_id", "nonce"),)

    id: Mapped[int] = mapped_column(primary_key=True)
    platform_id: Mapped[int] = mapped_column(ForeignKey("lti_platforms.id", ondelete="CASCADE"))
    nonce: Mapped[str] = mapped_column(String(LTI_ID))
    expires_at: Mapped[datetime] = mapped_column(index=True)


class LtiScorePassback(Base):
    __tablename__ = "lti_score_passbacks"
    __table_args__ = (UniqueConstraint("resource_link_id", "user_id", "score_version"),
                      Index("ix_lti_score_passbacks_due", "sent_at", "next_try_at"))

    id: Mapped[int] = mapped_column(primary_key=True)
    resource_link_id: Mapped[int] = mapped_column(ForeignKey("lti_resource_links.id", ondelete="CASCADE"))
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"))
    score_version: Mapped[int]  # 1, 2, ... per (link, user): each distinct score once
    score_given: Mapped[float]
    score_maximum: Mapped[float]
    scored_at: Mapped[datetime] = mapped_column(default=utcnow)  # AGS timestamp: newer scores win
    attempts: Mapped[int] = mapped_column(default=0)
    next_try_at: Mapped[datetime] = mapped_column(default=utcnow)
    sent_at: Mapped[datetime | None]
    superseded: Mapped[bool] = mapped_column(default=False)  # a newer score was queued before this one went out
    last_error: Mapped[str | None] = mapped_column(Text)

    resource_link: Mapped[LtiResourceLink] = relationship()
