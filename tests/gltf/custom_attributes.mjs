#!/usr/bin/env node
// Every preset's .glb, as the CLI writes it (--textures off), has only
// float SCALAR custom ("_"-prefixed) attributes, so every mesh's custom
// attributes share one element count: Blender's glTF importer before 5.2
// fails on a mesh whose custom attributes mix element counts, depending on
// Python's hash seed (docs/gltf.md, "Wind"). Also checks that the wind
// pivot's three scalars are there, as the writer converts them together.
//
//   node tests/gltf/custom_attributes.mjs BANYAN_CLI SOURCE_DIR OUT_DIR
//
// Each file is removed once read. Exits 1 on any failure.
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import path from 'node:path';

const [cli, src, outRoot] = process.argv.slice(2);
if (!cli || !src || !outRoot) {
  console.error('usage: node custom_attributes.mjs BANYAN_CLI SOURCE_DIR OUT_DIR');
  process.exit(2);
}
const out = path.join(outRoot, 'custom_attributes');
mkdirSync(out, { recursive: true });

function json(file) {
  const b = readFileSync(file);
  if (b.toString('latin1', 0, 4) !== 'glTF') throw new Error('not a .glb');
  return JSON.parse(b.toString('utf8', 20, 20 + b.readUInt32LE(12)));
}

let passed = 0, failed = 0;
const fail = (msg) => { failed++; console.log(`FAIL: ${msg}`); };
const presets = readdirSync(path.join(src, 'presets')).filter((n) => n.endsWith('.json')).sort();
if (presets.length === 0) fail('no preset in presets/');
for (const name of presets) {
  const preset = JSON.parse(readFileSync(path.join(src, 'presets', name), 'utf8'));
  const glb = path.join(out, name.replace(/\.json$/, '.glb'));
  // A *_large preset is a benchmark (ivy_wall_large: 7 M vertices), as in test_cli.sh.
  const extra = name.endsWith('_large.json') ? ['--set', 'steps=300'] : [];
  const r = spawnSync(cli, [preset.generator, '--preset', path.join(src, 'presets', name), '--textures', 'off',
    ...extra, '-o', glb], { encoding: 'utf8' });
  if (r.status !== 0) {
    fail(`${name}: banyan ${preset.generator} exited ${r.status}: ${r.stderr}`);
    continue;
  }
  let j;
  try {
    j = json(glb);
  } catch (e) {
    fail(`${name}: cannot read ${glb}: ${e.message}`);
    continue;
  } finally {
    rmSync(glb, { force: true });
  }
  const bad = [], counts = new Set(), names = new Set();
  (j.meshes || []).forEach((m, mi) => {
    const kinds = new Set();
    m.primitives.forEach((p, pi) => {
      for (const [k, a] of Object.entries(p.attributes)) {
        if (!k.startsWith('_')) continue;
        const acc = j.accessors[a];
        names.add(k);
        kinds.add(acc.type);
        if (acc.type !== 'SCALAR' || acc.componentType !== 5126) {
          bad.push(`mesh ${mi} primitive ${pi} ${k}: ${acc.type} of component type ${acc.componentType}`);
        }
      }
    });
    counts.add(kinds.size);
  });
  const wind = ['_WIND_PIVOT_X', '_WIND_PIVOT_Y', '_WIND_PIVOT_Z', '_WIND_LEVEL', '_WIND_STIFFNESS', '_WIND_PHASE',
    '_WIND_FLUTTER'];
  const windOff = !!preset.params && (preset.params.wind === false || preset.params['tree.wind'] === false);
  const missing = windOff ? [] : wind.filter((k) => !names.has(k));
  if (bad.length || [...counts].some((c) => c > 1) || missing.length) {
    fail(`${name}: ${bad.slice(0, 5).join('; ')}${missing.length ? ` missing ${missing.join(', ')}` : ''}`);
  } else {
    passed++;
    console.log(`ok ${name}: ${names.size} custom attributes, all float SCALAR`);
  }
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed > 0 ? 1 : 0);
