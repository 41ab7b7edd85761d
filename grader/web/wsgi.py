"""The WSGI application for several web processes: ``gunicorn -w 4 'grader.web.wsgi:app'``.

Each process makes its app from the environment (``DATABASE_URL``, ``LAGRADE_*``, and for shared
rate limits ``LAGRADE_RATELIMIT_STORAGE_URI=redis://...``) and starts its background work
(:mod:`grader.web.background`). Migrations are a separate step, run once before: ``grader db
upgrade`` (docker-compose's ``migrate`` service).
"""

from __future__ import annotations

import atexit
import os

from grader.web import create_app
from grader.web.background import start_background

app = create_app()
background = start_background(app, grading_workers=int(os.environ.get("GRADER_WORKERS", "2")))
atexit.register(background.stop)
