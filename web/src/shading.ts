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

const VERTEX = /* glsl */ `
#include <common>
uniform vec3 diffuse;
uniform vec3 skyColor;
uniform vec3 groundColor;
uniform vec3 sunDir;
uniform vec3 sunColor;
uniform vec3 fillDir;
uniform vec3 fillColor;
varying vec3 vColor;
void main() {
  mat4 m = modelMatrix;
#ifdef USE_INSTANCING
  m = m * instanceMatrix;
#endif
  vec3 n = normalize(mat3(m) * normal);
  vec3 irradiance = mix(groundColor, skyColor, 0.5 * n.y + 0.5)
    + max(dot(n, sunDir), 0.0) * sunColor + max(dot(n, fillDir), 0.0) * fillColor;
  vColor = diffuse * irradiance * RECIPROCAL_PI;
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
    uniforms: {
      diffuse: { value: diffuse },
      skyColor: { value: light(LIGHTS.sky.color, LIGHTS.sky.intensity) },
      groundColor: { value: light(LIGHTS.sky.ground, LIGHTS.sky.intensity) },
      sunDir: { value: new THREE.Vector3(...LIGHTS.sun.direction).normalize() },
      sunColor: { value: light(LIGHTS.sun.color, LIGHTS.sun.intensity) },
      fillDir: { value: new THREE.Vector3(...LIGHTS.fill.direction).normalize() },
      fillColor: { value: light(LIGHTS.fill.color, LIGHTS.fill.intensity) },
    },
  });
  (m as THREE.ShaderMaterial & { color: THREE.Color }).color = diffuse;
  return m;
}
