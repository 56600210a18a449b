"""Edit a drawing in the browser: a local server with the studio's 3D editor.

The server binds 127.0.0.1 only and refuses pages from other hosts. Drawings
are opened and saved inside the workspace folder (default: the drawing's
folder, else the current folder). Stop it with Ctrl+C.

examples:
  auszug studio tn-11.uc
  auszug studio --workspace drawings/ --port 8765 --no-browser
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from auszug.cli import _common

if TYPE_CHECKING:  # pragma: no cover
    import socket

    import uvicorn

HELP = "edit a drawing in the browser (local 3D studio)"

DEFAULT_PORT = 8765


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug studio``."""
    parser.add_argument("drawing", metavar="DRAWING", nargs="?", help="a drawing file to open (.uc, .json)")
    parser.add_argument("--port", type=_common.at_least(0), default=DEFAULT_PORT,
                        help=f"port on 127.0.0.1 (default {DEFAULT_PORT}; 0: any free port)")
    parser.add_argument("--workspace", metavar="DIR", type=Path, default=None,
                        help="folder the studio may open and save drawings in "
                             "(default: the drawing's folder, else the current folder)")
    parser.add_argument("--no-browser", action="store_true", help="do not open a browser")


def resolve_paths(drawing: str | None, workspace: Path | None) -> tuple[Path, str | None]:
    """The workspace folder and the drawing relative to it; refuses a drawing outside it."""
    from auszug.errors import AuszugError

    if workspace is None:
        workspace = Path(drawing).resolve().parent if drawing else Path.cwd()
    workspace = workspace.resolve()
    if not workspace.is_dir():
        raise AuszugError(f"{workspace}: the workspace must be an existing folder")
    if drawing is None:
        return workspace, None
    p = Path(drawing).resolve()
    if not p.is_file():
        raise AuszugError(f"{drawing}: no such file")
    if workspace not in p.parents:
        raise AuszugError(f"{drawing}: the drawing must lie inside the workspace {workspace}")
    return workspace, p.relative_to(workspace).as_posix()


def bind_local(port: int) -> "socket.socket":
    """A listening TCP socket on 127.0.0.1:``port`` (0: any free port) for uvicorn.

    TCP_NODELAY is set (accepted connections inherit it), and the socket says
    it is TCP so asyncio sets it on every connection too: otherwise the binary
    frame that follows each geometry message waits for the browser's delayed
    ACK, and every edit takes 40 ms more.

    Raises
    ------
    OSError
        If the port cannot be bound.
    """
    import socket

    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        sock.bind(("127.0.0.1", port))
        sock.listen(128)
    except OSError:
        sock.close()
        raise
    return sock


def server_config(app: Any, *, lifespan: Literal["auto", "on", "off"] = "on") -> "uvicorn.Config":
    """The uvicorn configuration the studio runs with (the CLI, benchmarks and tests share it).

    WebSocket compression (permessage-deflate) is off: on 127.0.0.1 it only costs time,
    about 0.2 ms to compress a reply's frame on the server and as long to inflate it in
    the browser.
    ``lifespan="on"`` lets shutdown flush pending autosaves.
    """
    import uvicorn

    from auszug.studio import protocol

    return uvicorn.Config(app, log_level="warning", ws_max_size=4 * protocol.MAX_MESSAGE_BYTES,
                          ws_ping_interval=20, ws_per_message_deflate=False, lifespan=lifespan)


def run(args: argparse.Namespace) -> int:
    """Start the server and serve until interrupted."""
    import threading
    import webbrowser

    import uvicorn

    from auszug.errors import AuszugError
    from auszug.studio.server import BUILD_COMMAND, create_app, static_dir

    workspace, rel = resolve_paths(args.drawing, args.workspace)
    if not (static_dir() / "index.html").is_file():
        raise AuszugError(f"the studio front end is not built ({static_dir()} has no index.html): "
                          f"run `{BUILD_COMMAND}` in the auszug source tree")
    try:
        sock = bind_local(args.port)
    except OSError as e:
        raise AuszugError(f"cannot listen on 127.0.0.1:{args.port} ({e.strerror}); try --port 0") from None
    port = sock.getsockname()[1]
    url = f"http://127.0.0.1:{port}/"
    app = create_app(workspace, rel)
    server = uvicorn.Server(server_config(app))
    print(f"auszug studio: {url}  (workspace {workspace}; Ctrl+C stops)", file=sys.stderr, flush=True)
    if not args.no_browser:
        threading.Timer(0.5, webbrowser.open, args=(url,)).start()
    server.run(sockets=[sock])
    return 0
