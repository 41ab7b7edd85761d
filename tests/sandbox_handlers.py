"""Test-only sandbox handlers that misbehave on request (never shipped in ``grader``).

The sandbox child imports them by name, so tests put this folder on the child's ``PYTHONPATH``.
"""

import os
import time


def runaway(request):
    """Misbehaves as asked: ``{"sleep": s}``, ``{"spin": true}``, ``{"allocate_mb": n}``,
    ``{"exit": code}`` or ``{"raise": true}``; otherwise replies with its pid."""
    request = request or {}
    if request.get("sleep"):
        time.sleep(float(request["sleep"]))
    if request.get("spin"):
        while True:
            pass
    if request.get("allocate_mb"):
        hog = bytearray(int(request["allocate_mb"]) * 1024 * 1024)
        return {"allocated": len(hog)}
    if "exit" in request:
        os._exit(int(request["exit"]))
    if request.get("raise"):
        raise RuntimeError("a handler bug")
    return {"pid": os.getpid(), "echo": request.get("echo")}


def verdict(request):
    """Replies with whatever ``request["reply"]`` is: a stand-in checker for verdict mapping tests."""
    return (request or {}).get("reply")
