#!/usr/bin/env node
// Validates glTF files with the Khronos glTF validator.
//
//   node tests/gltf/validate.mjs [--no-warnings] FILE_OR_DIR...
//
// A directory stands for every .glb / .gltf file directly in it (at least
// one is required). Prints one line per file with its error / warning
// counts, then each error (and warning) message. Exits 1 when any file has
// errors (or, with --no-warnings, warnings: what banyan writes must have
// none) or cannot be read, 2 on bad usage. The validator comes from
// tests/gltf/node_modules:
//   npm install --prefix tests/gltf   (package.json pins gltf-validator)
import { createRequire } from 'node:module';
import { readFileSync, readdirSync, statSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, 'package.json'));

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error(`validate.mjs: cannot load gltf-validator from ${here}/node_modules: ${e.message}`);
  console.error(`install it with: npm install --prefix ${here}`);
  process.exit(2);
}

let args = process.argv.slice(2);
const noWarnings = args.includes('--no-warnings');
args = args.filter((a) => a !== '--no-warnings');
if (args.length === 0) {
  console.error('usage: node validate.mjs [--no-warnings] FILE_OR_DIR...');
  process.exit(2);
}

const SEVERITY = ['error', 'warning', 'info', 'hint'];
const isGltf = (name) => /\.(glb|gltf)$/i.test(name);

let failed = 0;
let passed = 0;
const files = [];
for (const arg of args) {
  let st;
  try {
    st = statSync(arg);
  } catch (e) {
    console.log(`${arg}: cannot read: ${e.message}`);
    failed++;
    continue;
  }
  if (st.isDirectory()) {
    const found = readdirSync(arg).filter(isGltf).sort().map((n) => path.join(arg, n));
    if (found.length === 0) {
      console.log(`${arg}: no .glb or .gltf file in this directory`);
      failed++;
    }
    files.push(...found);
  } else {
    files.push(arg);
  }
}

for (const file of files) {
  let bytes;
  try {
    bytes = new Uint8Array(readFileSync(file));
  } catch (e) {
    console.log(`${file}: cannot read: ${e.message}`);
    failed++;
    continue;
  }
  let report;
  try {
    report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0, // no limit
      // For .gltf files that point at external .bin / images.
      externalResourceFunction: (uri) =>
        new Promise((resolve, reject) => {
          try {
            resolve(new Uint8Array(readFileSync(path.join(path.dirname(file), decodeURIComponent(uri)))));
          } catch (e) {
            reject(e.message);
          }
        }),
    });
  } catch (e) {
    console.log(`${file}: validator failed: ${e && e.message ? e.message : e}`);
    failed++;
    continue;
  }
  const is = report.issues;
  console.log(`${file}: ${is.numErrors} errors, ${is.numWarnings} warnings, ` +
    `${is.numInfos} infos, ${is.numHints} hints`);
  for (const m of is.messages) {
    if (m.severity > 1) continue;
    const where = m.pointer ? ` at ${m.pointer}` : (m.offset !== undefined ? ` at byte ${m.offset}` : '');
    console.log(`  ${SEVERITY[m.severity]} ${m.code}${where}: ${m.message}`);
  }
  if (is.numErrors > 0 || (noWarnings && is.numWarnings > 0)) failed++;
  else passed++;
}

console.log(`${passed} passed, ${failed} failed`);
process.exit(failed > 0 ? 1 : 0);
