// Small .glb helpers for the viewer tests: read the JSON chunk, write a
// .glb, list the meshes the scene draws, tell whether a file carries the
// writer's wind attributes.
import { closeSync, openSync, readSync } from 'node:fs';

// The JSON chunk of a .glb file. Only the header and the JSON are read:
// preset files can pass 2 GiB (avenue_boulevard with its wind
// attributes), more than one Node Buffer holds.
export function readGlb(file) {
  const fd = openSync(file, 'r');
  try {
    const head = Buffer.alloc(20);
    readSync(fd, head, 0, 20, 0);
    const text = Buffer.alloc(head.readUInt32LE(12));
    readSync(fd, text, 0, text.length, 20);
    return { json: JSON.parse(text.toString('utf8')) };
  } finally {
    closeSync(fd);
  }
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
  return (json.meshes || []).some((m) => m.primitives.some((p) => '_WIND_PIVOT_X' in p.attributes && '_WIND_STIFFNESS' in p.attributes));
}
