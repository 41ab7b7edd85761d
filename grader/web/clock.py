"""The server's clock: one place every deadline decision reads "now" from.

Tests set ``app.config["CLOCK"]`` to a function returning the moment they want (the boundary second
of a deadline). A test that runs the real server in another process sets ``LAGRADE_CLOCK_FILE`` to a
file holding an ISO 8601 time with an offset, and rewrites it to move time (never set it in
production). Otherwise it is the system's time in UTC.
"""

from __future__ import annotations

from datetime import datetime, timezone
from pathlib import Path

from flask import current_app

__all__ = ["now"]


def now() -> datetime:
    """Now, aware, in UTC (or what the app's ``CLOCK`` or ``CLOCK_FILE`` says)."""
    clock = current_app.config.get("CLOCK")
    if clock is not None:
        moment = clock()
    elif current_app.config.get("CLOCK_FILE"):
        moment = datetime.fromisoformat(Path(current_app.config["CLOCK_FILE"]).read_text().strip())
    else:
        moment = datetime.now(timezone.utc)
    return moment if moment.tzinfo is not None else moment.replace(tzinfo=timezone.utc)
