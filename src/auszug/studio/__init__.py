"""The studio: a local web editor for drawings (``auszug studio``).

Python is the single source of geometry: the browser sends edits over a
WebSocket (:mod:`auszug.studio.protocol`), the document they address
(:class:`~auszug.studio.session.Document`, shared by every tab on the same file through
:mod:`auszug.studio.hub`) applies them with :mod:`auszug.microarch.edit`, and the
server (:mod:`auszug.studio.server`) replies with the network's geometry; meshes,
loops and exports come from :mod:`auszug.studio.meshes`. Starlette and uvicorn are
imported only by :mod:`auszug.studio.server` (extra ``auszug[studio]``).
"""

from __future__ import annotations

__all__: list[str] = []
