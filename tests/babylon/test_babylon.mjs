#!/usr/bin/env node
// banyan's .glb files in Babylon.js, headless (NullEngine: no GPU, the
// loader and the scene graph as an app gets them).
//
//   node tests/babylon/test_babylon.mjs BANYAN_CLI REPO_DIR OUT_DIR
//
// Writes one file per generator with the CLI (roots' defaults,
// keyaki_young and ivy_wall with textures, an instanced avenue of
// variants with --engine-uvs, a keyaki with --lod 0.5,0.15,billboard) and
// loads each twice into a fresh scene:
// - with the stock glTF loader: the load must succeed with no error
//   logged; every primitive the file's scene draws must be a Babylon mesh
//   with the file's vertex and index counts and its POSITION, NORMAL,
//   TEXCOORD_0 and indices bit for bit; nothing else may carry geometry;
//   an EXT_mesh_gpu_instancing node must give thin instances, as many as
//   its TRANSLATION accessor holds, each moved by its TRANSLATION; the
//   textured files' materials must hold the file's PNG images, as many
//   textures as the file has images; the `_` attributes (_WIND_*, _BIRTH, ...) must
//   NOT be there (Babylon's loader reads only the standard semantics: if
//   that changes, docs/game-engines.md must say so); TEXCOORD_1..4
//   (--engine-uvs) must arrive as uv2..uv5;
// - with the loader extension docs/game-engines.md gives to keep them
//   (run from the page's code): every `_` attribute must arrive as a
//   vertex buffer of its own name holding the file's values bit for bit.
// The LOD file: Babylon reads MSFT_lod, loading the levels coarsest first
// and dropping each when the next finer one is ready; the test checks
// that it reports every level and ends with LOD0 alone.
// Controls that must NOT pass: a truncated .glb must fail to load, and a
// file whose _WIND_PHASE points at the stiffness values must fail the
// checks made from the real file.
// Exits 77 (ctest SKIP) when Babylon.js is not installed and npm is
// missing to install it (tools/setup.sh: npm ci --prefix tests/babylon).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const T0 = Date.now();
const here = path.dirname(fileURLToPath(import.meta.url));
const [cli, repo, outDir] = process.argv.slice(2).map((a) => a && path.resolve(a));
if (!outDir) {
  console.error('usage: node test_babylon.mjs BANYAN_CLI REPO_DIR OUT_DIR');
  process.exit(2);
}
if (!existsSync(path.join(here, 'node_modules/@babylonjs/loaders/glTF/index.js'))) {
  const npm = spawnSync('npm', ['--version'], { stdio: 'ignore' }).status === 0;
  console.log(`${npm ? 'FAIL' : 'SKIP'}: Babylon.js is not installed: npm ci --prefix tests/babylon (tools/setup.sh)`);
  process.exit(npm ? 1 : 77);
}
const { NullEngine, Scene, SceneLoader, AppendSceneAsync, Logger } = await import('@babylonjs/core');
await import('@babylonjs/loaders/glTF/index.js');
const { registerGLTFExtension, unregisterGLTFExtension } = await import('@babylonjs/loaders/glTF/2.0/index.js');
Logger.LogLevels = Logger.WarningLogLevel | Logger.ErrorLogLevel;

// Babylon's glTF loader keeps only the standard attributes. An app that
// wants banyan's `_` attributes registers a loader extension that keeps
// each as a vertex buffer of the same name; the test runs the one
// docs/game-engines.md shows, taken from its ```js block, so the page's
// code is the tested code.
function docsExtension() {
  const page = readFileSync(path.join(repo, 'docs/game-engines.md'), 'utf8');
  const block = [...page.matchAll(/^```js\n([\s\S]*?)^```$/gm)].map((m) => m[1])
    .find((code) => code.includes("registerGLTFExtension('banyan_attributes'"));
  if (!block) throw new Error("docs/game-engines.md has no ```js block registering 'banyan_attributes'");
  let registered = null;
  new Function('registerGLTFExtension', block.replace(/^import .*$/gm, ''))(
    (name, isGLTFExtension, factory) => { registered = { name, isGLTFExtension, factory }; });
  if (!registered) throw new Error("docs/game-engines.md's banyan_attributes block registers nothing");
  return registered;
}
let docs;
try {
  docs = docsExtension();
} catch (e) {
  console.log(`FAIL: ${e.message}`);
  process.exit(1);
}

// --- the .glb as the file states it ---------------------------------------
function parseGlb(bytes) {
  const b = Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (b.length < 20 || b.toString('latin1', 0, 4) !== 'glTF') throw new Error('not a .glb');
  const jsonLen = b.readUInt32LE(12);
  const json = JSON.parse(b.toString('utf8', 20, 20 + jsonLen));
  const binAt = 20 + jsonLen;
  const bin = binAt + 8 <= b.length ? b.subarray(binAt + 8, binAt + 8 + b.readUInt32LE(binAt)) : Buffer.alloc(0);
  return { json, bin };
}

const COMPONENTS = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };
const TYPED = { 5121: Uint8Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
// An accessor's values, tightly packed, in its own component type.
function accessorData({ json, bin }, index) {
  const a = json.accessors[index], view = json.bufferViews[a.bufferView];
  const T = TYPED[a.componentType], n = COMPONENTS[a.type];
  const size = T.BYTES_PER_ELEMENT, stride = view.byteStride || n * size;
  const start = (view.byteOffset || 0) + (a.byteOffset || 0);
  const out = new T(a.count * n);
  for (let i = 0; i < a.count; i++) {
    for (let c = 0; c < n; c++) {
      const at = start + i * stride + c * size;
      out[i * n + c] = T === Float32Array ? bin.readFloatLE(at) : T === Uint32Array ? bin.readUInt32LE(at)
                     : T === Uint16Array ? bin.readUInt16LE(at) : bin.readUInt8(at);
    }
  }
  return out;
}

// What the scene draws: one Babylon mesh per primitive of each scene node
// (Babylon names it after the node, with _primitiveN when there are
// several), its thin instances (EXT_mesh_gpu_instancing) and its data.
function expectations(glb) {
  const { json } = glb, out = [];
  const visit = (i) => {
    const node = json.nodes[i];
    if (node.mesh !== undefined) {
      const prims = json.meshes[node.mesh].primitives;
      const inst = node.extensions?.EXT_mesh_gpu_instancing;
      prims.forEach((p, k) => out.push({
        name: prims.length === 1 ? node.name : `${node.name}_primitive${k}`,
        vertices: json.accessors[p.attributes.POSITION].count,
        indices: json.accessors[p.indices].count,
        instances: inst ? json.accessors[inst.attributes.TRANSLATION].count : 0,
        translation: inst ? inst.attributes.TRANSLATION : undefined,
        first: k === 0,
        primitive: p,
      }));
    }
    for (const c of node.children || []) visit(c);
  };
  for (const i of json.scenes[json.scene ?? 0].nodes || []) visit(i);
  return out;
}

// --- loading -----------------------------------------------------------
async function load(bytes, { attributes }) {
  if (attributes) registerGLTFExtension(docs.name, docs.isGLTFExtension, docs.factory);
  const engine = new NullEngine();
  const scene = new Scene(engine);
  const errors0 = Logger.errorsCount;
  const lodLevels = [];
  let complete;
  const completed = new Promise((resolve) => { complete = resolve; });
  const pluginObserver = SceneLoader.OnPluginActivatedObservable.addOnce((plugin) => {
    plugin.onCompleteObservable.addOnce(() => complete());
    plugin.onExtensionLoadedObservable.add((e) => {
      if (e.name === 'MSFT_lod') e.onNodeLODsLoadedObservable.add((i) => lodLevels.push(i));
    });
  });
  try {
    await AppendSceneAsync(new Uint8Array(bytes), scene, { pluginExtension: '.glb' });
    await completed;   // every MSFT_lod level has loaded
    return { engine, scene, lodLevels, errors: Logger.errorsCount - errors0 };
  } catch (e) {
    scene.dispose();
    engine.dispose();
    throw e;
  } finally {
    SceneLoader.OnPluginActivatedObservable.remove(pluginObserver);
    if (attributes) unregisterGLTFExtension(docs.name);
  }
}

function sameValues(a, b) {
  if (!a || !b || a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i] && !(Number.isNaN(a[i]) && Number.isNaN(b[i]))) return false;
  return true;
}

// The checks of one load against the file `glb` (the complete file: the
// loaded bytes may be a control that differs). Returns the failures.
function check(glb, { scene, lodLevels, errors }, { attributes, textured, lod }) {
  const fail = [];
  if (errors) fail.push(`${errors} error(s) logged by Babylon`);
  const expected = expectations(glb);
  const byName = new Map(scene.meshes.map((m) => [m.name, m]));
  const drawn = scene.meshes.filter((m) => m.getTotalVertices() > 0).map((m) => m.name).sort();
  const names = expected.map((e) => e.name).sort();
  if (drawn.join() !== names.join()) fail.push(`meshes with geometry: [${drawn}], the file's scene: [${names}]`);
  const KEEP = { POSITION: 'position', NORMAL: 'normal', TEXCOORD_0: 'uv' };
  const UVS = { TEXCOORD_1: 'uv2', TEXCOORD_2: 'uv3', TEXCOORD_3: 'uv4', TEXCOORD_4: 'uv5' };
  for (const e of expected) {
    const m = byName.get(e.name);
    if (!m) continue;
    const where = `${e.name}:`;
    if (m.getTotalVertices() !== e.vertices || m.getTotalIndices() !== e.indices)
      fail.push(`${where} ${m.getTotalVertices()} vertices, ${m.getTotalIndices()} indices; the file: ${e.vertices}, ${e.indices}`);
    if (!m.isEnabled()) fail.push(`${where} not enabled`);
    if ((m.thinInstanceCount || 0) !== e.instances) {
      fail.push(`${where} ${m.thinInstanceCount} thin instances, the file: ${e.instances}`);
    } else if (e.instances) {
      // Each thin instance's matrix moves the mesh by the file's TRANSLATION.
      const want = accessorData(glb, e.translation), got = m.thinInstanceGetWorldMatrices();
      const off = got.findIndex((w, i) => [0, 1, 2].some((c) => Math.abs(w.m[12 + c] - want[3 * i + c]) > 1e-5));
      if (off >= 0) fail.push(`${where} thin instance ${off} is not at the file's TRANSLATION`);
    }
    if (!sameValues(m.getIndices(), accessorData(glb, e.primitive.indices))) fail.push(`${where} indices differ from the file's`);
    const kinds = m.getVerticesDataKinds();
    for (const [attr, kind] of Object.entries({ ...KEEP, ...UVS })) {
      if (!(attr in e.primitive.attributes)) {
        if (kinds.includes(kind)) fail.push(`${where} has ${kind}, the file has no ${attr}`);
      } else if (!sameValues(m.getVerticesData(kind), accessorData(glb, e.primitive.attributes[attr]))) {
        fail.push(`${where} ${attr} (${kind}) ${kinds.includes(kind) ? 'differs from the file' : 'missing'}`);
      }
    }
    const custom = Object.keys(e.primitive.attributes).filter((n) => n.startsWith('_'));
    if (!custom.includes('_WIND_PIVOT_X') || !custom.includes('_BIRTH'))
      fail.push(`${where} the file lacks the wind or birth attributes`);
    for (const n of custom) {
      if (!attributes) {
        if (kinds.includes(n)) fail.push(`${where} the stock loader kept ${n} (update docs/game-engines.md)`);
      } else if (!sameValues(m.getVerticesData(n), accessorData(glb, e.primitive.attributes[n]))) {
        fail.push(`${where} ${n} ${kinds.includes(n) ? 'differs from the file' : 'missing'}`);
      }
    }
    if (textured) {
      const mat = m.material;
      const want = glb.json.materials[e.primitive.material]?.pbrMetallicRoughness?.baseColorTexture;
      if (!want) fail.push(`${where} the file's material has no base colour texture`);
      else if (!mat?.albedoTexture || mat.albedoTexture.mimeType !== 'image/png')
        fail.push(`${where} material ${mat?.name} has no PNG base colour texture`);
    }
  }
  const images = (glb.json.images || []).length;
  if (textured && images === 0) fail.push('the file has no images');
  const textures = scene.textures.filter((t) => t.mimeType).length;
  if (textures !== images) fail.push(`${textures} image textures in the scene, the file has ${images} images`);
  const levels = glb.json.nodes.map((n) => n.extensions?.MSFT_lod?.ids.length ?? -1).reduce((a, b) => Math.max(a, b), -1) + 1;
  if (lod && levels < 4) fail.push(`the file has ${levels} MSFT_lod levels, expected 4`);
  if (lodLevels.length !== Math.max(levels, 0))
    fail.push(`Babylon reported ${lodLevels.length} MSFT_lod levels, the file has ${levels}`);
  return fail;
}

// --- the cases ---------------------------------------------------------
mkdirSync(outDir, { recursive: true });
const preset = (n) => path.join(repo, 'presets', n);
const CASES = [
  { name: 'roots', args: ['roots', '--textures', 'off'] },
  { name: 'keyaki_young', args: ['keyaki', '--preset', preset('keyaki_young.json'), '--texture-size', '256'], textured: true },
  { name: 'ivy_wall', args: ['ivy', '--preset', preset('ivy_wall.json'), '--texture-size', '256'], textured: true },
  { name: 'avenue_variants', args: ['avenue', '--preset', preset('avenue_young.json'), '--set', 'end=18,0,0',
                                    '--set', 'variants=3', '--engine-uvs', '--textures', 'off'], instanced: true },
  { name: 'keyaki_lod', args: ['keyaki', '--preset', preset('keyaki_young.json'), '--lod', '0.5,0.15,billboard',
                               '--textures', 'off'], lod: true },
];

let failed = 0, passed = 0;
const report = (name, fail, ms, note = '') => {
  if (fail.length) {
    failed++;
    console.log(`FAIL ${name}${note} (${ms} ms)`);
    for (const f of fail.slice(0, 20)) console.log(`  ${f}`);
  } else {
    passed++;
    console.log(`ok   ${name}${note} (${ms} ms)`);
  }
};

const files = {};
for (const c of CASES) {
  const file = path.join(outDir, `${c.name}.glb`);
  const r = spawnSync(cli, [...c.args, '--threads', '2', '-o', file], { encoding: 'utf8' });
  if (r.status !== 0) {
    report(c.name, [`banyan ${c.args.join(' ')} exited ${r.status}: ${r.stderr}`], 0);
    continue;
  }
  const bytes = readFileSync(file);
  const glb = parseGlb(bytes);
  files[c.name] = { bytes, glb };
  for (const attributes of [false, true]) {
    const t = Date.now();
    let fail;
    try {
      const loaded = await load(bytes, { attributes });
      fail = check(glb, loaded, { ...c, attributes });
      if (c.instanced && !expectations(glb).some((e) => e.instances > 0)) fail.push('the file has no EXT_mesh_gpu_instancing node');
      if (c.instanced && !expectations(glb).every((e) => 'TEXCOORD_4' in e.primitive.attributes))
        fail.push('the file lacks TEXCOORD_1..4');
      const ex = expectations(glb);
      const note = ` [${attributes ? 'with the docs extension' : 'stock loader'}: ${ex.length} meshes, `
        + `${ex.reduce((s, e) => s + e.vertices, 0)} vertices, ${ex.reduce((s, e) => s + e.indices, 0)} indices`
        + (c.instanced ? `, ${ex.filter((e) => e.first).reduce((s, e) => s + e.instances, 0)} trees as thin instances` : '')
        + (c.lod ? `, MSFT_lod levels reported ${loaded.lodLevels.length}` : '') + ']';
      loaded.scene.dispose();
      loaded.engine.dispose();
      report(c.name, fail, Date.now() - t, note);
    } catch (e) {
      report(c.name, [`load failed: ${e.message}`], Date.now() - t, attributes ? ' [with the docs extension]' : ' [stock loader]');
    }
  }
}

// --- controls: these must not pass -------------------------------------
if (files.roots) {
  const { bytes, glb } = files.roots;
  const truncated = bytes.subarray(0, bytes.length >> 1);
  writeFileSync(path.join(outDir, 'control_truncated.glb'), truncated);
  let t = Date.now();
  try {
    const loaded = await load(truncated, { attributes: true });
    loaded.scene.dispose();
    loaded.engine.dispose();
    report('control_truncated', ['a .glb cut in half loaded'], Date.now() - t);
  } catch (e) {
    report('control_truncated', [], Date.now() - t, ` (rejected: ${String(e.message).split('\n')[0].slice(0, 100)})`);
  }
  // The same file whose _WIND_PHASE is its stiffness, checked against the real file.
  const json = structuredClone(glb.json);
  for (const m of json.meshes) for (const p of m.primitives) p.attributes._WIND_PHASE = p.attributes._WIND_STIFFNESS;
  let text = Buffer.from(JSON.stringify(json));
  text = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
  const binChunk = bytes.subarray(20 + bytes.readUInt32LE(12));
  const head = Buffer.alloc(20);
  head.write('glTF', 0);
  head.writeUInt32LE(2, 4);
  head.writeUInt32LE(20 + text.length + binChunk.length, 8);
  head.writeUInt32LE(text.length, 12);
  head.writeUInt32LE(0x4e4f534a, 16);
  const dropped = Buffer.concat([head, text, binChunk]);
  writeFileSync(path.join(outDir, 'control_wrong_phase.glb'), dropped);
  t = Date.now();
  try {
    const loaded = await load(dropped, { attributes: true });
    const fail = check(glb, loaded, { attributes: true });
    loaded.scene.dispose();
    loaded.engine.dispose();
    report('control_wrong_phase', fail.length ? [] : ['a mesh whose _WIND_PHASE is its stiffness passed the checks'], Date.now() - t,
           fail.length ? ` (caught: ${fail[0]})` : '');
  } catch (e) {
    report('control_wrong_phase', [`load failed: ${e.message}`], Date.now() - t);
  }
} else {
  report('controls', ['roots.glb was not written'], 0);
}

console.log(`${passed} passed, ${failed} failed (${((Date.now() - T0) / 1000).toFixed(1)} s)`);
process.exit(failed ? 1 : 0);
