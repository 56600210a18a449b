// The lights of the 3D view, and the members' material: diffuse light computed per vertex
// (Gouraud), so a fragment costs one interpolated colour. On a software renderer (headless
// chromium's SwiftShader) three.js' MeshStandardMaterial made a frame of U.XI.28's tubes cost
// 75-180 ms (its per-pixel PBR shading); members are thin tubes, bars and ribbons seen from a
// distance, where per-vertex diffuse light looks the same (bench_studio.py, benchmarks/RESULTS.md).
import * as THREE from "three";

/** The scene's lights: a sky light (three.js' hemisphere, its up along +y) and two directional
 * lights (directions towards the light), intensities as three.js counts them. */
export const LIGHTS = {
  sky: { color: 0xffffff, ground: 0xb8b0a0, intensity: 1.6 },
  sun: { color: 0xffffff, intensity: 1.5, direction: [0.6, -1, 1.6] },
  fill: { color: 0xffffff, intensity: 0.6, direction: [-1, 0.8, 0.4] },
} as const;

/** The lights as three.js objects (added to the scene by Views). */
export function sceneLights(): THREE.Light[] {
  const sky = new THREE.HemisphereLight(LIGHTS.sky.color, LIGHTS.sky.ground, LIGHTS.sky.intensity);
  const sun = new THREE.DirectionalLight(LIGHTS.sun.color, LIGHTS.sun.intensity);
  sun.position.set(...LIGHTS.sun.direction);
  const fill = new THREE.DirectionalLight(LIGHTS.fill.color, LIGHTS.fill.intensity);
  fill.position.set(...LIGHTS.fill.direction);
  return [sky, sun, fill];
}

// The lights' uniforms (lightUniforms) and the irradiance they give a unit normal, for both shaders.
const LIGHTING = /* glsl */ `
uniform vec3 diffuse;
uniform vec3 skyColor;
uniform vec3 groundColor;
uniform vec3 sunDir;
uniform vec3 sunColor;
uniform vec3 fillDir;
uniform vec3 fillColor;
vec3 irradiance(vec3 n) {
  return mix(groundColor, skyColor, 0.5 * n.y + 0.5)
    + max(dot(n, sunDir), 0.0) * sunColor + max(dot(n, fillDir), 0.0) * fillColor;
}`;

const VERTEX = /* glsl */ `
#include <common>
${LIGHTING}
varying vec3 vColor;
void main() {
  mat4 m = modelMatrix;
#ifdef USE_INSTANCING
  m = m * instanceMatrix;
#endif
  vec3 n = normalize(mat3(m) * normal);
  vColor = diffuse * irradiance(n) * RECIPROCAL_PI;
  gl_Position = projectionMatrix * viewMatrix * m * vec4(position, 1.0);
}`;

const FRAGMENT = /* glsl */ `
varying vec3 vColor;
void main() {
  gl_FragColor = vec4(vColor, 1.0);
#include <colorspace_fragment>
}`;

/** A colour scaled by an intensity (linear, as three.js' lights add up). */
function light(color: number, intensity: number): THREE.Color {
  return new THREE.Color(color).multiplyScalar(intensity);
}

/**
 * A member material of colour `color` lit by LIGHTS per vertex (Lambert's diffuse term, as
 * three.js' physically based lights give it). `color` is exposed as `.color` (like three.js'
 * materials), so tests and the page read a material's colour the same way.
 */
export function memberMaterial(color: THREE.ColorRepresentation, side: THREE.Side = THREE.FrontSide): THREE.ShaderMaterial {
  const diffuse = new THREE.Color(color);
  const m = new THREE.ShaderMaterial({
    vertexShader: VERTEX,
    fragmentShader: FRAGMENT,
    side,
    uniforms: lightUniforms(diffuse),
  });
  (m as THREE.ShaderMaterial & { color: THREE.Color }).color = diffuse;
  return m;
}

// A tube drawn as a strip along its axis (tubes.ts: each station twice, with the axis' unit
// tangent and a signed offset of one radius): the vertex shader moves each vertex by its offset
// along s, the unit normal to the tangent and to the line of sight (towards the camera, or the
// orthographic camera's axis), so the strip always faces the camera and is as wide as the tube.
// A round tube's normal across it runs from -s over f (towards the camera, normal to the axis)
// to +s; the vertex shader lights those three normals with the lights of memberMaterial and
// converts them to sRGB (the renderer's output), and the fragment shader only interpolates them
// quadratically across the strip (u from -1 to 1): a fragment costs a few multiply-adds, as a
// software renderer pays per pixel (no light or colour-space power per pixel).
const STRIP_VERTEX = /* glsl */ `
#include <common>
#include <colorspace_pars_fragment>
attribute vec3 axisTangent;
attribute float across;
${LIGHTING}
varying vec3 vMinus;
varying vec3 vMid;
varying vec3 vPlus;
varying float vU;
vec3 shade(vec3 n) {
  return sRGBTransferOETF(vec4(diffuse * irradiance(n) * RECIPROCAL_PI, 1.0)).rgb;
}
void main() {
  mat4 m = modelMatrix;
#ifdef USE_INSTANCING
  m = m * instanceMatrix;
#endif
  vec3 p = (m * vec4(position, 1.0)).xyz;
  vec3 t = normalize(mat3(m) * axisTangent);
  vec3 e = isOrthographic ? vec3(viewMatrix[0][2], viewMatrix[1][2], viewMatrix[2][2]) : normalize(cameraPosition - p);
  vec3 s = cross(t, e);
  float ls = length(s);
  // seen along its axis: any normal to the tangent
  s = ls > 1e-6 ? s / ls : normalize(cross(t, abs(t.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vMinus = shade(-s);
  vMid = shade(cross(s, t));
  vPlus = shade(s);
  vU = sign(across);
  gl_Position = projectionMatrix * viewMatrix * vec4(p + across * s, 1.0);
}`;

const STRIP_FRAGMENT = /* glsl */ `
varying vec3 vMinus;
varying vec3 vMid;
varying vec3 vPlus;
varying float vU;
void main() {
  float u = vU;
  gl_FragColor = vec4(vMid + 0.5 * u * (vPlus - vMinus) + u * u * (0.5 * (vPlus + vMinus) - vMid), 1.0);
}`;

/** The uniforms of a member of colour `diffuse` lit by LIGHTS. */
function lightUniforms(diffuse: THREE.Color): Record<string, THREE.IUniform> {
  return {
    diffuse: { value: diffuse },
    skyColor: { value: light(LIGHTS.sky.color, LIGHTS.sky.intensity) },
    groundColor: { value: light(LIGHTS.sky.ground, LIGHTS.sky.intensity) },
    sunDir: { value: new THREE.Vector3(...LIGHTS.sun.direction).normalize() },
    sunColor: { value: light(LIGHTS.sun.color, LIGHTS.sun.intensity) },
    fillDir: { value: new THREE.Vector3(...LIGHTS.fill.direction).normalize() },
    fillColor: { value: light(LIGHTS.fill.color, LIGHTS.fill.intensity) },
  };
}

/**
 * The material of the page's drag tubes (tubes.ts): strips turned to the camera and shaded as
 * round tubes of colour `color`, lit by LIGHTS as memberMaterial lights the server's tubes, for
 * the renderer's default sRGB output.
 * Seen from both sides (a strip faces the camera whatever its instance's handedness). `color`
 * is exposed as `.color`.
 */
export function tubeStripMaterial(color: THREE.ColorRepresentation): THREE.ShaderMaterial & { color: THREE.Color } {
  const diffuse = new THREE.Color(color);
  const m = new THREE.ShaderMaterial({
    vertexShader: STRIP_VERTEX,
    fragmentShader: STRIP_FRAGMENT,
    side: THREE.DoubleSide,
    uniforms: lightUniforms(diffuse),
  }) as THREE.ShaderMaterial & { color: THREE.Color };
  m.color = diffuse;
  return m;
}

const VERTEX_COLOUR_VERTEX = /* glsl */ `
#include <common>
#include <colorspace_pars_fragment>
varying vec3 vColor;
void main() {
  vColor = sRGBTransferOETF(vec4(color, 1.0)).rgb;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const VERTEX_COLOUR_FRAGMENT = /* glsl */ `
varying vec3 vColor;
void main() {
  gl_FragColor = vec4(vColor, 1.0);
}`;

/**
 * Unlit, with the vertices' colours (linear RGB, as three.js takes vertex colours), encoded to sRGB
 * (the renderer's default output) per vertex and interpolated in sRGB: three.js' MeshBasicMaterial
 * encodes per pixel (a power per channel), which a software renderer pays for every pixel of a
 * frame. For the tracery page's view, whose vertex colours are its lighting (vertexlight.ts).
 */
export function vertexColourMaterial(side: THREE.Side = THREE.FrontSide): THREE.ShaderMaterial {
  return new THREE.ShaderMaterial({
    vertexShader: VERTEX_COLOUR_VERTEX,
    fragmentShader: VERTEX_COLOUR_FRAGMENT,
    vertexColors: true,
    side,
  });
}
