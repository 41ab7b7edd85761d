"""The handler of a derivation sandbox child: it lowers the child's CPU priority, then derives.

Only a derivation child calls :func:`derive_request` from here (it is the ``handler`` of
:func:`grader.jobs.derivation.derivation_sandbox`); its first call lowers the child's priority
before sympy is imported or anything derived, so a slow scene only takes the processor time that
the server's requests and checkers leave over. Importing this module changes nothing.
"""

from __future__ import annotations

import os

from grader.jobs import derivation

__all__ = ["DERIVE_NICENESS", "derive_request"]

DERIVE_NICENESS = 10

_lowered = False


def derive_request(request: dict) -> dict:
    """:func:`grader.jobs.derivation.derive_request`, at a lowered priority (from the first call on)."""
    global _lowered
    if not _lowered:
        _lowered = True
        try:
            os.nice(DERIVE_NICENESS)
        except OSError:  # not permitted on this system: derive at normal priority
            pass
    return derivation.derive_request(request)
