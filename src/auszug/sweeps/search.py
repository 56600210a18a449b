"""The search for movable cuts (paper sec. 1.3): coarse planes, then adaptive refinement.

Round 0 cuts the mesh by the :func:`~auszug.sweeps.planes.initial_planes`. Each plane's energy is
the lowest gliding energy of its movable runs (infinite without one). Every refinement round
takes the good planes, the lowest ``percentile`` % of all planes cut so far (finite energy only),
cuts a ``refine_steps^3`` box in (normal, offset) coordinates around each (half-widths
``angle0 / 2^r`` degrees and ``offset0 / 2^r``, ``r = 0, 1, ...``), skipping planes already cut,
and weighs the new cuts. The result holds every plane and cut of every round; the good planes
and runs are those of the last ranking.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from auszug.sweeps.cut import Cuts, cut
from auszug.sweeps.mesh import SweepMesh
from auszug.sweeps.movability import Movability, movability
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.planes import canonical, initial_planes, refine_box

__all__ = ["PlaneSearch", "search_planes", "good_planes"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class PlaneSearch:
    """Every plane cut by the search, its cuts and their movability.

    Attributes
    ----------
    cuts : Cuts
        All planes of all rounds and their curves.
    movability : Movability
        Alg. 1 on every curve.
    plane_round : (p,) int array
        The round in which each plane was added (0: the initial sampling).
    plane_energy : (p,) float array
        Lowest gliding energy of the plane's runs (inf where none is ``l_min`` long).
    good : (g,) int array
        The good planes after the last round: lowest ``percentile`` % of all planes, by energy.
    good_runs : (h,) int array
        The runs (indices into ``movability``) on good planes whose energy is at most the
        percentile's threshold.
    rounds : tuple of int
        Planes cut per round.
    """

    cuts: Cuts
    movability: Movability
    plane_round: IntArray
    plane_energy: Array
    good: IntArray
    good_runs: IntArray
    rounds: tuple[int, ...]

    @property
    def n_planes(self) -> int:
        """Total number of planes cut."""
        return self.cuts.n_planes


def good_planes(energy: Array, percentile: float) -> tuple[IntArray, float]:
    """Indices of the lowest ``percentile`` % of ``energy`` (of all entries, at least one if any is finite).

    Returns them and the threshold energy (inf if none is finite).

    Examples
    --------
    >>> good_planes(np.array([3.0, 1.0, np.inf, 2.0] * 5), 10.0)
    (array([1, 5]), 1.0)
    """
    k = max(1, int(round(len(energy) * percentile / 100.0)))
    finite = np.flatnonzero(np.isfinite(energy))
    if len(finite) == 0:
        return np.zeros(0, np.int64), float("inf")
    order = finite[np.argsort(energy[finite], kind="stable")]
    keep = np.sort(order[:k]).astype(np.int64)
    return keep, float(energy[order[min(k, len(order)) - 1]])


def _concat_cuts(parts: list[Cuts]) -> Cuts:
    if len(parts) == 1:
        return parts[0]
    plane_base = np.cumsum([0] + [c.n_planes for c in parts])
    point_base = np.cumsum([0] + [len(c.points) for c in parts])
    starts = [c.curve_start[:-1] + b for c, b in zip(parts, point_base, strict=False)]
    return Cuts(
        np.vstack([c.plane_normals for c in parts]),
        np.concatenate([c.plane_offsets for c in parts]),
        np.vstack([c.points for c in parts]),
        np.vstack([c.normals for c in parts]),
        np.concatenate([c.edges for c in parts]),
        np.append(np.concatenate(starts), point_base[-1]).astype(np.int64),
        np.concatenate([c.curve_plane + b for c, b in zip(parts, plane_base, strict=False)]).astype(np.int64),
        np.concatenate([c.curve_closed for c in parts]),
    )


def _concat_mov(parts: list[Movability], cuts: list[Cuts]) -> Movability:
    if len(parts) == 1:
        return parts[0]
    curve_base = np.cumsum([0] + [c.n_curves for c in cuts])
    return Movability(
        np.vstack([m.velocity for m in parts]),
        np.vstack([m.eigenvalues for m in parts]),
        np.concatenate([m.matrices for m in parts]),
        np.concatenate([m.weights for m in parts]),
        np.concatenate([m.f for m in parts]),
        np.concatenate([m.run_curve + b for m, b in zip(parts, curve_base, strict=False)]).astype(np.int64),
        np.concatenate([m.run_start for m in parts]),
        np.concatenate([m.run_end for m in parts]),
        np.concatenate([m.run_length for m in parts]),
        np.concatenate([m.run_energy for m in parts]),
        np.concatenate([m.run_sliding for m in parts]),
    )


def _plane_keys(n: Array, d: Array, q_ang: float, q_off: float) -> Array:
    cn, cd = canonical(n, d)
    return np.column_stack([np.round(cn / q_ang), np.round(cd / q_off)])


def search_planes(mesh: SweepMesh, params: SweepParams = DEFAULT) -> PlaneSearch:
    """Coarse sampling plus ``params.refinements`` rounds of refinement around the good planes.

    Examples
    --------
    >>> from auszug.sweeps.fixtures import extruded
    >>> from auszug.sweeps.mesh import normalise
    >>> fx = extruded(n_profile=30, n_path=30)
    >>> s = search_planes(normalise(fx.vertices, fx.faces), DEFAULT.with_(refinements=1))
    >>> s.rounds[0], s.n_planes == sum(s.rounds), len(s.good) > 0
    (1017, True, True)
    """
    n, d = initial_planes(mesh.vertices, params.sphere_frequency, params.offset_spacing)
    cuts_parts = [cut(mesh, n, d)]
    mov_parts = [movability(cuts_parts[0], params)]
    rounds = [len(d)]
    all_n, all_d = n, d
    energy = mov_parts[0].plane_energy(cuts_parts[0])
    for r in range(params.refinements):
        good, _ = good_planes(energy, params.percentile)
        if len(good) == 0:
            break
        ang, off = params.angle0 / 2**r, params.offset0 / 2**r
        nn, dd = refine_box(all_n[good], all_d[good], ang, off, params.refine_steps)
        q_ang = np.radians(2 * ang / (params.refine_steps - 1)) / 4
        q_off = 2 * off / (params.refine_steps - 1) / 4
        old = _plane_keys(all_n, all_d, q_ang, q_off)
        new = _plane_keys(nn, dd, q_ang, q_off)
        both = np.vstack([old, new])
        _, first = np.unique(both, axis=0, return_index=True)
        fresh = np.sort(first[first >= len(old)] - len(old))
        nn, dd = nn[fresh], dd[fresh]
        if len(dd) == 0:
            break
        c = cut(mesh, nn, dd)
        m = movability(c, params)
        cuts_parts.append(c)
        mov_parts.append(m)
        rounds.append(len(dd))
        all_n, all_d = np.vstack([all_n, nn]), np.concatenate([all_d, dd])
        energy = np.concatenate([energy, m.plane_energy(c)])
    cuts = _concat_cuts(cuts_parts)
    mov = _concat_mov(mov_parts, cuts_parts)
    good, thresh = good_planes(energy, params.percentile)
    is_good = np.zeros(cuts.n_planes, bool)
    is_good[good] = True
    good_runs = np.flatnonzero(is_good[cuts.curve_plane[mov.run_curve]] & (mov.run_energy <= thresh)).astype(np.int64)
    plane_round = np.repeat(np.arange(len(rounds)), rounds).astype(np.int64)
    return PlaneSearch(cuts, mov, plane_round, energy, good, good_runs, tuple(rounds))
