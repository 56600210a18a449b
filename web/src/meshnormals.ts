// Vertex normals of the first `nTris` triangles of an indexed mesh, written into `out` (the first `nVerts`
// vertices): the area-weighted sum of the faces' normals, normalised. The tracery page's 3D view keeps
// its buffers between edits (larger than the mesh, the rest unused), so three.js's
// computeVertexNormals, which runs over the whole buffers, does not fit.

export function vertexNormals(pos: Float32Array, idx: Uint32Array, nVerts: number, nTris: number, out: Float32Array): void {
  out.fill(0, 0, 3 * nVerts);
  for (let t = 0; t < 3 * nTris; t += 3) {
    const a = 3 * idx[t], b = 3 * idx[t + 1], c = 3 * idx[t + 2];
    const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
    const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    out[a] += nx; out[a + 1] += ny; out[a + 2] += nz;
    out[b] += nx; out[b + 1] += ny; out[b + 2] += nz;
    out[c] += nx; out[c + 1] += ny; out[c + 2] += nz;
  }
  for (let i = 0; i < 3 * nVerts; i += 3) {
    const l = Math.hypot(out[i], out[i + 1], out[i + 2]);
    if (l > 0) {
      out[i] /= l; out[i + 1] /= l; out[i + 2] /= l;
    } else {
      out[i + 2] = 1; // a vertex of no (or only degenerate) triangles: any unit normal
    }
  }
}
