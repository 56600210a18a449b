"""Kinematic surfaces: where every cut moves by one and the same motion (rotation, translation, screw).

On a surface of revolution every planar cut glides by the rotation about the axis; on an
extrusion by the translation along it; on a helical surface by the screw motion. There the
question "which plane carries the profile" has no answer (every plane does) and the result is the
motion itself: the axis of a rotation, the direction of a translation, axis and pitch of a screw.

The consensus is the eigenvector of the smallest eigenvalue of ``sum_k A_k / n_k``, the sum of
the cuts' movability matrices (Eq. 4, with the weights of Alg. 1, each cut counted once): the
least-squares motion of all cut points together. Cuts whose residual under it exceeds
``kinematic_trim`` times the median are dropped and the sum is solved again (up to three times).
The score is the share of cuts that glide under that one motion (at least ``kinematic_share`` of
their points with weight above 2/3): near 1 on a kinematic surface, near 0 elsewhere. For
comparison, the median angle between the consensus axis and the axes of the single cuts whose
own velocity state is well determined (second eigenvalue at least ``kinematic_gap`` times the
first; cuts through one cylinder, plane or sphere admit a family of motions) is reported too.
Then
for ``C = (c, c_bar)``:

- ``0.5 |c| <= translation_ratio |c_bar|`` (the rotational part changes the velocity over the
  normalised mesh by less than that share): a translation along ``c_bar``;
- otherwise the axis has direction ``c / |c|`` through ``c x c_bar / |c|^2``, pitch
  ``p = c . c_bar / |c|^2``; a rotation if ``|p| <= pitch_tolerance``, else a screw.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.sweeps.cut import Cuts
from auszug.sweeps.movability import Movability
from auszug.sweeps.params import DEFAULT, SweepParams

__all__ = ["KinematicAxis", "kinematic_axis", "axis_angle", "motion_of"]

Array = NDArray[np.float64]
Kind = Literal["rotation", "translation", "screw"]


@dataclass(frozen=True)
class KinematicAxis:
    """The motion the cuts of a kinematic surface agree on (normalised mesh coordinates).

    Attributes
    ----------
    kind : {"rotation", "translation", "screw"}
    velocity : (6,) float array
        The consensus unit velocity state ``(c, c_bar)``.
    direction : (3,) float array
        Unit axis direction (rotation, screw) or translation direction.
    point : (3,) float array or None
        The axis' point nearest the origin (None for a translation).
    pitch : float
        Translation per radian along the axis (0 for a rotation; inf for a translation).
    voters : int
        Cuts whose own velocity state is well determined.
    agreement : float
        Share of all cuts that glide under the consensus motion.
    median_angle : float
        Median angle (degrees) between those cuts' own axes (or directions) and the consensus'.
    """

    kind: Kind
    velocity: Array
    direction: Array
    point: Array | None
    pitch: float
    voters: int
    agreement: float
    median_angle: float


def axis_angle(a: ArrayLike, b: ArrayLike) -> Array:
    """Angle in degrees between unoriented directions ``(..., 3)``.

    Examples
    --------
    >>> float(axis_angle([0, 0, 1], [0, 0, -2]))
    0.0
    """
    u = np.asarray(a, float)
    v = np.asarray(b, float)
    norms = np.linalg.norm(u, axis=-1) * np.linalg.norm(v, axis=-1)
    c = np.abs(np.sum(u * v, axis=-1)) / np.where(norms > 0, norms, np.inf)
    return np.degrees(np.arccos(np.clip(c, 0.0, 1.0)))


def motion_of(c: ArrayLike, params: SweepParams = DEFAULT) -> tuple[Kind, Array, Array | None, float]:
    """Kind, direction, axis point and pitch of a velocity state ``(6,)``.

    Examples
    --------
    The rotation about the vertical line through (1, 0, 0): ``c_bar = p x c``.

    >>> kind, d, p, h = motion_of(np.r_[0, 0, 1.0, np.cross([1.0, 0, 0], [0, 0, 1.0])])
    >>> kind, d.tolist(), p.tolist(), h
    ('rotation', [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 0.0)
    """
    cc = np.asarray(c, float)
    w, v = cc[:3], cc[3:]
    norm_c = float(np.linalg.norm(w))
    # over the normalised mesh (within 0.5 of the origin) the rotational part changes the
    # velocity by at most 0.5 |c|: below translation_ratio of |c_bar| the motion is a translation
    if 0.5 * norm_c <= params.translation_ratio * float(np.linalg.norm(v)):
        return "translation", v / np.linalg.norm(v), None, float("inf")
    pitch = float(w @ v) / norm_c**2
    point = np.cross(w, v) / norm_c**2
    kind: Kind = "rotation" if abs(pitch) <= params.pitch_tolerance else "screw"
    return kind, w / norm_c, point + 0.0, pitch if kind == "screw" else 0.0


def _moving_share(cuts: Cuts, c: Array, params: SweepParams) -> Array:
    """Per curve, the share of its points that glide (weight above the threshold) under ``c``."""
    v = c[3:] + np.cross(c[:3], cuts.points)
    f = np.einsum("ij,ij->i", cuts.normals, v) ** 2 / (np.einsum("ij,ij->i", v, v) + params.speed_floor**2)
    w = 1.0 / (1.0 + params.beta * f**params.gamma)
    good = (w > params.weight_threshold).astype(float)
    counts = np.diff(cuts.curve_start)
    return np.add.reduceat(good, cuts.curve_start[:-1]) / np.maximum(counts, 1)


def kinematic_axis(cuts: Cuts, mov: Movability, params: SweepParams = DEFAULT) -> KinematicAxis | None:
    """The one motion under which the cuts glide; None for a mesh without cuts.

    Examples
    --------
    >>> from auszug.sweeps import cut, initial_planes, movability, normalise
    >>> from auszug.sweeps.fixtures import revolved
    >>> fx = revolved(n_profile=40, n_path=60)
    >>> m = normalise(fx.vertices, fx.faces)
    >>> c = cut(m, *initial_planes(m.vertices, 3, 0.1))
    >>> k = kinematic_axis(c, movability(c))
    >>> k.kind, round(float(axis_angle(k.direction, fx.axis_direction)), 3), k.agreement > 0.95
    ('rotation', 0.015, True)
    """
    if cuts.n_curves == 0:
        return None
    counts = np.diff(cuts.curve_start).astype(float)
    mats = mov.matrices / np.maximum(counts, 1)[:, None, None]
    use = np.ones(cuts.n_curves, bool)
    best = np.zeros(6)
    for _ in range(3):
        vals, vecs = np.linalg.eigh(mats[use].sum(axis=0))
        best = vecs[:, 0]
        resid = np.einsum("i,kij,j->k", best, mats, best)
        keep = resid <= params.kinematic_trim * max(float(np.median(resid[use])), 1e-300)
        if keep.sum() == 0 or np.array_equal(keep, use):
            break
        use = keep
    kind, direction, point, pitch = motion_of(best, params)
    share = _moving_share(cuts, best, params)
    ev = mov.eigenvalues
    voters = ev[:, 1] >= params.kinematic_gap * np.maximum(ev[:, 0], 1e-300)
    own = mov.velocity[voters, 3:] if kind == "translation" else mov.velocity[voters, :3]
    angles = axis_angle(own, direction) if voters.any() else np.array([np.nan])
    return KinematicAxis(kind, best, direction, point, pitch, int(voters.sum()),
                         float(np.mean(share >= params.kinematic_share)), float(np.nanmedian(angles)))
