"""The derivation sandbox child's handler module: importing it lowers the child's CPU priority.

Only a derivation child imports this module (it is the ``handler`` of
:func:`grader.jobs.derivation.derivation_sandbox`), before it imports sympy or derives anything,
so a slow scene and even the child's start-up only take the processor time that the server's
requests and checkers leave over.
"""

from __future__ import annotations

import os

__all__ = ["DERIVE_NICENESS", "derive_request"]

DERIVE_NICENESS = 10

try:
    os.nice(DERIVE_NICENESS)
except OSError:  # not permitted on this system: derive at normal priority
    pass

from grader.jobs.derivation import derive_request  # noqa: E402  (imported at the lowered priority)
