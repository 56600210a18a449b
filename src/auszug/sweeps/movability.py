"""Movability of cut curves within the surface (paper sec. 1.1-1.2, Eq. 3-5, Alg. 1).

A velocity state ``C = (c, c_bar)`` moves a point ``x`` with ``x_dot = c_bar + c x x`` (Eq. 2).
A curve with vertices ``x_i`` and surface normals ``n_i`` moves within the surface if every
``n_i . x_dot_i = 0`` (Eq. 3); the weighted least-squares solution under ``||C|| = 1`` is the
eigenvector of the smallest eigenvalue of ``A = sum w_i a_i a_i^T``, ``a_i = (x_i x n_i, n_i)``
(Eq. 4). ``f_i = cos^2 angle(x_dot_i, n_i)`` (Eq. 5) is the movability of a vertex; Alg. 1
re-weights ``w_i = 1 / (1 + beta f_i^gamma)`` and refits, and the runs of vertices with weight
above 2/3 are the movable parts, each with its gliding energy
``E = mean over the run of (1 - w_i)^2 f_i``.

Choices where the paper is silent (both parameters, both documented in docs/sweeps.md):
a stretch of low weight no longer than ``gap`` of arc length between two movable stretches is
bridged (one noisy vertex must not cut a profile in two), and a run whose velocity slides it
along itself (more than ``max_sliding`` of its squared speed along its own tangent) is dropped:
every helix, and over a short length every smooth curve, glides within any surface that contains
it by moving along itself, which is no evidence of a sweep. A run that is a whole closed cut is kept all the
same when another velocity state glides it with little sliding (``loop_sliding``; a loop slides
along itself only by turning in its plane): the least sliding share plus mean
movability, in units of the threshold's, over all velocity states is at most ``loop_sliding``
(a coarse closed cut nearly glides under the turn in its own plane too, and Eq. 4's eigenvector
is any mix of that turn and the motions out of the plane). And a run whose normals hardly turn (the second eigenvalue
of their mean ``n n^T`` below ``min_spread``) lies in a nearly flat strip, where every in-plane
motion glides: dropped too.

A third: Eq. 5 divides by ``|x_dot_i|^2``, which makes ``f_i`` pure noise where a vertex barely
moves (near a rotation axis). We divide by ``|x_dot_i|^2 + speed_floor^2`` (``speed_floor = 0``
is Eq. 5 as printed, with ``f_i = 0`` where ``x_dot_i = 0``).
Closed cuts are handled as cycles: a run may wrap around the loop's start (the paper's
implementation does not handle closed profiles).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.sweeps import _kernels
from auszug.sweeps.cut import Cuts
from auszug.sweeps.params import DEFAULT, SweepParams

__all__ = ["Movability", "velocity_state", "movability", "velocities"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class Movability:
    """The weight iteration's result on every curve of a :class:`~auszug.sweeps.cut.Cuts`.

    Attributes
    ----------
    velocity : (c, 6) float array
        Per curve, the unit velocity state ``(c, c_bar)`` of its last fit (sign arbitrary).
    eigenvalues : (c, 6) float array
        Per curve, the eigenvalues of ``A`` in the last fit, ascending (``[:, 0] = min F``).
    matrices : (c, 6, 6) float array
        Per curve, the matrix ``A`` of its last fit (the weights of that fit).
    weights : (N,) float array
        Per cut point, its final weight.
    f : (N,) float array
        Per cut point, its movability ``f_i`` under the final velocity state.
    run_curve : (r,) int array
        The curve of each movable run (runs shorter than ``l_min`` are dropped).
    run_start, run_end : (r,) int array
        First and last vertex of the run, indices into its curve (``end < start``: it wraps
        around a closed curve).
    run_length : (r,) float array
        Arc length of the run.
    run_energy : (r,) float array
        Its gliding energy.
    run_sliding : (r,) float array
        Share of the run's (weighted) squared speed along the curve's own tangent; where that is
        more than ``max_sliding`` on a whole closed cut, the least sliding share plus mean
        movability over all velocity states where that is at most ``loop_sliding``.
    """

    velocity: Array
    eigenvalues: Array
    matrices: Array
    weights: Array
    f: Array
    run_curve: IntArray
    run_start: IntArray
    run_end: IntArray
    run_length: Array
    run_energy: Array
    run_sliding: Array

    @property
    def n_runs(self) -> int:
        """Number of movable runs."""
        return len(self.run_curve)

    def run_indices(self, cuts: Cuts, r: int) -> IntArray:
        """Indices into ``cuts.points`` of the vertices of run ``r``, in order."""
        k = int(self.run_curve[r])
        a, b = int(cuts.curve_start[k]), int(cuts.curve_start[k + 1])
        i0, i1 = int(self.run_start[r]), int(self.run_end[r])
        local = np.arange(i0, i1 + 1) if i1 >= i0 else np.concatenate([np.arange(i0, b - a), np.arange(0, i1 + 1)])
        return a + local

    def plane_energy(self, cuts: Cuts) -> Array:
        """Per plane ``(p,)``: the lowest gliding energy of its runs (inf where it has none)."""
        out = np.full(cuts.n_planes, np.inf)
        np.minimum.at(out, cuts.curve_plane[self.run_curve], self.run_energy)
        return out


def velocities(c: ArrayLike, points: ArrayLike) -> Array:
    """Velocities ``c_bar + c x x`` ``(n, 3)`` of points under velocity states ``(6,)`` or ``(n, 6)``.

    Examples
    --------
    >>> velocities([0, 0, 1, 0, 0, 0], [[1.0, 0, 0]]).tolist()
    [[0.0, 1.0, 0.0]]
    """
    cc = np.asarray(c, float)
    x = np.asarray(points, float)
    return cc[..., 3:] + np.cross(cc[..., :3], x)


def velocity_state(points: ArrayLike, normals: ArrayLike, weights: ArrayLike | None = None) -> tuple[Array, Array]:
    """The unit velocity state ``(6,)`` minimising Eq. 4, and the eigenvalues ``(6,)`` of ``A``.

    Examples
    --------
    A wavy curve on a cone about the z axis moves by the rotation about z only:

    >>> t = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    >>> rho = 0.3 + 0.05 * np.sin(3 * t)
    >>> x = np.column_stack([rho * np.cos(t), rho * np.sin(t), rho / 2])
    >>> n = np.column_stack([np.cos(t), np.sin(t), -0.5 + 0 * t])
    >>> c, lam = velocity_state(x, n)
    >>> bool(lam[0] < 1e-14 < 1e-3 < lam[1]), np.round(np.abs(c), 9).tolist()
    (True, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    """
    x = np.asarray(points, float)
    n = np.asarray(normals, float)
    w = np.ones(len(x)) if weights is None else np.asarray(weights, float)
    a = np.hstack([np.cross(x, n), n])
    vals, vecs = np.linalg.eigh((a * w[:, None]).T @ a)
    return vecs[:, 0], vals


def movability(cuts: Cuts, params: SweepParams = DEFAULT) -> Movability:
    """Alg. 1 on every curve of ``cuts`` (one compiled parallel pass), then its movable runs.

    Examples
    --------
    Every cut of an extrusion moves (by the translation along it):

    >>> from auszug.sweeps.fixtures import extruded
    >>> from auszug.sweeps.mesh import normalise
    >>> from auszug.sweeps.cut import cut
    >>> fx = extruded(n_profile=40, n_path=40)
    >>> m = movability(cut(normalise(fx.vertices, fx.faces), [[0.8, 0, 0.6]], [0.0]))
    >>> m.n_runs, bool(m.run_energy[0] < 1e-20), np.round(np.abs(m.velocity[0]), 6).tolist()
    (1, True, [0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
    """
    cs, ev, w, f, mats = _kernels.weight_iteration(cuts.points, cuts.normals, cuts.curve_start, float(params.beta),
                                             float(params.gamma), int(params.iterations),
                                             float(params.speed_floor))
    # the movability at which Alg. 1's weight falls to the threshold: the unit of loop_sliding's mean f
    f_star = ((1.0 / params.weight_threshold - 1.0) / params.beta) ** (1.0 / params.gamma)
    rc, r0, r1, rl, re, rs = _kernels.movable_runs(
        cuts.points, cuts.normals, w, f, cs, cuts.curve_start, cuts.curve_closed, float(params.weight_threshold),
        float(params.l_min), float(params.gap), float(params.max_sliding), float(params.min_spread),
        float(f_star), float(params.loop_sliding))
    return Movability(cs, ev, mats, w, f, rc, r0, r1, rl, re, rs)
