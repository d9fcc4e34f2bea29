// banyan viewer: shows one banyan .glb (drag and drop, the Open button or
// ?file=URL, optionally &colour=ATTRIBUTE and &wind=0) with orbit controls,
// and lists what it holds. A file with banyan's wind attributes (_WIND_PIVOT_X,
// ..., _WIND_FLUTTER) sways in the vertex shader (wind.js); otherwise the page
// renders only when something changes, so an idle page costs nothing.
//
// window.__banyanViewer is the page's state for tests and scripts:
// loaded / error (null or a message) / file / counts / attributes / wind,
// plus render(), setColour(name), setWind({...}) and setWindTime(t). loaded
// turns true two frames after the model's first render, so a screenshot
// taken then shows it.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { Wind, hasWind } from './wind.js';

const $ = (id) => document.getElementById(id);
const state = {
  loaded: false, error: null, file: null, meshes: 0, primitives: 0, vertices: 0, triangles: 0,
  materials: [], attributes: {}, colors: false, bounds: null, model: null,
  instances: 0, lods: 0, windMeshes: 0,
  render, setColour, setWind, setWindTime,
};
window.__banyanViewer = state;
const query = new URLSearchParams(window.location.search);

// Viridis, sampled at five stops (sRGB): readable from dark to light.
const RAMP = [[0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551],
              [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];

let renderer;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true });
} catch (e) {
  fail(`WebGL is not available: ${e.message}`);
  throw e;
}
renderer.setPixelRatio(window.devicePixelRatio);
$('view').appendChild(renderer.domElement);

const scene = new THREE.Scene();
scene.background = new THREE.Color(0xdfe6ec);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
camera.position.set(6, 5, 10);
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);
state.camera = camera;

// The wind: on unless ?wind=0; the panel's checkbox and slider drive it.
const wind = new Wind({ enabled: query.get('wind') !== '0' });
state.wind = wind.settings;

scene.add(new THREE.HemisphereLight(0xffffff, 0x8d7c6a, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
scene.add(sun, sun.target);
let grid = null;
let loadToken = 0;

function render() {
  wind.update();
  renderer.render(scene, camera);
}

// While the wind blows over a model that has wind attributes, draw every
// frame; otherwise draw only on change.
let animating = false;
const swaying = () => state.model !== null && state.windMeshes > 0 && wind.running();
function tick() {
  animating = swaying();
  if (!animating) return;
  render();
  requestAnimationFrame(tick);
}
// Draws now (so a caller can read the canvas back in the same task) and
// starts the frame loop if the model should sway.
function kick() {
  render();
  if (!animating && swaying()) {
    animating = true;
    requestAnimationFrame(tick);
  }
}

// setWind({enabled, strength, gust, frequency, direction, flutter}): any
// subset; the panel follows.
function setWind(changes) {
  Object.assign(wind.settings, changes);
  $('wind').checked = wind.settings.enabled;
  $('wind-strength').value = wind.settings.strength;
  kick();
}

// Freezes the wind's clock at t seconds (null: the real clock again) and
// draws, so a test can compare two moments.
function setWindTime(t) {
  wind.settings.time = t;
  kick();
}

function resize() {
  const w = window.innerWidth, h = window.innerHeight;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}
window.addEventListener('resize', resize);
resize();

function setStatus(text, isError) {
  $('status').textContent = text;
  $('status').classList.toggle('error', !!isError);
}

function fail(message) {
  state.loaded = false;
  state.error = message;
  setStatus(message, true);
  document.title = 'banyan viewer: error';
}

function disposeModel() {
  if (!state.model) return;
  scene.remove(state.model);
  state.model.traverse((o) => {
    if (!o.isMesh) return;
    o.geometry.dispose();
    for (const m of [].concat(o.material, o.userData.original || [])) m.dispose();
  });
  state.model = null;
  state.windMeshes = 0;
}

// source: a URL, or the bytes of a dropped file.
function load(source, name) {
  const token = ++loadToken;
  disposeModel();
  Object.assign(state, { loaded: false, error: null, file: name });
  document.title = 'banyan viewer: loading';
  setStatus(`Loading ${name}…`);
  $('info').replaceChildren();
  $('colour-row').hidden = true;
  $('wind-row').hidden = true;
  const onLoad = (gltf) => { if (token === loadToken) show(gltf, name); };
  const onError = (e) => {
    if (token === loadToken) fail(`Cannot load ${name}: ${e && e.message ? e.message : e}`);
  };
  // EXT_meshopt_compression: banyan's compact files (docs/gltf.md).
  const loader = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder);
  if (typeof source === 'string') loader.load(source, onLoad, undefined, onError);
  else loader.parse(source, '', onLoad, onError);
}

// Where each colourable attribute lives: glTF `_ROOT_KIND` arrives in
// three.js as `_root_kind` (GLTFLoader lower-cases names it does not know).
// banyan writes every custom attribute as a scalar (docs/gltf.md); vector
// ones from elsewhere are not listed.
function scalarsOf(g) {
  const out = [];
  for (const [key, attr] of Object.entries(g.attributes)) {
    if (key.startsWith('_') && attr.itemSize === 1) out.push([key.slice(1), attr, 0]);
  }
  return out;
}

function component(attr, c, i) {
  return c === 0 ? attr.getX(i) : c === 1 ? attr.getY(i) : c === 2 ? attr.getZ(i) : attr.getW(i);
}

// Counts, material names and the range of every colourable attribute.
function measure(gltf) {
  const positions = new Set(), scanned = new Map(), materials = new Set();
  const ranges = {};
  let primitives = 0, triangles = 0, colors = false;
  gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    const g = o.geometry;
    primitives++;
    positions.add(g.attributes.position);
    triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
    for (const m of [].concat(o.material)) materials.add(m.name || '(unnamed)');
    colors ||= !!g.attributes.color;
    for (const [name, attr, c] of scalarsOf(g)) {
      // An accessor shared by several primitives is scanned once.
      const seen = scanned.get(attr) || new Set();
      if (seen.has(c)) continue;
      scanned.set(attr, seen.add(c));
      const r = ranges[name] ||= [Infinity, -Infinity];
      for (let i = 0; i < attr.count; i++) {
        const v = component(attr, c, i);
        if (v < r[0]) r[0] = v;
        if (v > r[1]) r[1] = v;
      }
    }
  });
  let vertices = 0;
  for (const p of positions) vertices += p.count;
  const json = gltf.parser.json;
  const meshes = (json.meshes || []).length;
  // three.js's GLTFLoader does not implement MSFT_lod: it shows each
  // node's own mesh (LOD0) and never the coarser levels.
  const lods = (json.nodes || []).filter((n) => n.extensions && n.extensions.MSFT_lod).length;
  // Placed copies: EXT_mesh_gpu_instancing's count on every node the scene
  // draws (three.js makes one InstancedMesh per primitive of each).
  let instances = 0;
  const visit = (i) => {
    const n = json.nodes[i], ext = n.extensions && n.extensions.EXT_mesh_gpu_instancing;
    const first = ext && ext.attributes && Object.values(ext.attributes)[0];
    if (first !== undefined && n.mesh !== undefined) instances += json.accessors[first].count;
    for (const c of n.children || []) visit(c);
  };
  for (const i of ((json.scenes || [])[json.scene ?? 0] || {}).nodes || []) visit(i);
  return { meshes, primitives, vertices, triangles, colors, instances, lods,
           materials: [...materials], attributes: ranges };
}

function show(gltf, name) {
  const root = gltf.scene;
  const info = measure(gltf);
  if (info.triangles === 0) {
    fail(`${name} holds no triangles`);
    return;
  }
  const box = new THREE.Box3().setFromObject(root);
  Object.assign(state, info, { model: root, bounds: { min: box.min.toArray(), max: box.max.toArray() } });
  // Wind: each mesh that carries the attributes gets a wind-patched copy
  // of its material (instanced ones too).
  state.windMeshes = wind.attach(root);
  scene.add(root);
  frame(box);
  fillInfo(gltf, name);
  setStatus(`Loaded ${name}`);
  const colour = query.get('colour');
  if (colour && colour in state.attributes) {
    $('colour').value = colour;
    setColour(colour);
  }
  kick();
  requestAnimationFrame(() => requestAnimationFrame(() => {
    state.loaded = true;
    document.title = `banyan viewer: ${name}`;
  }));
}

// Camera from the front right, above, just far enough to see the whole
// box; a grid on the ground (y = 0, banyan's z = 0) in cells of a power of
// ten metres, or under the model if it dips below.
function frame(box) {
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const r = Math.max(sphere.radius, 1e-3);
  const dir = new THREE.Vector3(0.55, 0.45, 1).normalize();
  const dist = Math.max(fitDistance(box, sphere.center, dir), r * 0.1);
  camera.position.copy(sphere.center).addScaledVector(dir, dist);
  camera.near = r * 1e-3;
  camera.far = dist + r * 20;
  camera.updateProjectionMatrix();
  controls.target.copy(sphere.center);
  controls.maxDistance = (dist + r) * 10;
  controls.update();

  sun.position.copy(sphere.center).add(new THREE.Vector3(0.4, 1, 0.6).multiplyScalar(r * 3));
  sun.target.position.copy(sphere.center);

  if (grid) { scene.remove(grid); grid.geometry.dispose(); grid.material.dispose(); }
  const extent = Math.max(box.max.x - box.min.x, box.max.z - box.min.z, 1e-3) * 1.6;
  const cell = 10 ** Math.floor(Math.log10(extent / 4)); // 4 to 40 cells
  const divisions = 2 * Math.ceil(extent / cell / 2);
  grid = new THREE.GridHelper(divisions * cell, divisions, 0x7b8790, 0xa9b3ba);
  const snap = (v) => Math.round(v / cell) * cell;
  grid.position.set(snap(sphere.center.x), Math.min(0, box.min.y), snap(sphere.center.z));
  scene.add(grid);
}

// The distance from center along dir at which every corner of box lies
// inside the camera's view, with a 5 % margin.
function fitDistance(box, center, dir) {
  const forward = dir.clone().negate();
  const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
  const up = new THREE.Vector3().crossVectors(right, forward);
  const tanV = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2) / 1.05;
  const tanH = tanV * camera.aspect;
  const v = new THREE.Vector3();
  let dist = 0;
  for (let i = 0; i < 8; i++) {
    v.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).sub(center);
    const depth = v.dot(forward); // beyond the centre: more room
    dist = Math.max(dist, Math.abs(v.dot(right)) / tanH - depth, Math.abs(v.dot(up)) / tanV - depth);
  }
  return dist;
}

function fillInfo(gltf, name) {
  const rows = [];
  const row = (label, value) => {
    const tr = document.createElement('tr');
    for (const text of [label, value]) tr.appendChild(document.createElement('td')).textContent = text;
    rows.push(tr);
  };
  const fmt = (v) => (Number.isInteger(v) ? String(v) : v.toFixed(3));
  const s = state.bounds;
  row('file', name);
  row('generator', (gltf.asset && gltf.asset.generator) || '?');
  row('meshes', `${state.meshes} (${state.primitives} primitives)`);
  row('vertices', state.vertices.toLocaleString('en'));
  row('triangles', state.triangles.toLocaleString('en'));
  // glTF is y-up; banyan's z-up sizes are x, -z, y.
  row('size (m)', [0, 2, 1].map((i) => (s.max[i] - s.min[i]).toFixed(2)).join(' × ') + '  (x y z, z up)');
  row('materials', state.materials.join(', '));
  row('colours', state.colors ? 'vertex colours (COLOR_0)' : 'material colours only');
  if (state.instances) row('instances', `${state.instances.toLocaleString('en')} (EXT_mesh_gpu_instancing)`);
  if (state.lods) row('levels of detail', `MSFT_lod on ${state.lods} node(s): three.js shows LOD0 only`);
  row('wind', state.windMeshes ? `${state.windMeshes} primitive(s) with the _WIND_* attributes` : 'no wind attributes');
  for (const [key, [lo, hi]] of Object.entries(state.attributes)) row(key, `${fmt(lo)} … ${fmt(hi)}`);
  $('info').replaceChildren(...rows);

  const select = $('colour');
  select.replaceChildren(new Option('materials', ''), ...Object.keys(state.attributes).map((k) => new Option(k, k)));
  $('colour-row').hidden = Object.keys(state.attributes).length === 0;
  $('wind-row').hidden = state.windMeshes === 0;
  $('wind').checked = wind.settings.enabled;
  $('wind-strength').value = wind.settings.strength;
}

// Colours the model by one scalar attribute over its range, or restores
// the file's own materials and colours when name is ''.
function setColour(name) {
  if (!state.model) return;
  const plain = name ? new THREE.MeshStandardMaterial({ vertexColors: true, side: THREE.DoubleSide, roughness: 0.8 }) : null;
  const swaying = new Map();   // one swaying copy per plant base (wind.js)
  const range = name ? state.attributes[name] : null;
  const c = new THREE.Color();
  state.model.traverse((o) => {
    if (!o.isMesh) return;
    const g = o.geometry;
    if (!o.userData.original) o.userData.original = o.material;
    if (!('originalColor' in g.userData)) g.userData.originalColor = g.attributes.color || null;
    if (!name) {
      if (o.material !== o.userData.original) o.material.dispose();
      o.material = o.userData.original;
      if (g.userData.originalColor) g.setAttribute('color', g.userData.originalColor);
      else g.deleteAttribute('color');
      return;
    }
    const [, attr, k] = scalarsOf(g).find(([n]) => n === name) || [];
    const out = new Float32Array(g.attributes.position.count * 3);
    for (let i = 0; i < g.attributes.position.count; i++) {
      const v = attr ? component(attr, k, i) : 0;
      const t = attr && range[1] > range[0] ? (v - range[0]) / (range[1] - range[0]) : attr ? 0 : -1;
      ramp(t, c).toArray(out, i * 3);
    }
    g.setAttribute('color', new THREE.BufferAttribute(out, 3));
    if (o.material !== o.userData.original) o.material.dispose();
    if (hasWind(g)) {
      const base = wind.baseOf(o);
      if (!swaying.has(base)) swaying.set(base, wind.patch(plain.clone(), base));
      o.material = swaying.get(base);
    } else {
      o.material = plain;
    }
  });
  kick();
}

// t in [0, 1] along the ramp; t < 0 (attribute missing) is grey.
function ramp(t, c) {
  if (t < 0) return c.setRGB(0.6, 0.6, 0.6, THREE.SRGBColorSpace);
  const x = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
  const i = Math.min(Math.floor(x), RAMP.length - 2), f = x - i;
  const [a, b] = [RAMP[i], RAMP[i + 1]];
  return c.setRGB(a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f,
                  THREE.SRGBColorSpace);
}

$('colour').addEventListener('change', (e) => setColour(e.target.value));
$('wind').addEventListener('change', (e) => setWind({ enabled: e.target.checked }));
$('wind-strength').addEventListener('input', (e) => setWind({ strength: Number(e.target.value) }));
$('open').addEventListener('change', (e) => {
  const f = e.target.files[0];
  if (f) f.arrayBuffer().then((buf) => load(buf, f.name));
});
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', (e) => { if (!e.relatedTarget) document.body.classList.remove('dragging'); });
window.addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  const f = e.dataTransfer.files[0];
  if (f) f.arrayBuffer().then((buf) => load(buf, f.name));
});

const param = query.get('file');
if (param) {
  const url = new URL(param, window.location.href);
  load(url.href, decodeURIComponent(url.pathname.split('/').pop()) || param);
}
