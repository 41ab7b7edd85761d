"""The tool's own RSA key pair and its JWKS: the one adapter between lagrade and the JOSE library.

LTI 1.3 is JSON Web Tokens signed with RS256 both ways: the platform signs launches (checked against
its JWKS), the tool signs its OAuth client assertions and deep-linking responses (checked by the
platform against the JWKS this tool publishes at ``/lti/jwks``). The JOSE work (keys, signing,
verifying, claims) is done by ``joserfc``, a maintained implementation of the JOSE RFCs; this module
is the only place that imports it, so changing library touches one file.

The private key lives in the database (``lti_tool_keys``), made on first use, so that every server
process and the score sender sign with the same key, and rotating it is a new row.

>>> key = new_key()
>>> claims = verify(sign({"iss": "me"}, key), public_key_set([key])).claims
>>> claims["iss"]
'me'
"""

from __future__ import annotations

import secrets
from typing import Any

from joserfc import jwk, jwt
from joserfc.errors import JoseError
from sqlalchemy import select

from grader.store.db import Database
from grader.store.lti_models import LtiToolKey

__all__ = ["ALGORITHM", "JoseError", "KeySet", "RSAKey", "active_key", "import_key_set", "new_key",
           "public_key_set", "public_pem", "sign", "tool_jwks", "verify"]

ALGORITHM = "RS256"  # the one algorithm LTI 1.3 requires; nothing else is accepted
KEY_BITS = 2048
RSAKey = jwk.RSAKey
KeySet = jwk.KeySet


def new_key() -> RSAKey:
    """A fresh RSA key pair with a random ``kid``, for signing with RS256."""
    return jwk.RSAKey.generate_key(KEY_BITS, private=True, parameters={
        "kid": secrets.token_urlsafe(12), "use": "sig", "alg": ALGORITHM})


def _from_row(row: LtiToolKey) -> RSAKey:
    return jwk.RSAKey.import_key(row.private_pem, parameters={"kid": row.kid, "use": "sig", "alg": ALGORITHM})


def active_key(database: Database) -> RSAKey:
    """The tool's signing key (the newest active one), made and stored on first use."""
    with database.read() as session:
        row = session.scalar(select(LtiToolKey).where(LtiToolKey.active.is_(True)).order_by(LtiToolKey.id.desc()))
    if row is None:
        with database.write() as session:
            row = session.scalar(select(LtiToolKey).where(LtiToolKey.active.is_(True)).order_by(LtiToolKey.id.desc()))
            if row is None:
                key = new_key()
                row = LtiToolKey(kid=key.kid, private_pem=key.as_pem(private=True).decode())
                session.add(row)
    return _from_row(row)


def tool_jwks(database: Database) -> dict[str, Any]:
    """The public halves of every stored tool key (``{"keys": [...]}``), the JWKS platforms fetch."""
    active_key(database)
    with database.read() as session:
        rows = session.scalars(select(LtiToolKey).order_by(LtiToolKey.id)).all()
    return public_key_set([_from_row(row) for row in rows]).as_dict(private=False)


def public_key_set(keys: list[RSAKey]) -> KeySet:
    return jwk.KeySet([jwk.RSAKey.import_key(k.as_dict(private=False)) for k in keys])


def public_pem(key: RSAKey) -> str:
    """The public key in PEM, for platforms that take a key rather than a JWKS URL."""
    return key.as_pem(private=False).decode()


def import_key_set(data: Any) -> KeySet:
    """A platform's JWKS document as a key set; ``ValueError`` if it is not one."""
    if not isinstance(data, dict) or not isinstance(data.get("keys"), list):
        raise ValueError("a JWKS document is an object with a 'keys' list")
    try:
        return jwk.KeySet.import_key_set(data)
    except (JoseError, TypeError, KeyError, ValueError) as error:
        raise ValueError(f"the JWKS holds a key that cannot be read: {error}") from error


def sign(claims: dict[str, Any], key: RSAKey) -> str:
    """``claims`` as a compact JWT signed with ``key`` (RS256, its ``kid`` in the header)."""
    return jwt.encode({"alg": ALGORITHM, "typ": "JWT", "kid": key.kid}, claims, key, algorithms=[ALGORITHM])


def verify(token: str, keys: KeySet | RSAKey) -> jwt.Token:
    """The token's header and claims if its RS256 signature verifies with ``keys``; else ``JoseError``.

    Only the signature: the claims (issuer, audience, expiry, nonce) are the caller's to check.
    """
    return jwt.decode(token, keys, algorithms=[ALGORITHM])
