// Small .glb helpers for the viewer tests: read the JSON chunk, and
// (only while the CLI's glTF writer does not yet emit them) add stand-in
// wind attributes to a CLI-made .glb.
import { readFileSync } from 'node:fs';

export function readGlb(file) {
  const b = Buffer.isBuffer(file) ? file : readFileSync(file);
  const jsonLen = b.readUInt32LE(12);
  const json = JSON.parse(b.subarray(20, 20 + jsonLen).toString('utf8'));
  const binAt = 20 + jsonLen;
  const bin = binAt + 8 <= b.length ? b.subarray(binAt + 8, binAt + 8 + b.readUInt32LE(binAt)) : Buffer.alloc(0);
  return { json, bin };
}

export function writeGlb(json, bin) {
  let text = Buffer.from(JSON.stringify(json));
  text = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
  bin = Buffer.concat([bin, Buffer.alloc((4 - (bin.length % 4)) % 4, 0)]);
  const header = Buffer.alloc(12), jh = Buffer.alloc(8), bh = Buffer.alloc(8);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + text.length + 8 + bin.length, 8);
  jh.writeUInt32LE(text.length, 0);
  jh.writeUInt32LE(0x4e4f534a, 4);
  bh.writeUInt32LE(bin.length, 0);
  bh.writeUInt32LE(0x004e4942, 4);
  return Buffer.concat([header, jh, text, bh, bin]);
}

// The meshes the default scene draws (MSFT_lod levels, reachable only
// through the extension, are not among them), once per node that uses them.
export function sceneMeshes(json) {
  const out = [];
  const visit = (i) => {
    const n = json.nodes[i];
    if (n.mesh !== undefined) out.push(json.meshes[n.mesh]);
    for (const c of n.children || []) visit(c);
  };
  for (const i of json.scenes[json.scene ?? 0].nodes || []) visit(i);
  return out;
}

export function hasWindAttributes(json) {
  return (json.meshes || []).some((m) => m.primitives.some((p) => '_WIND_PIVOT' in p.attributes && '_WIND_PARAMS' in p.attributes));
}

// A stand-in for the writer's wind attributes on a single tree: every
// vertex sways about the foot of the plant's vertical axis (the bounds'
// bottom centre), stiffness falls from 1 at the ground to 0 at the top,
// leaves (alpha-masked materials) flutter. Crude, but with the same
// layout and frame as the real ones, for developing the viewer.
// instances: when the file has no EXT_mesh_gpu_instancing (the writer's
// instancing not yet there either), also place the first mesh node twice
// with it (at 0 and 40 m along banyan's +y).
export function withStandInWind(buffer, { instances = false } = {}) {
  const { json, bin } = readGlb(buffer);
  const parts = [bin];
  let length = bin.length;
  const add = (floats, type, count) => {
    const bytes = Buffer.from(floats.buffer);
    json.bufferViews.push({ buffer: 0, byteOffset: length, byteLength: bytes.length });
    json.accessors.push({ bufferView: json.bufferViews.length - 1, componentType: 5126, count, type });
    parts.push(bytes);
    length += bytes.length;
    return json.accessors.length - 1;
  };
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const m of json.meshes) for (const p of m.primitives) {
    const a = json.accessors[p.attributes.POSITION];
    for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], a.min[k]); hi[k] = Math.max(hi[k], a.max[k]); }
  }
  const foot = [(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2];
  const height = Math.max(hi[1] - lo[1], 1e-6);
  const done = new Map();
  for (const m of json.meshes) for (const p of m.primitives) {
    if (done.has(p.attributes.POSITION)) { Object.assign(p.attributes, done.get(p.attributes.POSITION)); continue; }
    const a = json.accessors[p.attributes.POSITION];
    const v = json.bufferViews[a.bufferView];
    const stride = v.byteStride || 12;
    const leaf = p.material !== undefined && json.materials[p.material].alphaMode === 'MASK';
    const pivot = new Float32Array(a.count * 3), params = new Float32Array(a.count * 4);
    for (let i = 0; i < a.count; i++) {
      const y = bin.readFloatLE((v.byteOffset || 0) + (a.byteOffset || 0) + i * stride + 4);
      pivot.set(foot, i * 3);
      params.set([leaf ? 1 : 0, Math.sqrt(1 - Math.min(Math.max((y - lo[1]) / height, 0), 1)),
                  ((i >> 6) * 0.618034) % 1, leaf ? 1 : 0], i * 4);
    }
    const attrs = { _WIND_PIVOT: add(pivot, 'VEC3', a.count), _WIND_PARAMS: add(params, 'VEC4', a.count) };
    done.set(p.attributes.POSITION, attrs);
    Object.assign(p.attributes, attrs);
  }
  if (instances && !(json.extensionsUsed || []).includes('EXT_mesh_gpu_instancing')) {
    const n = json.nodes.find((x) => x.mesh !== undefined);
    n.extensions = { ...(n.extensions || {}), EXT_mesh_gpu_instancing: { attributes: {
      TRANSLATION: add(new Float32Array([0, 0, 0, 0, 0, -40]), 'VEC3', 2) } } };
    json.extensionsUsed = [...new Set([...(json.extensionsUsed || []), 'EXT_mesh_gpu_instancing'])];
  }
  json.buffers[0].byteLength = length;
  return writeGlb(json, Buffer.concat(parts));
}
