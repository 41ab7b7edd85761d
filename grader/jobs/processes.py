"""Which process holds a claim: worker ids that say their host and process, so a process starting
up can tell a claim left by a dead process on this host (queue it again at once) from one held by
a live process, here or on another host (leave it; its lease runs out if that process dies).

Examples
--------
>>> tag = process_tag()
>>> holder_is_dead(f"{tag}:pool/0")
False
>>> holder_is_dead(f"{socket.gethostname()}:999999999:pool/0")
True
>>> holder_is_dead("other-host:1:pool/0")
False
"""

from __future__ import annotations

import os
import socket

__all__ = ["holder_is_dead", "process_tag"]


def process_tag() -> str:
    """``host:pid`` of this process: the start of every worker id it uses."""
    return f"{socket.gethostname()}:{os.getpid()}"


def holder_is_dead(worker_id: str | None) -> bool:
    """True when ``worker_id`` names a process on this host that no longer exists (or no holder)."""
    if not worker_id:
        return True
    host, _, rest = worker_id.partition(":")
    pid_text = rest.partition(":")[0]
    if host != socket.gethostname() or not pid_text.isdigit():
        return False  # another host, or an id we cannot read: its lease decides
    try:
        os.kill(int(pid_text), 0)
    except ProcessLookupError:
        return True
    except (PermissionError, OverflowError):
        return int(pid_text) > 2 ** 22  # exists but not ours (PermissionError), or impossible pid
    return False
