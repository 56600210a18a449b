"""The studio's ASGI app (Starlette): static front end + one WebSocket endpoint.

Security, for a server that edits files on the user's machine:

- it is meant to bind 127.0.0.1 only (the CLI does);
- every HTTP and WebSocket request whose ``Host`` or ``Origin`` names another
  host, or whose ``Origin`` names another port, is refused (403 / close 1008):
  this defeats DNS rebinding, where a foreign page's domain resolves to
  127.0.0.1, and pages of other local servers;
- every HTTP response forbids framing (``frame-ancestors 'none'``);
- drawings are opened and saved only inside the workspace folder;
- client messages larger than :data:`~auszug.studio.protocol.MAX_MESSAGE_BYTES`
  are refused with an error reply;
- a malformed message or a failing edit gets an :class:`~auszug.studio.protocol.Error`
  reply and the connection stays open.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import os
import threading
import time
from importlib.resources import files
from pathlib import Path
from typing import Any, Iterable
from urllib.parse import urlsplit

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import PlainTextResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Message, Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from auszug.errors import AuszugError
from auszug.limits import LIMITS
from auszug.studio import meshes
from auszug.studio import protocol as P
from auszug.studio.hub import AUTOSAVE_DELAY, Connection, Hub
from auszug.studio.session import (
    Document,
    EditCancelled,
    Workspace,
    example_document,
    new_document,
    open_document,
    prune_offers,
    resume_document,
    text_document,
)

__all__ = ["LOCAL_HOSTS", "BUILD_COMMAND", "SECURITY_HEADERS", "static_dir", "create_app", "HostOriginGuard"]

log = logging.getLogger(__name__)

#: Host names the studio answers to.
LOCAL_HOSTS: tuple[str, ...] = ("127.0.0.1", "localhost", "::1")
#: What builds the front end into the package.
BUILD_COMMAND = "make web"


def static_dir() -> Path:
    """The built front end inside the installed package (``auszug/studio/static``).

    The environment variable ``AUSZUG_STUDIO_STATIC`` names another folder
    (development: a front end built elsewhere with ``vite build --outDir``).
    """
    override = os.environ.get("AUSZUG_STUDIO_STATIC")
    if override:
        return Path(override)
    return Path(str(files("auszug.studio").joinpath("static")))


def _hostname(value: str) -> str | None:
    """The host name of a ``Host`` header value (``name[:port]``, ``[v6]:port``)."""
    try:
        return urlsplit("//" + value).hostname
    except ValueError:
        return None


class HostOriginGuard:
    """ASGI middleware: refuse requests whose Host or Origin is not one of ``hosts``."""

    def __init__(self, app: ASGIApp, hosts: Iterable[str]):
        self.app = app
        self.hosts = {h.lower() for h in hosts}
        self.hub: Hub | None = None  # create_app hands the studio's hub out through the guard

    def _allowed(self, scope: Scope) -> bool:
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])}
        host = headers.get("host")
        if host is None or _hostname(host) not in self.hosts:
            return False
        origin = headers.get("origin")
        if origin is not None:  # browsers always send it on WebSockets and cross-origin requests
            try:
                parts = urlsplit(origin)
                host_port = urlsplit("//" + host).port
                origin_port = parts.port
            except ValueError:
                return False
            if parts.scheme not in ("http", "https") or parts.hostname not in self.hosts:
                return False
            # the same scheme and port too: another local server (a dev server, another app on
            # localhost:OTHER) is another origin and must not drive this one
            scheme = _PAGE_SCHEME.get(scope.get("scheme", "http"), "http")
            if parts.scheme != scheme:
                return False
            default = _DEFAULT_PORTS[scheme]
            if (origin_port or default) != (host_port or default):
                return False
        return True

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        """Pass a request on to the app, or refuse it when its host or origin is not local."""
        if scope["type"] in ("http", "websocket") and not self._allowed(scope):
            if scope["type"] == "websocket":
                await send({"type": "websocket.close", "code": 1008, "reason": "foreign host or origin"})
            else:
                await PlainTextResponse("foreign host or origin", status_code=403,
                                        headers=dict(SECURITY_HEADERS))(scope, receive, send)
            return
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                message = dict(message)
                message["headers"] = [*message.get("headers", []), *_SECURITY_RAW]
            await send(message)

        await self.app(scope, receive, send_with_headers)


#: The page scheme of a request's scheme.
_PAGE_SCHEME = {"http": "http", "ws": "http", "https": "https", "wss": "https"}
#: Ports a Host or Origin without one means.
_DEFAULT_PORTS = {"http": 80, "https": 443}
#: Headers of every HTTP response: no other page may show the studio in a frame (clickjacking).
SECURITY_HEADERS: tuple[tuple[str, str], ...] = (
    ("content-security-policy", "frame-ancestors 'none'"),
    ("x-frame-options", "DENY"),
)
_SECURITY_RAW = [(k.encode("latin-1"), v.encode("latin-1")) for k, v in SECURITY_HEADERS]


#: An edit that took longer than this (seconds, edit + geometry) sends the document's next
#: edits to a worker thread; quicker ones run on the event loop, where a thread hop
#: (about 0.05-0.1 ms) would cost more than the edit saves.
INLINE_EDIT_SECONDS = 0.003


def _text_bytes(data: str | bytes) -> int:
    """Size of a frame in bytes (UTF-8 for text), cheaply for small frames."""
    if isinstance(data, bytes):
        return len(data)
    return len(data) if len(data) * 4 <= P.MAX_MESSAGE_BYTES else len(data.encode("utf-8", "surrogatepass"))


def _raw_id(data: str | bytes) -> int:
    """The ``id`` of a message that did not decode, if it has an integer one (else 0)."""
    try:
        v = json.loads(data).get("id", 0)
    except (ValueError, AttributeError, UnicodeDecodeError, RecursionError):  # as P.decode refused it
        return 0
    return v if isinstance(v, int) and not isinstance(v, bool) else 0


def _error(e: BaseException, msg_id: int, label: str = "") -> P.Error:
    """One line naming the file (``label``) and the problem."""
    if isinstance(e, OSError):
        text = f"{e.filename or label or 'file'}: {e.strerror or e}"
    elif isinstance(e, AuszugError):
        text = str(e)
    else:
        log.exception("studio: message failed", exc_info=e)
        text = f"internal error: {type(e).__name__}: {e}"
    if label and not text.startswith(label) and not isinstance(e, OSError):
        text = f"{label}: {text}"
    return P.Error(message=" ".join(text.split()), id=msg_id)


class _Studio:
    """The message handlers of one app: a hub of shared documents on one workspace."""

    def __init__(self, workspace: Workspace, drawing: str | None, autosave_delay: float):
        self.workspace = workspace
        self.drawing = drawing
        self.hub = Hub(workspace, autosave_delay)
        prune_offers(workspace)   # set-aside autosaves past their lifetime (LIMITS.autosave_offer*)

    # -- the socket -------------------------------------------------------------------
    async def socket(self, ws: WebSocket, max_message_bytes: int) -> None:
        await ws.accept()
        conn = Connection()

        async def send(text: str, payload: bytes | None) -> None:
            if payload is None:
                await ws.send({"type": "websocket.send", "text": text})
            else:   # a message and its payload travel as one frame
                await ws.send({"type": "websocket.send", "bytes": P.pack(text, payload)})

        sender = asyncio.create_task(conn.outbox.run(send))
        jobs: asyncio.Queue = asyncio.Queue()
        worker = asyncio.create_task(self._jobs(conn, jobs))
        try:
            if self.drawing:
                await self.handle(conn, P.Open(path=self.drawing), jobs)
            while True:
                try:
                    event = await ws.receive()
                except (WebSocketDisconnect, RuntimeError):
                    return
                if event["type"] == "websocket.disconnect":
                    return
                data = event.get("text")
                if data is None:
                    data = event.get("bytes") or b""
                n = _text_bytes(data)
                if n > max_message_bytes:
                    conn.outbox.put(P.encode(P.Error(
                        message=f"message of {n} bytes is larger than the limit of {max_message_bytes} bytes")))
                    continue
                msg_id, msg = 0, None
                try:
                    msg = P.decode(data)
                    msg_id = msg.id
                    await self.handle(conn, msg, jobs)
                except Exception as e:  # a bad message must not kill the session
                    if msg is None:
                        msg_id = _raw_id(data)
                    # edits name the document they failed on; the other messages name their own file
                    on_doc = isinstance(msg, (P.EditOp, P.Undo, P.Redo, P.Recover)) and not isinstance(
                        e, P.ProtocolError)
                    label = conn.doc.label if on_doc and conn.doc is not None else ""
                    conn.outbox.put(P.encode(_error(e, msg_id, label)))
        finally:
            worker.cancel()
            conn.outbox.close()
            sender.cancel()
            await self.hub.detach(conn)   # last: it may wait for an autosave

    async def _jobs(self, conn: Connection, jobs: asyncio.Queue) -> None:
        """Meshes, loops and exports of one connection, one after the other, in worker threads."""
        while True:
            msg, snapshot, label = await jobs.get()
            try:
                reply, payload = await asyncio.to_thread(self._job, msg, snapshot, label)
            except Exception as e:
                reply, payload = _error(e, msg.id, label), None
            conn.outbox.put(P.encode(reply), payload)

    @staticmethod
    def _job(msg: Any, snapshot: tuple, label: str) -> tuple[Any, bytes | None]:
        drawing, net, revision = snapshot
        if isinstance(msg, P.GetMesh):
            return meshes.mesh_message(net, style=msg.style, faces=msg.faces, loops=msg.loops, size=msg.size,
                                       segments=msg.segments, revision=revision, msg_id=msg.id)
        if isinstance(msg, P.GetLoops):
            return meshes.loops_message(net, revision=revision, msg_id=msg.id)
        name, mime, data = meshes.export_file(net, label or drawing.name or "drawing", format=msg.format,
                                              style=msg.style, faces=msg.faces, loops=msg.loops,
                                              solid=msg.solid, colors=msg.colors, segments=msg.segments,
                                              around=msg.around)
        return P.Exported(name=name, mime=mime, size=len(data), id=msg.id), data

    # -- messages ---------------------------------------------------------------------
    def _need(self, conn: Connection) -> Document:
        if conn.doc is None:
            raise AuszugError("no drawing is open: send an 'open' message first")
        return conn.doc

    async def handle(self, conn: Connection, msg: Any, jobs: asyncio.Queue) -> None:
        """Carry out one decoded message for ``conn``; replies go to the outboxes."""
        hub = self.hub
        if isinstance(msg, (P.EditOp, P.Undo, P.Redo, P.Recover)):
            doc = self._need(conn)
            async with hub.lock(doc):
                if isinstance(msg, P.EditOp):
                    fn, args = doc.apply, (msg,)
                else:
                    fn, args = {P.Undo: doc.undo, P.Redo: doc.redo, P.Recover: doc.recover}[type(msg)], ()
                # a drag's edits on a quick document run on the event loop (a thread hop would cost more
                # than they take); everything else (a fold, a new curve, a slow document) in a worker
                # thread, so the other tabs are answered meanwhile
                dragging = isinstance(msg, (P.Undo, P.Redo)) or bool(getattr(msg, "drag", 0))
                inline = dragging and not doc.slow_edits
                t0 = time.perf_counter()
                if inline:
                    doc.change(fn, *args)
                else:
                    await self._in_worker(doc, fn, args)
                doc.slow_edits = time.perf_counter() - t0 > INLINE_EDIT_SECONDS
                hub.broadcast(doc, conn, msg.id)
            hub.changed(doc)
        elif isinstance(msg, P.Open):
            rel = self.workspace.relative(self.workspace.resolve(msg.path))
            await hub.settle()   # a tab that just closed this file may still be writing its autosave
            doc = hub.get(rel)
            if doc is None:
                doc = await asyncio.to_thread(self._opened, open_document, self.workspace, msg.path)
                doc = hub.add(doc, rel)
            await hub.attach(conn, doc)
            text, payload = doc.frames()
            conn.outbox.put(text.text(msg.id), payload)
        elif isinstance(msg, P.Resume):
            await hub.settle()
            doc = hub.by_id(msg.doc)
            if doc is None and msg.path:
                doc = hub.get(self.workspace.relative(self.workspace.resolve(msg.path)))
            if doc is None:
                doc = await asyncio.to_thread(self._opened, resume_document, self.workspace, msg.doc, msg.path)
                doc = hub.add(doc, doc.path or conn.private_key())
            await hub.attach(conn, doc)
            text, payload = doc.frames()
            conn.outbox.put(text.text(msg.id), payload)
        elif isinstance(msg, (P.OpenExample, P.OpenText, P.NewDrawing)):
            await hub.settle()
            if isinstance(msg, P.OpenExample):
                doc = await asyncio.to_thread(self._opened, example_document, self.workspace, msg.name)
            elif isinstance(msg, P.OpenText):
                doc = await asyncio.to_thread(self._opened, text_document, self.workspace, msg.name, msg.text)
            else:
                doc = await asyncio.to_thread(self._opened, new_document, self.workspace, msg.name)
            hub.add(doc, conn.private_key())
            await hub.attach(conn, doc)
            text, payload = doc.frames()
            conn.outbox.put(text.text(msg.id), payload)
        elif isinstance(msg, P.Save):
            doc = self._need(conn)
            async with hub.lock(doc):
                others = hub.members.get(doc, set()) - {conn}
                target = msg.path and self.workspace.relative(self.workspace.resolve(msg.path))
                if others and target and target != doc.path:
                    # "Save as" in one tab of a shared document: only this tab moves to the new file
                    fork = doc.fork()
                    rel = await asyncio.to_thread(fork.save, msg.path)
                    hub.add(fork, conn.private_key())
                    await hub.attach(conn, fork)
                    doc = fork
                else:
                    rel = await asyncio.to_thread(doc.save, msg.path)
                await hub.rekey(doc, rel)
                conn.outbox.put(P.encode(P.Saved(path=rel, id=msg.id)))
                hub.broadcast(doc, None, 0)
        elif isinstance(msg, P.ListFiles):
            from auszug import examples

            try:
                ws_files, notes = await asyncio.to_thread(self.workspace.listing)
            except OSError as e:   # the workspace folder itself is gone or unreadable: still the examples
                ws_files, notes = [], [f"workspace: cannot list it ({e.strerror or e})"]
            conn.outbox.put(P.encode(P.Files(workspace=ws_files, examples=examples.names(), notes=notes,
                                             id=msg.id)))
        elif isinstance(msg, P.GetThumbnail):
            svg = await asyncio.to_thread(self._thumbnail, msg.path, msg.example)
            conn.outbox.put(P.encode(P.Thumbnail(svg=svg, path=msg.path, example=msg.example, id=msg.id)))
        elif isinstance(msg, (P.TraceryBuild, P.TracerySave, P.TraceryExport)):
            reply, text, payload = await self._tracery(msg)
            conn.outbox.put(text, payload)
        elif isinstance(msg, P.ListStyles):
            from auszug.studio.tracery import style_files
            from auszug.tracery import builtin_styles

            try:
                ws_styles, notes = await asyncio.to_thread(style_files, self.workspace)
            except OSError as e:
                ws_styles, notes = [], [f"workspace: cannot list it ({e.strerror or e})"]
            lib = builtin_styles()
            conn.outbox.put(P.encode(P.Styles(builtin=list(lib), descriptions=list(lib.values()),
                                              workspace=ws_styles, notes=notes, id=msg.id)))
        elif isinstance(msg, (P.GetMesh, P.GetLoops, P.Export)):
            doc = self._need(conn)
            jobs.put_nowait((msg, doc.snapshot(), doc.label))
        else:  # pragma: no cover - decode only returns the types above
            raise P.ProtocolError(f"unhandled message {type(msg).__name__}")

    @staticmethod
    async def _in_worker(doc: Document, fn: Any, args: tuple) -> None:
        """``doc.change(fn, *args)`` in a worker thread within :attr:`Limits.edit_seconds`.

        Past the budget the change is cancelled: the error is raised at once (the
        sender hears of it), and the document is put back when the thread ends
        (the caller's document lock is held until then, so no change slips in).
        """
        cancel = threading.Event()
        task = asyncio.ensure_future(asyncio.to_thread(doc.change, fn, *args, cancel=cancel))
        budget = LIMITS.edit_seconds
        done, _ = await asyncio.wait({task}, timeout=budget)
        if task in done:
            task.result()
            return
        cancel.set()
        with contextlib.suppress(Exception):
            await task   # rolled back (or it failed anyway)
        raise EditCancelled(f"the change took longer than {budget:g} s and was given up; the drawing is "
                            "unchanged (auszug.limits.LIMITS.edit_seconds)")

    async def _tracery(self, msg: Any) -> tuple[Any, str, bytes | None]:
        """A tracery page message in a worker thread within :attr:`Limits.edit_seconds`.

        A value the style refuses is answered by :class:`~auszug.studio.protocol.TraceryRefused`
        naming it (the page shows it at the field); the server keeps no tracery state, so
        nothing changes. Past the budget the answer is an error (the thread's result is dropped).
        """
        task = asyncio.ensure_future(asyncio.to_thread(self._tracery_encoded, msg))
        budget = LIMITS.edit_seconds
        done, _ = await asyncio.wait({task}, timeout=budget)
        if task not in done:
            raise EditCancelled(f"the window took longer than {budget:g} s to build and was given up; "
                                "nothing changed (auszug.limits.LIMITS.edit_seconds)")
        return task.result()

    def _tracery_encoded(self, msg: Any) -> tuple[Any, str, bytes | None]:
        """:meth:`_tracery_job` and its reply's JSON text, in the worker thread."""
        from auszug.studio.tracery import tracery_text

        reply, payload = self._tracery_job(msg)
        return reply, tracery_text(reply) if isinstance(reply, P.TraceryGeometry) else P.encode(reply), payload

    def _tracery_job(self, msg: Any) -> tuple[Any, bytes | None]:
        from auszug.errors import FormatError
        from auszug.studio import tracery as T
        from auszug.tracery import ParameterError

        label = msg.path or msg.style
        try:
            st = T.window_style(self.workspace, msg.style, msg.path, msg.values)
            if isinstance(msg, P.TraceryBuild):
                return T.build_message(st, msg.style, msg.path, msg.values, msg.id)
            if isinstance(msg, P.TracerySave):
                T.build_message(st, msg.style, msg.path, msg.values)   # only a style that builds is saved
                return P.Saved(path=T.save_style(self.workspace, st, msg.target), id=msg.id), None
            _, _, sub = T.split_values(msg.values)
            name, mime, data = T.export_window(st, msg.format, sub)
            return P.Exported(name=name, mime=mime, size=len(data), id=msg.id), data
        except ParameterError as e:
            return P.TraceryRefused(key=e.name, message=" ".join(f"{label}: {e}".split()), id=msg.id), None
        except FormatError as e:
            return P.TraceryRefused(key="", message=" ".join(str(e).split()), id=msg.id), None

    def _thumbnail(self, path: str, example: str) -> str:
        """The top view of a workspace file or a bundled example as a small SVG (in a worker thread)."""
        from auszug.microarch import build
        from auszug.studio.session import example_drawing, load_drawing
        from auszug.studio.thumbnails import thumbnail_svg

        if bool(path) == bool(example):
            raise P.ProtocolError("get_thumbnail: give exactly one of path and example")
        drawing = example_drawing(example) if example else load_drawing(self.workspace, path)[0]
        return thumbnail_svg(build(drawing))

    @staticmethod
    def _opened(make: Any, *args: Any) -> Document:
        t0 = time.perf_counter()
        doc = make(*args)
        doc.frames()
        doc.slow_edits = time.perf_counter() - t0 > INLINE_EDIT_SECONDS   # its first drag edit goes to a thread
        return doc


def create_app(
    workspace: Path,
    drawing: str | None = None,
    *,
    hosts: Iterable[str] = LOCAL_HOSTS,
    max_message_bytes: int = P.MAX_MESSAGE_BYTES,
    autosave_delay: float = AUTOSAVE_DELAY,
) -> ASGIApp:
    """The studio app for ``workspace``; ``drawing`` (relative to it) opens on connect.

    All connections that open the same workspace file share one document
    (:class:`~auszug.studio.hub.Hub`). The returned app has the hub as
    ``app.hub``; its lifespan shutdown flushes the autosaves.
    """
    studio = _Studio(Workspace(Path(workspace)), drawing, autosave_delay)

    async def socket(ws: WebSocket) -> None:
        await studio.socket(ws, max_message_bytes)

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette):
        try:
            yield
        finally:
            await studio.hub.close()

    static = static_dir()

    async def missing(request: Request) -> Response:
        return PlainTextResponse(
            f"the studio front end is not built (no {static / 'index.html'}); run `{BUILD_COMMAND}` "
            "in the auszug source tree", status_code=503)

    routes: list[Any] = [WebSocketRoute("/ws", socket)]
    if (static / "index.html").is_file():
        routes.append(Mount("/", app=StaticFiles(directory=str(static), html=True)))
    else:
        routes.append(Route("/{path:path}", missing))
    guard = HostOriginGuard(Starlette(routes=routes, lifespan=lifespan), hosts)
    guard.hub = studio.hub
    return guard
