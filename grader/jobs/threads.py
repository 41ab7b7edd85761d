"""Starting a pool's worker threads: one thread per worker, each with a worker id that names its
process (``host:pid:boot``, read by start-up recovery) and its number."""

from __future__ import annotations

import threading
from typing import Callable

__all__ = ["start_threads"]


def start_threads(target: Callable[[str], None], count: int, boot_id: str, name: str,
                  tag: str = "") -> list[threading.Thread]:
    """``count`` daemon threads running ``target(worker_id)``, ids ``f"{boot_id}/{tag}{n}"``.

    >>> ids = []
    >>> for thread in start_threads(ids.append, 2, "host:1:abc", "example", "d"):
    ...     thread.join()
    >>> sorted(ids)
    ['host:1:abc/d0', 'host:1:abc/d1']
    """
    threads = []
    for number in range(count):
        thread = threading.Thread(target=target, args=(f"{boot_id}/{tag}{number}",), name=f"{name}-{number}",
                                  daemon=True)
        thread.start()
        threads.append(thread)
    return threads
