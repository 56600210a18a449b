"""Up-front work limits of the mesh stages, checked before the work starts.

The members, the faces and the solid of a drawing grow with its fold, its
curves and the sampling (``segments`` along a member, points ``around`` the
profile, boundary points per face): a fold-1024 drawing took 5.2 GB and 188 s
for ``--faces auto`` at fold 256 already, and ``--segments 10000`` on it ran
out of memory. These checks estimate the size of each stage's output from
quantities known before it runs and refuse, with the limit and what to
lower, anything beyond :attr:`~auszug.limits.Limits.mesh_triangles` (output
triangles) or :attr:`~auszug.limits.Limits.face_solid_curves` (network curves
that the face search and the solid's union compare pairwise).
"""

from __future__ import annotations

from typing import Any

from auszug.errors import DrawingError
from auszug.limits import LIMITS

__all__ = ["curve_count", "check_curves", "check_triangles", "member_triangles", "face_triangles",
           "TRIANGLES_PER_FACE_POINT2"]

#: Triangles of a minimal-surface face per squared boundary point: a face of ``resolution``
#: boundary points has about ``0.1 resolution**2`` triangles (measured: 940 at 96 on
#: tn-2's faces, 0.102; see docs/limits.md).
TRIANGLES_PER_FACE_POINT2 = 0.1


def curve_count(network: Any) -> int:
    """Curves of the network, every replica counted (what the stages mesh one by one)."""
    from auszug.geometry.network import as_curve_network

    cn = as_curve_network(network)
    return sum(len(cn.group(p.basic)[1]) for p in cn.pieces)


def check_curves(network: Any, stage: str) -> int:
    """Refuse a network of more curves than :attr:`~auszug.limits.Limits.face_solid_curves` for ``stage``.

    Returns
    -------
    int
        The number of network curves.

    Raises
    ------
    DrawingError
        Naming the stage, the count and the limit.
    """
    n = curve_count(network)
    if n > LIMITS.face_solid_curves:
        raise DrawingError(f"{stage} of a network of {n} curves is above the limit of {LIMITS.face_solid_curves} "
                           "curves (auszug.limits.LIMITS.face_solid_curves): its work grows with the square of "
                           "the curves; use a lower fold or fewer curves")
    return n


def member_triangles(n_curves: int, steps: int, around: int) -> int:
    """Triangles of the swept members: two per profile edge and step, per curve (caps aside)."""
    return 2 * n_curves * steps * around


def face_triangles(n_faces: int, resolution: int) -> int:
    """Estimated triangles of ``n_faces`` minimal-surface faces of ``resolution`` boundary points."""
    return int(n_faces * TRIANGLES_PER_FACE_POINT2 * resolution * resolution)


def check_triangles(n: int, what: str, lower: str) -> None:
    """Refuse an estimated ``n`` output triangles above :attr:`~auszug.limits.Limits.mesh_triangles`.

    Raises
    ------
    DrawingError
        ``"{what} would have about {n} triangles, above the limit ...; use {lower}"``.
    """
    if n > LIMITS.mesh_triangles:
        raise DrawingError(f"{what} would have about {n:,} triangles, above the limit of {LIMITS.mesh_triangles:,} "
                           f"(auszug.limits.LIMITS.mesh_triangles); use {lower}")
