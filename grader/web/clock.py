"""The server's clock: one place every deadline decision reads "now" from.

Tests set ``app.config["CLOCK"]`` to a function returning the moment they want (the boundary second
of a deadline); otherwise it is the system's time in UTC.
"""

from __future__ import annotations

from datetime import datetime, timezone

from flask import current_app

__all__ = ["now"]


def now() -> datetime:
    """Now, aware, in UTC (or what the app's ``CLOCK`` says)."""
    clock = current_app.config.get("CLOCK")
    moment = clock() if clock is not None else datetime.now(timezone.utc)
    return moment if moment.tzinfo is not None else moment.replace(tzinfo=timezone.utc)
