"""Gothic microarchitecture: symmetric top views to 3D ogee curve networks (Segall et al. 2025)."""

from auszug.microarch.model import BasicCurve, Drawing, Segment, Symmetry
from auszug.microarch.network import Network, NetworkCurve, Piece, build

__all__ = ["BasicCurve", "Drawing", "Segment", "Symmetry", "Network", "NetworkCurve", "Piece", "build"]
