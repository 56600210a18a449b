"""A small bounded LRU dict shared by every cache of auszug (engine pairs and pieces, studio networks and faces).

Thread-tolerant: the studio builds from several threads; a concurrent eviction only costs a
recomputation, never a wrong value (values are immutable).
"""

from __future__ import annotations

from collections import OrderedDict

__all__ = ["LruCache"]


class LruCache:
    """At most ``size`` entries; ``get`` refreshes an entry, ``put`` evicts the oldest.

    Examples
    --------
    >>> c = LruCache(2)
    >>> c.put("a", 1); c.put("b", 2); _ = c.get("a"); c.put("c", 3)
    >>> sorted(c.data), "b" in c
    (['a', 'c'], False)
    """

    def __init__(self, size: int):
        self.size = size
        self.data: OrderedDict = OrderedDict()

    def __contains__(self, key: object) -> bool:
        return key in self.data

    def get(self, key: object):
        """The value of ``key`` (made the newest), or None."""
        v = self.data.get(key)
        if v is not None:
            try:
                self.data.move_to_end(key)
            except KeyError:  # evicted meanwhile by another thread: still a valid result
                pass
        return v

    def put(self, key: object, value: object) -> None:
        """Store ``value`` under ``key``, evicting the oldest entries beyond ``size``."""
        self.data[key] = value
        while len(self.data) > self.size:
            try:
                self.data.popitem(last=False)
            except KeyError:  # emptied meanwhile by another thread
                break
