#!/usr/bin/env node
// The browser viewer (docs/viewer) in real headless Chromium.
//
//   node tests/viewer/test_viewer.mjs BANYAN_CLI REPO_DIR OUT_DIR
//   BANYAN_TEST_TIER=quick node tests/viewer/test_viewer.mjs ...
//
// Writes presets/*.json as .glb files with the CLI, serves the repository
// and those files from a local HTTP server, and opens the viewer with
// ?file= for each in one browser (a few pages at a time). A preset passes
// when the viewer reports it loaded with the file's own triangle and vertex
// counts and attributes, and the WebGL canvas is not blank: the model,
// drawn and then hidden, changes enough pixels, and the frame's luminance
// varies. Controls that must NOT pass: a text file, a truncated .glb and a
// missing URL must end in the viewer's error state, and a valid .glb whose
// only triangle is a point must be judged blank.
// Wind (docs/game-engines.md): every preset's .glb must carry _WIND_PIVOT_X,
// ..., _WIND_FLUTTER (the case fails before the browser if one does not) and
// must sway (two frozen moments draw differently) and
// stand still with the wind off (the same two moments draw the same). A
// single keyaki must sway in its crown while its trunk base and the ground
// do not move; the same file opened with ?wind=0 must be static; an
// instanced avenue (EXT_mesh_gpu_instancing, avenue variants) must sway
// across its whole length. A keyaki written with --lod (MSFT_lod) must
// show LOD0's counts and report its levels. Screenshots go to
// OUT_DIR/*.png.
//
// Tiers (BANYAN_TEST_TIER): `quick` runs one preset per generator
// (QUICK below; the avenue is an instanced one) plus the wind, LOD and
// negative controls; anything else, or unset, is `full`: every preset.
// What keeps it cheap (it once took 45 minutes; the steps of every case
// are timed and printed):
// - the files carry no textures (--textures off) except the quick presets'
//   (keyaki_young at the default 1024 px, the others at 256 px; they must
//   hold images, but segments never writes any), so the textured materials
//   of every generator that has them draw in both tiers;
// - avenue_boulevard (100 unique trees, 1.7 GB) is written with its first
//   2 trees per row: what it adds to the other avenues is the wind data
//   turned off, which 4 trees show as well as 100 (it is not instanced;
//   wind_avenue is, and is checked as a preset too);
// - the CLI writes the next files while the browser looks at the previous
//   ones, and 2 pages load at once;
// - WebGL without multisampling (3 times faster in SwiftShader);
// - the wind's clock is frozen once a model has loaded, so a page does not
//   redraw a million triangles every frame while the test reads it, and
//   the wind check draws only the frames it reads (4 of the model);
// - the single keyaki's wind checks run on the keyaki_young preset's page
//   (the same file the separate wind_keyaki page loaded).
// BANYAN_VIEWER_ONLY=regex narrows the presets; BANYAN_VIEWER_PAGES sets
// how many pages load at once (default 2); BANYAN_VIEWER_AA=1 keeps
// multisampling.
// Exits 77 (ctest SKIP) only when no chromium binary is found.
import { spawn } from 'node:child_process';
import { createServer } from 'node:http';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync,
         writeFileSync, createReadStream } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { launchChromium } from './cdp.mjs';
import { readGlb, sceneMeshes, hasWindAttributes, writeGlb } from './glb.mjs';

const T0 = Date.now();
const [cli, repo, outDir] = process.argv.slice(2).map((a) => a && path.resolve(a));
if (!outDir) {
  console.error('usage: node test_viewer.mjs BANYAN_CLI REPO_DIR OUT_DIR');
  process.exit(2);
}

// Thresholds of the blank check, luminance on the 0..255 scale. The
// presets give frame variances of 270 to 3700, models covering 1.1 to 32 %
// of the pixels with variances of 120 to 900 (no multisampling, textures
// as written here); the grid alone gave ~22 with multisampling.
const MIN_FRAME_VARIANCE = 50;     // luminance variance of the whole canvas
const MIN_MODEL_FRACTION = 0.005;  // share of pixels the model changes
const MIN_MODEL_VARIANCE = 4;      // luminance variance over the model's pixels
const MIN_RECOLOURED = 0.25;       // share of the model's pixels 'Colour by' changes
const LOAD_TIMEOUT_MS = 300000;    // the largest file (avenue_mixed_age, 255 MB) loads in well under that
const START_TIMEOUT_MS = 20000;    // until the viewer's module has run
const POLL_MS = 50;
const WIDTH = 960, HEIGHT = 640;
const PAGES = Math.max(1, Number(process.env.BANYAN_VIEWER_PAGES) || 2);

// One preset per generator for the quick tier; its avenue is INSTANCED.
const QUICK = ['roots_trunk.json', 'keyaki_young.json', 'ivy_statue.json', 'segments_paper.json'];
// Presets written smaller than they are: what is dropped, and why the
// check keeps its meaning, is said with each.
const SHORTEN = {
  // 100 unique trees without wind data (1.7 GB, minutes to write and load):
  // its first 2 trees per row (4 trees, 56 MB) still carry no wind data,
  // which is what it adds to the other avenues.
  'avenue_boulevard.json': ['--set', 'end=12,0,0'],
};

function findChromium() {
  if (process.env.CHROMIUM) return process.env.CHROMIUM;
  for (const dir of (process.env.PATH || '').split(':')) {
    for (const name of ['chromium', 'chromium-browser']) {
      const p = path.join(dir, name);
      if (existsSync(p)) return p;
    }
  }
  return null;
}

const chromium = findChromium();
if (!chromium) {
  console.log('SKIP: chromium not found on PATH (apt-get install chromium; tools/setup.sh installs it)');
  process.exit(77);
}
const threeModule = path.join(repo, 'docs/viewer/node_modules/three/build/three.module.js');
if (!existsSync(threeModule)) {
  console.log(`FAIL: ${threeModule} is missing: run npm ci --prefix docs/viewer (tools/setup.sh does)`);
  process.exit(1);
}

const glbDir = path.join(outDir, 'glb');
mkdirSync(glbDir, { recursive: true });
const since = (t) => (Date.now() - t) / 1000;

// --- inputs ---------------------------------------------------------------

// What the viewer must report for a file: counts from the glTF JSON, over
// the meshes the default scene draws (not MSFT_lod's coarser levels, which
// three.js ignores). Attributes: every "_NAME" scalar (banyan writes no
// other custom attribute).
function expected(file) {
  const { json: j } = readGlb(file);
  const positions = new Set(), attributes = new Set();
  let triangles = 0, colors = false;
  for (const m of sceneMeshes(j)) {
    for (const p of m.primitives) {
      positions.add(p.attributes.POSITION);
      triangles += j.accessors[p.indices].count / 3;
      colors ||= 'COLOR_0' in p.attributes;
      for (const [k, a] of Object.entries(p.attributes)) {
        if (k.startsWith('_') && j.accessors[a].type === 'SCALAR') attributes.add(k.slice(1).toLowerCase());
      }
    }
  }
  let vertices = 0;
  for (const a of positions) vertices += j.accessors[a].count;
  const textures = (j.images || []).length;
  const instanced = (j.nodes || []).some((n) => n.extensions && n.extensions.EXT_mesh_gpu_instancing);
  return { triangles, vertices, colors, attributes: [...attributes].sort(), wind: hasWindAttributes(j),
           textures, instanced };
}

// A valid .glb with one triangle whose corners coincide: it loads, but
// draws nothing, so the blank check must catch it.
function pointGlb() {
  const bin = Buffer.alloc(48);
  for (let i = 0; i < 9; i++) bin.writeFloatLE(1, i * 4);
  for (let i = 0; i < 3; i++) bin.writeUInt32LE(i, 36 + i * 4);
  const json = {
    asset: { version: '2.0', generator: 'banyan viewer test' }, scene: 0, scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }], meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [1, 1, 1], max: [1, 1, 1] },
                { bufferView: 1, componentType: 5125, count: 3, type: 'SCALAR' }],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 36 }, { buffer: 0, byteOffset: 36, byteLength: 12 }],
    buffers: [{ byteLength: 48 }],
  };
  return writeGlb(json, bin);
}

// The CLI writes one file at a time, in the order the pages ask for
// them, while the browser works on the files already written. A file is
// written once however many cases open it. Resolves to the file's
// expectations; rejects with the reason the case fails.
const written = new Map();
let cliQueue = Promise.resolve();
let cliSeconds = 0;
function runCli(args) {
  return new Promise((resolve) => {
    const t = Date.now();
    const child = spawn(cli, args, { stdio: ['ignore', 'ignore', 'pipe'] });
    let stderr = '';
    child.stderr.on('data', (d) => { stderr += d; });
    child.on('error', (e) => resolve({ status: null, stderr: e.message, seconds: since(t) }));
    child.on('close', (status) => resolve({ status, stderr, seconds: since(t) }));
  });
}
function write(file, args, { windOff = false } = {}) {
  if (written.has(file)) return written.get(file);
  const glb = path.join(glbDir, file);
  const job = cliQueue.then(async () => {
    const r = await runCli([...args, '-o', glb]);
    cliSeconds += r.seconds;
    if (r.status !== 0) throw new Error(`banyan ${args.join(' ')} exited ${r.status}: ${r.stderr}`);
    const expect = expected(glb);
    // Every generator writes the wind attributes:
    // a preset without them is a regression, not a file to skip the wind on,
    // unless it turns them off (and then it must have none).
    if (!expect.wind !== windOff) {
      throw new Error(`the CLI wrote ${expect.wind ? '' : 'no '}_WIND_PIVOT_X/_WIND_STIFFNESS` +
                      (windOff ? ' though the preset turns the wind off' : ''));
    }
    return { ...expect, cliSeconds: r.seconds, bytes: statSync(glb).size };
  });
  cliQueue = job.catch(() => {});
  written.set(file, job);
  return job;
}

const tier = (process.env.BANYAN_TEST_TIER || '').trim().toLowerCase() === 'quick' ? 'quick' : 'full';
const only = new RegExp(process.env.BANYAN_VIEWER_ONLY || '.');
const presets = readdirSync(path.join(repo, 'presets'))
  .filter((n) => n.endsWith('.json') && (tier === 'full' || QUICK.includes(n)) && only.test(n)).sort();
if (presets.length === 0) {
  console.log(`FAIL: no presets/*.json in tier ${tier}` + (process.env.BANYAN_VIEWER_ONLY ? ' matching BANYAN_VIEWER_ONLY' : ''));
  process.exit(1);
}
const youngFile = path.join(repo, 'presets/keyaki_young.json');
const avenueArgs = ['avenue', '--preset', path.join(repo, 'presets/avenue_young.json'),
                    '--set', 'end=18,0,0', '--set', 'variants=3'];

const cases = [];
for (const name of presets) {
  const file = path.join(repo, 'presets', name);
  const doc = JSON.parse(readFileSync(file, 'utf8'));
  const generator = doc.generator;
  // A preset may turn the wind data off (avenue_boulevard: 100 unique trees); then it must carry none.
  const windOff = !!(doc.params && (doc.params.wind === false || doc.params['tree.wind'] === false));
  // A *_large preset is a benchmark (ivy_wall_large: 7 M vertices): its first 300 steps.
  const cap = name.endsWith('_large.json') ? ['--set', 'steps=300'] : [];
  // Textures: the default on keyaki_young (its file is also the wind
  // keyaki's), 256 px on the other quick presets, none elsewhere.
  const textures = name === 'keyaki_young.json' ? [] : QUICK.includes(name) ? ['--texture-size', '256']
                                                                              : ['--textures', 'off'];
  const glb = name.replace(/\.json$/, '.glb');
  cases.push({ name: path.basename(glb, '.glb'), file: glb, kind: 'preset', tree: generator === 'keyaki',
               textured: QUICK.includes(name) && generator !== 'segments',   // segments writes no images (docs/gltf.md)
               note: SHORTEN[name] ? ` (${SHORTEN[name].filter((a) => a !== '--set').join(' ')})` : '',
               ready: () => write(glb, [generator, '--preset', file, ...cap, ...(SHORTEN[name] || []), ...textures],
                                 { windOff }) });
}
// The single swaying keyaki: the keyaki_young preset's page does its
// checks (tree: true), first on the file's own materials (windOwn), as the
// separate wind_keyaki page did, then, as for every preset, coloured by an
// attribute. Without that preset (BANYAN_VIEWER_ONLY) it gets a page of its own.
const young = () => write('keyaki_young.glb', ['keyaki', '--preset', youngFile]);
const youngCase = cases.find((c) => c.name === 'keyaki_young');
if (youngCase) Object.assign(youngCase, { windOwn: true, note: ' (also wind_keyaki)' });
else cases.push({ name: 'wind_keyaki', file: 'keyaki_young.glb', kind: 'wind', tree: true, ready: young });
// The same file with ?wind=0 must stand still.
cases.push({ name: 'wind_off', file: 'keyaki_young.glb', kind: 'wind', query: '&wind=0', ready: young });
// An instanced avenue of young trees (7 trees, 3 variants): the quick
// tier's avenue preset, with the wind checks on its own materials first.
cases.push({ name: 'wind_avenue', file: 'wind_avenue.glb', kind: 'preset', instanced: true, windOwn: true,
             note: ' (avenue_young, end=18,0,0 variants=3)',
             ready: () => write('wind_avenue.glb', [...avenueArgs, '--textures', 'off']) });
// Levels of detail: three.js ignores MSFT_lod, so the viewer must show
// (and count) LOD0 alone and say the file has levels.
cases.push({ name: 'lod_keyaki', file: 'lod_keyaki.glb', kind: 'preset', lod: true, tree: true,
             ready: () => write('lod_keyaki.glb', ['keyaki', '--preset', youngFile, '--lod', '0.5,0.15',
                                                   '--textures', 'off']) });
// A compact file (--compact: KHR_mesh_quantization, EXT_meshopt_compression)
// of the same keyaki with its levels: three.js decodes it with its
// MeshoptDecoder, and it must show, count and sway like the plain one.
cases.push({ name: 'compact_keyaki', file: 'compact_keyaki.glb', kind: 'preset', lod: true, tree: true,
             ready: () => write('compact_keyaki.glb', ['keyaki', '--preset', youngFile, '--lod', '0.5,0.15',
                                                       '--textures', 'off', '--compact']) });
// The controls that must fail, once every file is written (the truncated
// one is half of the smallest).
const allWritten = () => Promise.allSettled(cases.filter((c) => c.kind !== 'error' && c.kind !== 'blank')
                                                 .map((c) => c.ready()));
let controls = null;
const writeControls = () => controls ||= allWritten().then(() => {
  writeFileSync(path.join(glbDir, 'bad_text.glb'), 'this is not a glTF file\n');
  const files = [...written.keys()].map((f) => path.join(glbDir, f)).filter((f) => existsSync(f));
  const smallest = files.sort((a, b) => statSync(a).size - statSync(b).size)[0];
  const whole = smallest ? readFileSync(smallest) : pointGlb();
  writeFileSync(path.join(glbDir, 'bad_truncated.glb'), whole.subarray(0, Math.floor(whole.length / 2)));
  writeFileSync(path.join(glbDir, 'bad_point.glb'), pointGlb());
  return {};
});
cases.push({ name: 'bad_text', file: 'bad_text.glb', kind: 'error', ready: writeControls },
           { name: 'bad_truncated', file: 'bad_truncated.glb', kind: 'error', ready: writeControls },
           { name: 'bad_missing', file: 'bad_missing.glb', kind: 'error', ready: writeControls },
           { name: 'bad_point', file: 'bad_point.glb', kind: 'blank', ready: writeControls });

console.log(`viewer: tier ${tier} (BANYAN_TEST_TIER=${process.env.BANYAN_TEST_TIER ?? ''}): ${presets.length} presets ` +
            `(${presets.map((n) => n.replace(/\.json$/, '')).join(', ')}), plus ` +
            `${cases.slice(presets.length).map((c) => c.name).join(', ')}: ${cases.length} cases, ` +
            `${PAGES} pages at a time`);
// The CLI writes every file, in the order of the cases, while the browser
// starts and then works on the files already written.
for (const c of cases) c.ready().catch(() => {});


// --- server: the repository at /, the .glb files at /glb/ ------------------

const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
               '.glb': 'model/gltf-binary', '.png': 'image/png', '.css': 'text/css' };
const server = createServer((req, res) => {
  const url = new URL(req.url, 'http://localhost');
  let rel = decodeURIComponent(url.pathname);
  let base = repo;
  if (rel.startsWith('/glb/')) { base = glbDir; rel = rel.slice(4); }
  const file = path.join(base, path.normalize(rel));
  if (!file.startsWith(base)) { res.writeHead(403).end(); return; }
  let st = null;
  try { st = statSync(file); } catch { /* not found */ }
  const target = st && st.isDirectory() ? path.join(file, 'index.html') : file;
  if (!existsSync(target) || statSync(target).isDirectory()) { res.writeHead(404).end('not found'); return; }
  res.writeHead(200, { 'Content-Type': MIME[path.extname(target)] || 'application/octet-stream',
                       'Content-Length': statSync(target).size });
  createReadStream(target).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const origin = `http://127.0.0.1:${server.address().port}`;

// --- browser ---------------------------------------------------------------

// Runs in the page: draws the frame with the model shown, coloured by an
// attribute, then hidden, reading the WebGL canvas back right after each
// render (same task, so no preserveDrawingBuffer is needed). Luminance on
// the 0..255 scale.
const STATS = `(() => {
  const v = window.__banyanViewer, gl = document.querySelector('#view canvas');
  const w = gl.width, h = gl.height, c = document.createElement('canvas');
  c.width = w; c.height = h;
  const ctx = c.getContext('2d', { willReadFrequently: true });
  const read = () => { ctx.clearRect(0, 0, w, h); ctx.drawImage(gl, 0, 0); return ctx.getImageData(0, 0, w, h).data; };
  const grab = (visible) => { v.model.visible = visible; v.render(); return read(); };
  const changed = (p, q, i) => Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 24;
  const a = grab(true);
  // Colour by the first banyan attribute (setColour renders): the model's
  // pixels must change. Read right after a's frame, so a setColour that
  // changes nothing, or draws nothing, reads a again and fails.
  const attr = Object.keys(v.attributes)[0];
  let recoloured = null;
  if (attr) {
    v.setColour(attr);
    const r = read();
    recoloured = 0;
    for (let i = 0; i < a.length; i += 4) if (changed(a, r, i)) recoloured++;
    recoloured /= a.length / 4;
  }
  const b = grab(false);
  v.model.visible = true;
  const lum = (d, i) => 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2];
  let n = 0, s = 0, s2 = 0, m = 0, ms = 0, ms2 = 0;
  for (let i = 0; i < a.length; i += 4) {
    const y = lum(a, i);
    n++; s += y; s2 += y * y;
    if (changed(a, b, i)) { m++; ms += y; ms2 += y * y; }
  }
  return { width: w, height: h, variance: s2 / n - (s / n) ** 2, fraction: m / n,
           modelVariance: m ? ms2 / m - (ms / m) ** 2 : 0, attr, recoloured };
})()`;

// Runs in the page: the wind as loaded (on, or off for ?wind=0) at two
// frozen moments half a gust apart (the swing's two extremes), at a test
// strength, then the same two moments with the wind switched off. Pixels
// count as changed as in STATS. For a
// single tree (tree: true) it also counts changes in two screen regions
// made by projecting the trunk's foot (glTF (0, min y, 0): a keyaki
// stands at the origin) and points above it: the crown (above 55 % of the
// height) and a box around the trunk base and the ground in front of it
// (below 4 % of the height, half as wide as 10 % of the height is tall).
// For instanced files, changes in each third of the model's screen width.
// Afterwards the wind is as before (switch, strength, clock; the canvas
// is redrawn by whatever runs next), so the script can run twice on one page.
const WIND = (tree) => `(() => {
  const v = window.__banyanViewer, gl = document.querySelector('#view canvas');
  const w = gl.width, h = gl.height, c = document.createElement('canvas');
  c.width = w; c.height = h;
  const ctx = c.getContext('2d', { willReadFrequently: true });
  const read = () => { ctx.clearRect(0, 0, w, h); ctx.drawImage(gl, 0, 0); return ctx.getImageData(0, 0, w, h).data; };
  // setWindTime draws; the settings are changed in place before it, so
  // that every draw is one the checks read (setWind would draw too).
  const at = (t) => { v.setWindTime(t); return read(); };
  const s = v.wind, saved = { enabled: s.enabled, strength: s.strength, time: s.time };
  const enabled = s.enabled, f = s.frequency;
  const t1 = 0.25 / f, t2 = 0.75 / f;
  s.strength = 0.15;
  const a = at(t1), b = at(t2);
  s.enabled = false;
  const a0 = at(t1), b0 = at(t2);
  v.model.visible = false;
  const empty = at(t1);
  v.model.visible = true;
  Object.assign(s, saved);
  const changed = (p, q, i) => Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 24;
  const same = (p, q) => { for (let i = 0; i < p.length; i++) if (p[i] !== q[i]) return false; return true; };
  const px = (x, y, z) => {
    const p = new v.model.position.constructor(x, y, z).project(v.camera);
    return [(p.x + 1) / 2 * w, (1 - p.y) / 2 * h];
  };
  const lo = v.bounds.min, hi = v.bounds.max, H = hi[1] - lo[1];
  const [fx, fy] = px(0, lo[1], 0), [, y4] = px(0, lo[1] + 0.04 * H, 0), [, y10] = px(0, lo[1] + 0.1 * H, 0);
  const [, y55] = px(0, lo[1] + 0.55 * H, 0);
  const half = Math.max(0.5 * Math.abs(fy - y10), 4);
  let moved = 0, model = 0, crown = 0, crownModel = 0, base = 0, baseArea = 0, minX = w, maxX = 0;
  const cols = new Uint32Array(w);
  for (let y = 0, i = 0; y < h; y++) for (let x = 0; x < w; x++, i += 4) {
    const m = changed(a, empty, i), d = changed(a, b, i);
    if (m) { model++; minX = Math.min(minX, x); maxX = Math.max(maxX, x); }
    if (d) { moved++; cols[x]++; }
    if (y < y55) { crownModel += m; crown += d; }
    if (Math.abs(x - fx) <= half && y >= y4 && y <= fy + half) { baseArea++; base += d; }
  }
  const thirds = [0, 0, 0];
  for (let x = minX; x <= maxX; x++) thirds[Math.min(2, Math.floor(3 * (x - minX) / (maxX - minX + 1)))] += cols[x];
  return { enabled, moved, model, crown, crownModel, base, baseArea, thirds, off: same(a0, b0),
           foot: [fx, fy], instances: v.instances, windMeshes: v.windMeshes };
})()`;

const STATE = `(() => { const v = window.__banyanViewer; return v ? { loaded: v.loaded, error: v.error,
  triangles: v.triangles, vertices: v.vertices, colors: v.colors, title: document.title, lods: v.lods,
  attributes: Object.keys(v.attributes).sort() } : null; })()`;

// Once loaded (by then the viewer's frame loop has drawn the swaying
// model), the wind's clock stops and the viewer draws only on change: it
// would otherwise redraw the model every frame, in software, while the
// test reads the page. The checks set their own moments (setWindTime), so
// they see the same frames either way.
const FREEZE = `(() => { const v = window.__banyanViewer; if (v.wind.time === null) v.wind.time = 0; return v.wind.time; })()`;

const profile = mkdtempSync(path.join(tmpdir(), 'banyan-viewer-'));
// No multisampling: SwiftShader draws a WebGL frame about 3 times faster
// without it (avenue_street 2.1 s -> 0.7 s, keyaki_mature 0.9 s -> 0.3 s,
// on 2 busy cores), and no check depends on smoothed edges: the model and
// its motion change whole pixels either way. BANYAN_VIEWER_AA=1 keeps the
// viewer's antialias: true in force.
const aa = process.env.BANYAN_VIEWER_AA === '1' ? [] : ['--webgl-antialiasing-mode=none'];
const { proc, cdp, log } = launchChromium(chromium, profile, [`--window-size=${WIDTH},${HEIGHT}`, ...aa]);
// ctest's timeout sends SIGTERM: take the browser and its profile along.
process.on('SIGTERM', () => {
  proc.kill('SIGKILL');
  rmSync(profile, { recursive: true, force: true });
  process.exit(1);
});
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function openPage() {
  const { targetId } = await cdp.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await cdp.send('Target.attachToTarget', { targetId, flatten: true });
  const page = { targetId, exceptions: [], console: [],
                 send: (m, p) => cdp.send(m, p, sessionId) };
  cdp.on('Runtime.exceptionThrown', sessionId, (e) =>
    page.exceptions.push(e.exceptionDetails.exception?.description || e.exceptionDetails.text));
  cdp.on('Runtime.consoleAPICalled', sessionId, (e) => {
    if (e.type === 'error' || e.type === 'warning') page.console.push(e.args.map((a) => a.value ?? a.description).join(' '));
  });
  await page.send('Runtime.enable');
  await page.send('Page.enable');
  await page.send('Emulation.setDeviceMetricsOverride', { width: WIDTH, height: HEIGHT, deviceScaleFactor: 1, mobile: false });
  // Pages that load side by side must all draw (rAF), not only the front one.
  await page.send('Emulation.setFocusEmulationEnabled', { enabled: true }).catch(() => {});
  return page;
}

async function evaluate(page, expression) {
  const r = await page.send('Runtime.evaluate', { expression, returnByValue: true });
  if (r.exceptionDetails) throw new Error(`page: ${r.exceptionDetails.exception?.description || r.exceptionDetails.text}`);
  return r.result.value;
}

async function waitDone(page) {
  const t0 = Date.now();
  for (;;) {
    const s = await evaluate(page, STATE);
    if (s && s.loaded) await evaluate(page, FREEZE);
    if (s && (s.loaded || s.error)) return { ...s, seconds: since(t0) };
    if (Date.now() - t0 > (s ? LOAD_TIMEOUT_MS : START_TIMEOUT_MS)) return { ...(s || {}), timeout: true, seconds: since(t0) };
    await sleep(POLL_MS);
  }
}

function sameList(a, b) {
  return a.length === b.length && a.every((x, i) => x === b[i]);
}

// Thresholds of the wind checks, in pixels of the 960x640 canvas. At the
// test strength (0.15 rad) the crown's leaves move by a few pixels.
const MIN_CROWN_MOVED = 0.02;   // share of the crown's model pixels that must change
const MAX_BASE_MOVED = 0.002;   // share of the trunk-base box that may change
const MIN_THIRD_MOVED = 20;     // changed pixels in each third of an instanced row

function windProblems(c, r, label) {
  const out = [];
  if (r.windMeshes === 0) out.push('the viewer found no wind attributes');
  if (!r.off) out.push('with the wind off, two moments draw differently');
  const expectOn = c.query !== '&wind=0';
  if (r.enabled !== expectOn) out.push(`wind is ${r.enabled ? 'on' : 'off'} at load, expected ${expectOn ? 'on' : 'off'}`);
  if (expectOn) {
    if (r.moved === 0) out.push('the wind moves nothing');
    if (c.tree) {
      if (!(r.crown >= MIN_CROWN_MOVED * r.crownModel)) out.push(`the crown barely moves: ${r.crown} of ${r.crownModel} px`);
      if (r.baseArea === 0) out.push('the trunk base is off screen');
      if (r.base > MAX_BASE_MOVED * r.baseArea) out.push(`the trunk base or ground moves: ${r.base} of ${r.baseArea} px`);
    }
    if (c.instanced) {
      if (!(r.instances > 1)) out.push(`expected instances (EXT_mesh_gpu_instancing), the viewer has ${r.instances}`);
      if (r.thirds.some((n) => n < MIN_THIRD_MOVED)) out.push(`not every part of the row sways: ${r.thirds.join('/')} px by thirds`);
    }
  } else if (r.moved !== 0) {
    out.push(`?wind=0 is not static: ${r.moved} px moved`);
  }
  return out.map((p) => `${label}${p}`);
}

function windFigure(c, wind, label) {
  return `; ${label}wind ${wind.enabled ? 'on' : 'off'}: ${wind.moved} px moved` +
         (c.tree ? ` (crown ${wind.crown} of ${wind.crownModel}, base ${wind.base} of ${wind.baseArea})` : '') +
         (c.instanced ? ` (${wind.instances} instances, by thirds ${wind.thirds.join('/')})` : '') +
         `, ${wind.off ? 'still' : 'NOT still'} when off`;
}

// Returns a list of problems (empty: pass), the report line and the
// seconds of each step.
async function runCase(c) {
  const problems = [], steps = {};
  let t = Date.now();
  const step = (name) => { steps[name] = (steps[name] || 0) + since(t); t = Date.now(); };
  let expect;
  try {
    expect = await c.ready();
  } catch (e) {
    step('cli');
    return { problems: [e.message], line: `${c.name}: not written`, steps };
  }
  step('cli');   // waiting for the CLI (it writes ahead of the pages)
  const page = await openPage();
  let s, stats = null, winds = [];
  try {
    const url = `${origin}/docs/viewer/?file=${encodeURIComponent('/glb/' + c.file)}${c.query || ''}`;
    const nav = await page.send('Page.navigate', { url });
    if (nav.errorText) problems.push(`navigation failed: ${nav.errorText}`);
    s = await waitDone(page);
    step('load');
    if (s.timeout) problems.push(s.loaded === undefined ? 'the viewer did not start (no window.__banyanViewer)'
                                                        : `no load or error within ${LOAD_TIMEOUT_MS / 1000} s`);
    // The screenshot first: the pixel checks below redraw the model.
    const shot = await page.send('Page.captureScreenshot', { format: 'png' });
    writeFileSync(path.join(outDir, `${c.name}.png`), Buffer.from(shot.data, 'base64'));
    step('shot');
    const swaying = s.loaded && (c.kind === 'wind' || (c.kind === 'preset' && expect.wind));
    // Wind on the file's own materials (before 'Colour by' replaces them).
    if (swaying && c.windOwn) {
      const w = await evaluate(page, WIND(c.tree));
      winds.push(['own materials: ', w]);
      problems.push(...windProblems(c, w, 'own materials: '));
      step('wind');
    }
    if (c.kind === 'error') {
      if (!s.error) problems.push('expected the error state, got none');
      if (s.loaded) problems.push('reported loaded for a broken file');
      if (s.error && s.title !== 'banyan viewer: error') problems.push(`title is "${s.title}"`);
    } else {
      if (s.error) problems.push(`viewer error: ${s.error}`);
      if (s.loaded && c.kind !== 'wind') stats = await evaluate(page, STATS);
      step('stats');
    }
    if (c.kind === 'preset' && s.loaded) {
      const e = expect;
      if (s.triangles !== e.triangles) problems.push(`triangles ${s.triangles}, file has ${e.triangles}`);
      if (s.vertices !== e.vertices) problems.push(`vertices ${s.vertices}, file has ${e.vertices}`);
      if (s.colors !== e.colors) problems.push(`colours ${s.colors}, file has ${e.colors}`);
      if (!sameList(s.attributes, e.attributes)) problems.push(`attributes [${s.attributes}], file has [${e.attributes}]`);
      if (s.title !== `banyan viewer: ${c.file}`) problems.push(`title is "${s.title}"`);
      if (c.lod && !(s.lods >= 1)) problems.push(`the viewer reports ${s.lods} nodes with MSFT_lod`);
      if (c.instanced && !e.instanced) problems.push('the CLI wrote no EXT_mesh_gpu_instancing');
      if (c.textured && !e.textures) problems.push('written with textures, the file has no images');
    }
    const blank = stats && (stats.variance < MIN_FRAME_VARIANCE || stats.fraction < MIN_MODEL_FRACTION ||
                            stats.modelVariance < MIN_MODEL_VARIANCE);
    if (c.kind === 'preset' && blank) problems.push('canvas is blank');
    if (c.kind === 'preset' && stats && stats.attr && !(stats.recoloured >= MIN_RECOLOURED * stats.fraction))
      problems.push(`colouring by ${stats.attr} changed ${(100 * stats.recoloured).toFixed(2)}% of pixels`);
    // Wind as every preset had it: after STATS, coloured by an attribute
    // (the wind case, kind 'wind', on the file's own materials).
    if (swaying && (c.kind === 'wind' || c.kind === 'preset')) {
      const label = c.windOwn ? 'coloured: ' : '';
      const w = await evaluate(page, WIND(c.tree));
      winds.push([label, w]);
      problems.push(...windProblems(c, w, label));
      step('wind');
    }
    if (c.kind === 'blank' && !s.loaded) problems.push('expected it to load');
    if (c.kind === 'blank' && stats && !blank) problems.push('a point-sized model was not judged blank');
    if (page.exceptions.length) problems.push(`page exceptions: ${page.exceptions.join(' | ')}`);
  } finally {
    await cdp.send('Target.closeTarget', { targetId: page.targetId }).catch(() => {});
    step('close');
  }
  const fig = stats ? `variance ${stats.variance.toFixed(0)}, model ${(100 * stats.fraction).toFixed(2)}% of ` +
                      `${stats.width}x${stats.height} px, model variance ${stats.modelVariance.toFixed(0)}` +
                      (stats.attr ? `, by ${stats.attr} ${(100 * stats.recoloured).toFixed(2)}%` : '') : '';
  const windFig = winds.map(([label, w]) => windFigure(c, w, label)).join('');
  const size = expect && expect.bytes ? `${(expect.bytes / 1e6).toFixed(1)} MB` +
               (expect.textures ? `, ${expect.textures} textures` : ', no textures') + ', ' : '';
  const what = c.kind === 'error' ? `error state: ${s?.error}` : `${size}${s?.triangles} triangles, ${fig}${windFig}`;
  const times = Object.entries(steps).map(([k, v]) => `${k} ${v.toFixed(1)}`).join(', ');
  return { problems, steps, line: `${c.name}${c.note || ''}: ${what}; ${times} s` +
                                  (page.console.length ? `; console: ${page.console.join(' | ').slice(0, 300)}` : '') };
}

let passed = 0, failed = 0, stopped = false;
const results = new Map();
const tBrowser = Date.now();
try {
  // PAGES workers take the cases in order.
  let next = 0;
  const worker = async () => {
    while (!stopped && next < cases.length) {
      const c = cases[next++];
      const t = Date.now();
      let r;
      try {
        r = await runCase(c);
      } catch (e) {
        r = { problems: [e.message], line: `${c.name}: aborted`, steps: {} };
      }
      r.seconds = since(t);
      results.set(c, r);
      if (r.problems.length) {
        failed++;
        console.log(`FAIL ${r.line}\n     ${r.problems.join('\n     ')}`);
        if (cdp.closed) {
          console.log(`     ${cdp.closed}; chromium's last output:\n${log.join('').slice(-3000)}`);
          stopped = true;
        }
      } else {
        passed++;
        console.log(`ok   ${r.line}`);
      }
    }
  };
  await Promise.all(Array.from({ length: PAGES }, worker));
} finally {
  await cdp.send('Browser.close').catch(() => {});
  await Promise.race([new Promise((r) => proc.once('exit', r)), sleep(5000)]);
  if (proc.exitCode === null) proc.kill('SIGKILL');
  server.close();
  rmSync(profile, { recursive: true, force: true });
}
// Per case: seconds from taking it up to closing its page (with PAGES
// pages at once these overlap, so they add up to more than the total).
console.log(`times (s; cli = waiting for the CLI, ${PAGES} pages at once so they overlap):`);
for (const c of cases) {
  const r = results.get(c);
  if (!r) { console.log(`  ${c.name.padEnd(26)} not run`); continue; }
  console.log(`  ${c.name.padEnd(26)} ${r.seconds.toFixed(1).padStart(6)}  (` +
              Object.entries(r.steps).map(([k, v]) => `${k} ${v.toFixed(1)}`).join(', ') + ')');
}
console.log(`viewer: tier ${tier}, ${presets.length} presets, ${cases.length - presets.length} more cases; ` +
            `CLI ${cliSeconds.toFixed(1)} s (alongside), chromium ${since(tBrowser).toFixed(1)} s, ` +
            `total ${since(T0).toFixed(1)} s; screenshots in ${outDir}`);
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed || passed !== cases.length ? 1 : 0);
