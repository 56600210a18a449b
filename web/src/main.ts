// The studio: top view (orthographic, left) and 3D perspective (right) of the network.
import * as THREE from "three";
import { Connection, socketUrl } from "./connection";
import { networkObject, replicaCount } from "./geometry";
import { PROTOCOL_VERSION, type Geometry } from "./protocol";

const host = document.getElementById("app")!;
const status = document.getElementById("status")!;

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xf4f1ea);
renderer.setScissorTest(true);
host.appendChild(renderer.domElement);

const scene = new THREE.Scene();
const top = new THREE.OrthographicCamera(-1, 1, 1, -1, -1000, 1000);
top.up.set(0, 1, 0);
const persp = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
persp.up.set(0, 0, 1);
let network: THREE.Group | null = null;
let bounds = new THREE.Box3(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));

function frame(): void {
  const w = host.clientWidth, h = host.clientHeight, half = Math.floor(w / 2);
  renderer.setSize(w, h, false);
  const c = bounds.getCenter(new THREE.Vector3());
  const size = bounds.getSize(new THREE.Vector3());
  const r = 0.55 * Math.max(size.x, size.y, 1e-6);
  const aspect = half / Math.max(h, 1);
  top.left = c.x - r * aspect; top.right = c.x + r * aspect;
  top.bottom = c.y - r; top.top = c.y + r;
  top.position.set(0, 0, bounds.max.z + 10);
  top.lookAt(0, 0, 0);
  top.position.set(0, 0, bounds.max.z + 10);
  top.updateProjectionMatrix();
  const d = 1.6 * Math.max(size.x, size.y, size.z, 1e-6);
  persp.aspect = (w - half) / Math.max(h, 1);
  persp.position.set(c.x + 1.4 * d, c.y - 1.8 * d, c.z + 1.0 * d);
  persp.lookAt(c);
  persp.updateProjectionMatrix();
}

function render(): void {
  frame();
  const w = host.clientWidth, h = host.clientHeight, half = Math.floor(w / 2);
  renderer.setViewport(0, 0, half, h);
  renderer.setScissor(0, 0, half, h);
  renderer.render(scene, top);
  renderer.setViewport(half, 0, w - half, h);
  renderer.setScissor(half, 0, w - half, h);
  renderer.render(scene, persp);
}

function show(msg: Geometry, data: Float32Array): void {
  if (network) scene.remove(network);
  network = networkObject(msg, data);
  scene.add(network);
  const b = msg.bounds;
  bounds = new THREE.Box3(new THREE.Vector3(b[0], b[1], b[2]), new THREE.Vector3(b[3], b[4], b[5]));
  const n = replicaCount(msg);
  status.className = "";
  status.dataset.replicas = String(n);
  status.dataset.revision = String(msg.revision);
  status.textContent = `${msg.path}: ${msg.n_curves} basic curves, ${n} replicas, ` +
    `${msg.intersections.filter((x) => x.true).length} true intersections`;
  if (msg.protocol !== PROTOCOL_VERSION) {
    status.textContent += ` (protocol ${msg.protocol}, client ${PROTOCOL_VERSION}: reload)`;
  }
  render();
}

const conn = new Connection(socketUrl(window.location), {
  geometry: show,
  message(msg) {
    if (msg.type === "error") {
      status.className = "error";
      status.textContent = msg.message;
    } else if (msg.type === "saved") {
      status.textContent = `saved ${msg.path}`;
    }
  },
  closed() {
    status.className = "error";
    status.textContent = "disconnected from the studio server";
  },
});

window.addEventListener("resize", render);
window.addEventListener("keydown", (ev) => {
  if ((ev.ctrlKey || ev.metaKey) && ev.key === "z") conn.send({ type: ev.shiftKey ? "redo" : "undo" });
});
const params = new URLSearchParams(window.location.search);
const open = params.get("open");
if (open) conn.send({ type: "open", path: open });
render();
