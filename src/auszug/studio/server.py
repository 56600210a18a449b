"""The studio's ASGI app (Starlette): static front end + one WebSocket endpoint.

Security, for a server that edits files on the user's machine:

- it is meant to bind 127.0.0.1 only (the CLI does);
- every HTTP and WebSocket request whose ``Host`` or ``Origin`` names another
  host is refused (403 / close 1008): this defeats DNS rebinding, where a
  foreign page's domain resolves to 127.0.0.1;
- drawings are opened and saved only inside the workspace folder;
- client messages larger than :data:`~auszug.studio.protocol.MAX_MESSAGE_BYTES`
  are refused with an error reply;
- a malformed message or a failing edit gets an :class:`~auszug.studio.protocol.Error`
  reply and the connection stays open.
"""

from __future__ import annotations

import asyncio
import logging
import os
from importlib.resources import files
from pathlib import Path
from typing import Any, Iterable
from urllib.parse import urlsplit

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import PlainTextResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from auszug.errors import AuszugError
from auszug.studio import protocol as P
from auszug.studio.session import Session, Workspace

__all__ = ["LOCAL_HOSTS", "BUILD_COMMAND", "static_dir", "create_app", "HostOriginGuard"]

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

    def _allowed(self, scope: Scope) -> bool:
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])}
        host = headers.get("host")
        if host is None or _hostname(host) not in self.hosts:
            return False
        origin = headers.get("origin")
        if origin is not None:  # browsers always send it on WebSockets and cross-origin requests
            try:
                parts = urlsplit(origin)
            except ValueError:
                return False
            if parts.scheme not in ("http", "https") or parts.hostname not in self.hosts:
                return False
        return True

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket") and not self._allowed(scope):
            if scope["type"] == "websocket":
                await send({"type": "websocket.close", "code": 1008, "reason": "foreign host or origin"})
            else:
                await PlainTextResponse("foreign host or origin", status_code=403)(scope, receive, send)
            return
        await self.app(scope, receive, send)


async def _reply(ws: WebSocket, msg: Any, payload: bytes | None = None) -> None:
    await ws.send_text(P.encode(msg))
    if payload is not None:
        await ws.send_bytes(payload)


def _handle(session: Session, msg: Any) -> tuple[Any, bytes | None]:
    """Carry out one decoded message (blocking: runs in a worker thread)."""
    if isinstance(msg, P.Open):
        session.open(msg.path)
    elif isinstance(msg, P.Save):
        return P.Saved(path=session.save(msg.path), id=msg.id), None
    elif isinstance(msg, P.Undo):
        session.undo()
    elif isinstance(msg, P.Redo):
        session.redo()
    elif isinstance(msg, P.EditOp):
        session.apply(msg)
    else:  # pragma: no cover - decode only returns the types above
        raise P.ProtocolError(f"unhandled message {type(msg).__name__}")
    return session.geometry(msg_id=msg.id)


def create_app(
    workspace: Path,
    drawing: str | None = None,
    *,
    hosts: Iterable[str] = LOCAL_HOSTS,
    max_message_bytes: int = P.MAX_MESSAGE_BYTES,
) -> ASGIApp:
    """The studio app for ``workspace``; ``drawing`` (relative to it) opens on connect.

    Each WebSocket connection gets its own :class:`Session`.
    """
    ws_root = Workspace(Path(workspace))

    async def socket(ws: WebSocket) -> None:
        await ws.accept()
        session = Session(ws_root)
        if drawing:
            try:
                await asyncio.to_thread(session.open, drawing)
                await _reply(ws, *session.geometry())
            except AuszugError as e:
                await _reply(ws, P.Error(message=str(e)))
        while True:
            try:
                event = await ws.receive()
            except WebSocketDisconnect:
                return
            if event["type"] == "websocket.disconnect":
                return
            data = event.get("text")
            if data is None:
                data = event.get("bytes") or b""
            if len(data) > max_message_bytes:
                await _reply(ws, P.Error(message=f"message of {len(data)} bytes is larger than the "
                                         f"limit of {max_message_bytes} bytes"))
                continue
            msg_id = 0
            try:
                msg = P.decode(data)
                msg_id = msg.id
                reply, payload = await asyncio.to_thread(_handle, session, msg)
            except AuszugError as e:
                reply, payload = P.Error(message=str(e), id=msg_id), None
            except OSError as e:
                reply, payload = P.Error(message=f"{e.strerror or e}", id=msg_id), None
            except Exception as e:  # noqa: BLE001 - a bug in one edit must not kill the session
                log.exception("studio: message failed")
                reply, payload = P.Error(message=f"internal error: {type(e).__name__}: {e}", id=msg_id), None
            await _reply(ws, reply, payload)

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
    return HostOriginGuard(Starlette(routes=routes), hosts)
