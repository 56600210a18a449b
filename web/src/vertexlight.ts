// Lambert shading computed once per vertex, for an unlit material with vertex colours (the tracery page's
// 3D view). On a software WebGL renderer (SwiftShader, llvmpipe) a frame's cost is the fragment shader
// run per pixel; MeshLambertMaterial evaluates its lights there. Shading the vertices on the CPU after
// each edit (a few thousand vertices, well under a millisecond) and drawing unlit with vertex colours
// (shading.ts, vertexColourMaterial) gives the same matte look for a fraction of the fragment cost. The sums are three.js's (r170,
// lights_lambert_pars_fragment): colour = albedo / pi * (hemisphere + sum of max(0, n . l) * light), all
// in linear RGB (three.js encodes to sRGB on output, and treats vertex colours as linear).
// Pure functions over typed arrays; no three.js here.

export type Vec3 = readonly [number, number, number];
export type Rgb = readonly [number, number, number];

/** The lights of a view: colours in linear RGB, already multiplied by their intensities. */
export interface Lighting {
  /** The surface's reflectance (linear RGB, 0..1). */
  albedo: Rgb;
  /** A hemisphere light: `sky` for normals along `up` (a unit vector), `ground` against it, blended between. */
  hemisphere: { up: Vec3; sky: Rgb; ground: Rgb };
  /** Directional lights: `toward` is the unit vector from the surface to the light. */
  directional: readonly { toward: Vec3; color: Rgb }[];
}

/**
 * The colours of the first `nVerts` vertices of unit `normals` (x, y, z per vertex) under `light`,
 * written into `out` (r, g, b per vertex; the rest of `out` is left alone). With `mirrorY` the normals
 * are taken as (x, -y, z): the shading of the same mesh mirrored in the plane y = 0.
 */
export function shadeVertices(normals: Float32Array, nVerts: number, light: Lighting, out: Float32Array, mirrorY = false): void {
  const k = 1 / Math.PI;
  const [ar, ag, ab] = light.albedo;
  const { up, sky, ground } = light.hemisphere;
  const sy = mirrorY ? -1 : 1;
  const dirs = light.directional;
  for (let i = 0; i < 3 * nVerts; i += 3) {
    const nx = normals[i], ny = sy * normals[i + 1], nz = normals[i + 2];
    const w = 0.5 * (nx * up[0] + ny * up[1] + nz * up[2]) + 0.5;
    let r = ground[0] + (sky[0] - ground[0]) * w;
    let g = ground[1] + (sky[1] - ground[1]) * w;
    let b = ground[2] + (sky[2] - ground[2]) * w;
    for (const d of dirs) {
      const c = nx * d.toward[0] + ny * d.toward[1] + nz * d.toward[2];
      if (c > 0) {
        r += c * d.color[0];
        g += c * d.color[1];
        b += c * d.color[2];
      }
    }
    out[i] = k * ar * r;
    out[i + 1] = k * ag * g;
    out[i + 2] = k * ab * b;
  }
}
