"""Sweeps JSON (``.sweeps.json``): the result of sweep analysis (:func:`auszug.sweeps.detect`).

Required keys (more may be added, never removed)::

    {"format": "auszug.sweeps", "version": 1, "source": "moulding.stl",
     "bbox_diameter": 1.0, "coverage": 0.98, "face_coverage": 0.97,
     "patches": [{"id": 0, "kind": "rotation", "closed": false,
                  "profile": [[x, y, z], ...],
                  "motion": [{"t": 0.0, "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
                              "translation": [0, 0, 0]}, ...],
                  "faces": [0, 1, 2, ...], "fit_error": 0.0001, "coverage": 0.98}],
     "centre": [x, y, z], "n_vertices": 7200, "n_faces": 14042,
     "stages": [{"name": "cut", "seconds": 0.5, "summary": "...", "numbers": {...}}, ...],
     "params": {"beta": 400.0, ...}}

Everything is in the input mesh's coordinates. ``profile`` is the profile polyline at the first
motion parameter; ``motion`` the rigid maps ``x -> R x + T`` taking it to its position at ``t``
(identity at the first ``t``; at least 8, ``t`` increasing: the angle in radians for rotations
and screws, the distance in bounding-box diameters for translations, the rib number for general
sweeps); between two maps the motion is the screw between them. A patch may carry the optional
``"profile_fit"``: its profile as exact lines and arcs, ``{"origin": [x, y, z], "axes": [[...], [...],
[...]], "closed": false, "points": [[x, y], ...], "bulges": [b, ...], "hausdorff": h}`` (the
vertices of meshing's ``Profile`` in the plane frame whose columns are ``axes``, one bulge
``tan(angle / 4)`` per segment, ``hausdorff`` over ``bbox_diameter``). ``faces`` are indices into the
mesh's faces (those whose three corners lie within ``eps_prox`` of the patch's swept surface);
``fit_error`` (the largest distance of the swept profile to the mesh) and ``coverage`` are
relative to ``bbox_diameter`` and the mesh's area. The top-level ``coverage`` is the share of the
mesh's area covered (the faces some patch holds whole, and the sampled share of the others within
``eps_prox`` of a patch holding one of their corners: docs/sweeps.md, "Coverage"); the optional
``face_coverage`` is the per-face figure (the area of the union of the patches' ``faces``), and a
patch's ``coverage`` is its ``faces``' share of the area.

Floats are written in their shortest round-trip form, so reading gives back exactly the numbers
that were written (:func:`loads` then :func:`dumps` reproduces the text).
"""

from __future__ import annotations

import math
from dataclasses import fields
from typing import Any

import numpy as np
import orjson

from auszug.errors import FormatError, GeometryError
from auszug.formats._registry import FileFormat, register
from auszug.limits import check_text_size

__all__ = ["FORMAT", "VERSION", "to_dict", "dumps", "loads"]

FORMAT = "auszug.sweeps"
VERSION = 1
KINDS = ("rotation", "translation", "screw", "general")


def _params_dict(params: Any) -> dict[str, Any]:
    out = {}
    for f in fields(params):
        v = getattr(params, f.name)
        out[f.name] = list(v) if isinstance(v, tuple) else v
    return out


def to_dict(report: Any) -> dict[str, Any]:
    """The document of a :class:`auszug.sweeps.SweepReport` as plain Python data."""
    patches = []
    for p in report.patches:
        m = p.motion
        patches.append({
            "id": int(p.id), "kind": p.kind, "closed": bool(p.closed),
            "profile": p.profile.tolist(),
            "motion": [{"t": float(t), "rotation": r.tolist(), "translation": tr.tolist()}
                       for t, r, tr in zip(m.t, m.rotation, m.translation, strict=True)],
            "faces": p.faces.tolist(), "fit_error": float(p.fit_error), "coverage": float(p.coverage)})
        if p.profile_fit is not None:
            fit = p.profile_fit
            patches[-1]["profile_fit"] = {
                "origin": fit.origin.tolist(), "axes": fit.axes.tolist(), "closed": bool(fit.profile.closed),
                "points": fit.profile.points.tolist(), "bulges": fit.profile.bulges.tolist(),
                "hausdorff": float(fit.hausdorff)}
    return {"format": FORMAT, "version": VERSION, "source": report.source,
            "bbox_diameter": float(report.bbox_diameter), "coverage": float(report.coverage),
            **({} if report.face_coverage is None else {"face_coverage": float(report.face_coverage)}),
            "patches": patches,
            "centre": np.asarray(report.centre, float).tolist(), "n_vertices": int(report.n_vertices),
            "n_faces": int(report.n_faces),
            "stages": [{"name": s.name, "seconds": float(s.seconds), "summary": s.summary, "numbers": s.numbers}
                       for s in report.stages],
            "params": _params_dict(report.params)}


def dumps(report: Any) -> str:
    """The JSON text of a report: one patch per line block, floats in shortest round-trip form."""
    return orjson.dumps(to_dict(report), option=orjson.OPT_INDENT_2 | orjson.OPT_SERIALIZE_NUMPY).decode() + "\n"


def _write(obj: Any, name: str) -> str:
    return dumps(obj)


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _array(v: Any, shape: tuple[int | None, ...], where: str, name: str) -> np.ndarray:
    try:
        a = np.array(v, dtype=float)
    except (TypeError, ValueError):
        raise FormatError(f"{where}: expected numbers of shape {_shape(shape)}", name) from None
    if a.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, a.shape, strict=True)):
        raise FormatError(f"{where}: expected shape {_shape(shape)}, got {list(a.shape)}", name)
    if not np.isfinite(a).all():
        raise FormatError(f"{where}: expected finite numbers", name)
    return a


def _shape(shape: tuple[int | None, ...]) -> str:
    return "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"


def _profile_fit(raw: Any, where: str, pid: int, name: str) -> Any:
    """The optional ``profile_fit`` of a patch (None when absent or null)."""
    from auszug.meshing.profile import Profile
    from auszug.sweeps import FittedProfile

    if raw is None:
        return None
    if not isinstance(raw, dict):
        raise FormatError(f"{where}: expected an object or null", name)
    origin = _array(raw.get("origin"), (3,), f"{where}.origin", name)
    axes = _array(raw.get("axes"), (3, 3), f"{where}.axes", name)
    if not np.allclose(axes.T @ axes, np.eye(3), atol=1e-9) or np.linalg.det(axes) < 0:
        raise FormatError(f"{where}.axes: expected orthonormal right-handed columns", name)
    points = _array(raw.get("points"), (None, 2), f"{where}.points", name)
    bulges = _array(raw.get("bulges"), (None,), f"{where}.bulges", name)
    if not isinstance(raw.get("closed"), bool):
        raise FormatError(f"{where}.closed: expected true or false", name)
    if not (_number(raw.get("hausdorff")) and raw["hausdorff"] >= 0):
        raise FormatError(f"{where}.hausdorff: expected a finite number >= 0", name)
    try:
        prof = Profile(points, closed=raw["closed"], name=f"patch {pid}", bulge=bulges)
    except GeometryError as e:
        raise FormatError(f"{where}: {e}", name) from None
    return FittedProfile(origin, axes, prof, float(raw["hausdorff"]))


def loads(text: str | bytes, name: str = "<string>") -> Any:
    """Read a ``.sweeps.json`` document back into a :class:`auszug.sweeps.SweepReport`.

    Raises :class:`~auszug.errors.FormatError` naming the key and what was expected.

    Examples
    --------
    >>> from auszug.sweeps import detect
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=30, n_path=20)
    >>> r = detect((fx.vertices, fx.faces), source="x.stl")
    >>> text = dumps(r)
    >>> back = loads(text)
    >>> dumps(back) == text, back.patches[0].kind, len(back.patches[0].motion) >= 8
    (True, 'translation', True)
    """
    from auszug.sweeps import DEFAULT, Motion, Stage, SweepParams, SweepPatch, SweepReport

    check_text_size(text, name)
    try:
        doc = orjson.loads(text)
    except orjson.JSONDecodeError as e:
        raise FormatError(f"not JSON: {e}", name) from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise FormatError(f"expected a JSON object with \"format\": \"{FORMAT}\"", name)
    if doc.get("version") != VERSION:
        raise FormatError(f"version {doc.get('version')!r}: expected {VERSION}", name)
    for key in ("bbox_diameter", "coverage"):
        if not _number(doc.get(key)):
            raise FormatError(f"{key}: expected a finite number", name)
    if "face_coverage" in doc and not _number(doc["face_coverage"]):
        raise FormatError("face_coverage: expected a finite number", name)
    for key in ("n_vertices", "n_faces"):
        if key in doc and (not isinstance(doc[key], int) or isinstance(doc[key], bool) or doc[key] < 0):
            raise FormatError(f"{key}: expected a whole number >= 0", name)
    if not isinstance(doc.get("source", ""), str):
        raise FormatError("source: expected a string", name)
    raw = doc.get("patches")
    if not isinstance(raw, list):
        raise FormatError("patches: expected a list", name)
    n_faces = doc.get("n_faces")
    patches = []
    for i, p in enumerate(raw):
        where = f"patches[{i}]"
        if not isinstance(p, dict):
            raise FormatError(f"{where}: expected an object", name)
        if p.get("kind", "general") not in KINDS:
            raise FormatError(f"{where}.kind: expected one of {', '.join(KINDS)}, got {p.get('kind')!r}", name)
        if not isinstance(p.get("id"), int) or isinstance(p.get("id"), bool):
            raise FormatError(f"{where}.id: expected an integer", name)
        prof = _array(p.get("profile"), (None, 3), f"{where}.profile", name)
        if len(prof) < 2:
            raise FormatError(f"{where}.profile: expected at least 2 points", name)
        mo = p.get("motion")
        if not isinstance(mo, list) or len(mo) < 2 or not all(isinstance(q, dict) for q in mo):
            raise FormatError(f"{where}.motion: expected a list of at least 2 objects {{t, rotation, translation}}",
                              name)
        t = _array([q.get("t") for q in mo], (None,), f"{where}.motion[].t", name)
        rot = np.stack([_array(q.get("rotation"), (3, 3), f"{where}.motion[{k}].rotation", name)
                        for k, q in enumerate(mo)])
        tr = np.stack([_array(q.get("translation"), (3,), f"{where}.motion[{k}].translation", name)
                       for k, q in enumerate(mo)])
        try:
            motion = Motion(t, rot, tr)
        except GeometryError as e:
            raise FormatError(f"{where}.motion: {e}", name) from None
        faces = p.get("faces")
        if not isinstance(faces, list) or not all(isinstance(f, int) and not isinstance(f, bool) for f in faces):
            raise FormatError(f"{where}.faces: expected a list of face indices", name)
        fa = np.array(faces, dtype=np.int64)
        if len(fa) and (fa.min() < 0 or (isinstance(n_faces, int) and fa.max() >= n_faces)):
            raise FormatError(f"{where}.faces: indices must be in 0..{n_faces}", name)
        for key in ("fit_error", "coverage"):
            if not _number(p.get(key)):
                raise FormatError(f"{where}.{key}: expected a finite number", name)
        patches.append(SweepPatch(p["id"], p.get("kind", "general"), prof, bool(p.get("closed", False)), motion, fa,
                                  float(p["fit_error"]), float(p["coverage"]),
                                  _profile_fit(p.get("profile_fit"), f"{where}.profile_fit", p["id"], name)))
    raw_stages = doc.get("stages", [])
    if not isinstance(raw_stages, list):
        raise FormatError("stages: expected a list", name)
    stages = []
    for i, st in enumerate(raw_stages):
        if not (isinstance(st, dict) and _number(st.get("seconds", 0.0)) and isinstance(st.get("numbers", {}), dict)):
            raise FormatError(f"stages[{i}]: expected an object with a number \"seconds\" and an object "
                              "\"numbers\"", name)
        stages.append(Stage(str(st.get("name", "")), float(st.get("seconds", 0.0)), str(st.get("summary", "")),
                            dict(st.get("numbers", {}))))
    params = DEFAULT
    if isinstance(doc.get("params"), dict):
        known = {f.name for f in fields(SweepParams)}
        given: dict[str, Any] = {k: (tuple(v) if isinstance(v, list) else v) for k, v in doc["params"].items()
                                 if k in known}
        try:
            params = SweepParams(**given)
        except (GeometryError, TypeError) as e:
            raise FormatError(f"params: {e}", name) from None
    centre = _array(doc.get("centre", [0.0, 0.0, 0.0]), (3,), "centre", name)
    return SweepReport(tuple(patches), float(doc["coverage"]), float(doc["bbox_diameter"]), centre,
                       int(doc.get("n_vertices", 0)), int(n_faces) if isinstance(n_faces, int) else 0, tuple(stages),
                       params, doc.get("source", ""),
                       float(doc["face_coverage"]) if "face_coverage" in doc else None)


register(FileFormat("sweeps", (".sweeps.json",), "sweeps", reader=loads, writer=_write))
