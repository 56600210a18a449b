"""Shared documents: every tab that has the same workspace file open edits one :class:`Document`.

The :class:`Hub` lives on the server's event loop. It maps document keys
(the workspace path, or a private key for examples, uploads and new
drawings until they are saved) to documents and documents to the
:class:`Connection` objects that show them. A change is answered to the
sender (with its ``id``) and broadcast to every other connection of the
document (``id`` 0); each connection sends through its own :class:`Outbox`,
in order, so a slow tab never holds up the others, and a broadcast geometry
that has not gone out yet is replaced by a newer one (only the latest
drawing matters).

:class:`Autosaver` writes a changed document's drawing to
``<workspace>/.auszug/autosave/`` off the event loop: at most one write per
document in flight and at most one pending (changes in between are
coalesced), flushed when the last tab of a document leaves and at shutdown.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
from collections import deque
from typing import Any, Awaitable, Callable

from auszug.studio.session import Document, Workspace

__all__ = ["Outbox", "Connection", "Autosaver", "Hub", "AUTOSAVE_DELAY"]

log = logging.getLogger(__name__)

#: Seconds between a change and its autosave (changes meanwhile are written together).
AUTOSAVE_DELAY = 0.5

Sender = Callable[[str, "bytes | None"], Awaitable[None]]


class Outbox:
    """The ordered queue of frames for one connection, sent by :meth:`run`.

    Each item is a message's JSON and optionally its payload (the sender packs
    the two into one binary frame, :func:`auszug.studio.protocol.pack`). Items put with a ``coalesce`` key replace
    a pending item with the same key (a newer broadcast geometry of the same
    document supersedes an older one that has not been sent).
    """

    def __init__(self) -> None:
        self._items: deque[tuple[Any, str, bytes | None]] = deque()
        self._wake = asyncio.Event()
        self._closed = False

    def put(self, text: str, payload: bytes | None = None, coalesce: Any = None) -> None:
        """Queue a message's JSON (and its payload)."""
        if self._closed:
            return
        if coalesce is not None:
            for i, (key, _, _) in enumerate(self._items):
                if key == coalesce:
                    del self._items[i]
                    break
        self._items.append((coalesce, text, payload))
        self._wake.set()

    def pending(self) -> int:
        """Items not sent yet."""
        return len(self._items)

    def close(self) -> None:
        """Stop :meth:`run` after the items already queued."""
        self._closed = True
        self._wake.set()

    async def run(self, send: Sender) -> None:
        """Send queued items until closed; returns when the peer is gone or the box is closed."""
        while True:
            while self._items:
                _, text, payload = self._items.popleft()
                try:
                    await send(text, payload)
                except Exception:  # the socket is gone; the reader notices too
                    self._closed = True
                    self._items.clear()
                    return
            if self._closed:
                return
            self._wake.clear()
            await self._wake.wait()


class Connection:
    """One WebSocket: its outbox, the document it shows, its private-document counter."""

    _ids = itertools.count(1)

    def __init__(self) -> None:
        self.id = next(Connection._ids)
        self.outbox = Outbox()
        self.doc: Document | None = None
        self._private = itertools.count(1)

    def private_key(self) -> str:
        """A document key no other connection (and no workspace path) can have."""
        return f"\x00unsaved/{self.id}/{next(self._private)}"


class Autosaver:
    """Coalesced autosaves off the event loop (see the module docstring)."""

    def __init__(self, delay: float = AUTOSAVE_DELAY):
        self.delay = delay
        self._tasks: dict[Document, asyncio.Task] = {}

    def touch(self, doc: Document) -> None:
        """``doc`` changed: make sure a write follows (at most one is pending per document)."""
        t = self._tasks.get(doc)
        if t is None or t.done():
            self._tasks[doc] = asyncio.get_running_loop().create_task(self._run(doc))

    async def _run(self, doc: Document) -> None:
        while True:   # one write per ``delay`` at most, until the autosave is up to date
            if self.delay > 0:
                await asyncio.sleep(self.delay)
            if doc.changes == doc.autosaved_changes:
                return
            try:
                await asyncio.to_thread(doc.write_autosave)
            except Exception:  # a full disk must not kill the editor
                log.exception("studio: autosave of %s failed", doc.label)
                return

    async def flush(self, doc: Document) -> None:
        """Write ``doc``'s autosave now if a change is not written yet."""
        t = self._tasks.pop(doc, None)
        if t is not None and not t.done():
            t.cancel()
        if doc.changes != doc.autosaved_changes:
            try:
                await asyncio.to_thread(doc.write_autosave)
            except Exception:
                log.exception("studio: autosave of %s failed", doc.label)

    async def flush_all(self, docs: list[Document]) -> None:
        """:meth:`flush` every document (server shutdown)."""
        for d in docs:
            await self.flush(d)


class Hub:
    """Documents by key, and the connections of each (event-loop state: no locks needed).

    Parameters
    ----------
    workspace : Workspace
    autosave_delay : float
        Seconds from a change to its autosave.
    """

    def __init__(self, workspace: Workspace, autosave_delay: float = AUTOSAVE_DELAY):
        self.workspace = workspace
        self.docs: dict[str, Document] = {}
        self.members: dict[Document, set[Connection]] = {}
        self.keys: dict[Document, str] = {}
        self.locks: dict[Document, asyncio.Lock] = {}
        self.autosaver = Autosaver(autosave_delay)
        self._flushes: set[asyncio.Task] = set()

    # -- documents --------------------------------------------------------------------
    def lock(self, doc: Document) -> asyncio.Lock:
        """The lock that orders the changes of ``doc`` and their broadcasts."""
        lk = self.locks.get(doc)
        if lk is None:
            lk = self.locks[doc] = asyncio.Lock()
        return lk

    def get(self, key: str) -> Document | None:
        """The open document of ``key`` (a workspace path), if any tab has it."""
        return self.docs.get(key)

    def by_id(self, doc_id: str) -> Document | None:
        """The open document whose :attr:`~Document.doc_id` is ``doc_id``, if any."""
        for d in self.members:
            if d.doc_id == doc_id:
                return d
        return None

    def add(self, doc: Document, key: str) -> Document:
        """Register ``doc`` under ``key``; if another document got there first, that one is returned."""
        have = self.docs.get(key)
        if have is not None:
            return have
        self.docs[key] = doc
        self.keys[doc] = key
        self.members.setdefault(doc, set())
        return doc

    async def attach(self, conn: Connection, doc: Document) -> None:
        """Show ``doc`` in ``conn`` (leaving its previous document)."""
        if conn.doc is doc:
            return
        await self.detach(conn)
        conn.doc = doc
        self.members.setdefault(doc, set()).add(conn)

    async def detach(self, conn: Connection) -> None:
        """``conn`` leaves its document; the last one out flushes its autosave and closes it."""
        doc = conn.doc
        if doc is None:
            return
        conn.doc = None
        ms = self.members.get(doc)
        if ms is not None:
            ms.discard(conn)
            if not ms:
                await self._close(doc)

    async def _close(self, doc: Document) -> None:
        self.members.pop(doc, None)
        key = self.keys.pop(doc, None)
        if key is not None and self.docs.get(key) is doc:
            del self.docs[key]
        self.locks.pop(doc, None)
        # the flush runs as its own task: a cancelled caller (a server shutting down) does not
        # stop the write, and an open of the same file waits for it (:meth:`settle`)
        t = asyncio.get_running_loop().create_task(self.autosaver.flush(doc))
        self._flushes.add(t)
        t.add_done_callback(self._flushes.discard)
        await asyncio.shield(t)

    async def settle(self) -> None:
        """Wait for the autosave flushes of closed documents (before opening a file again)."""
        while self._flushes:
            await asyncio.shield(asyncio.gather(*self._flushes, return_exceptions=True))

    async def rekey(self, doc: Document, key: str) -> None:
        """``doc`` was saved as workspace path ``key``: it becomes that path's document.

        A document another tab had open under ``key`` is replaced: its tabs move
        to ``doc`` (the caller broadcasts the new geometry to them).
        """
        old = self.keys.get(doc)
        if old == key:
            return
        if old is not None and self.docs.get(old) is doc:
            del self.docs[old]
        other = self.docs.get(key)
        if other is not None and other is not doc:
            for c in list(self.members.get(other, ())):
                c.doc = doc
                self.members.setdefault(doc, set()).add(c)
            self.members.pop(other, None)
            self.keys.pop(other, None)
            self.locks.pop(other, None)
            t = self.autosaver._tasks.pop(other, None)
            if t is not None:
                t.cancel()
        self.docs[key] = doc
        self.keys[doc] = key

    # -- sending ------------------------------------------------------------------------
    def broadcast(self, doc: Document, sender: Connection | None, msg_id: int) -> None:
        """Queue ``doc``'s current geometry: to ``sender`` with ``msg_id``, to the other tabs with id 0."""
        text, payload = doc.frames()
        others = None
        for c in self.members.get(doc, ()):
            if c is sender:
                c.outbox.put(text.text(msg_id), payload)
            else:
                if others is None:
                    others = text.text(0)
                c.outbox.put(others, payload, coalesce=("geometry", id(doc)))
        if sender is not None and sender.doc is not doc:
            sender.outbox.put(text.text(msg_id), payload)

    def changed(self, doc: Document) -> None:
        """``doc`` changed: schedule its autosave."""
        self.autosaver.touch(doc)

    async def close(self) -> None:
        """Flush every autosave (server shutdown)."""
        await self.settle()
        await self.autosaver.flush_all(list(self.members))
