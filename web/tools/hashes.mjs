#!/usr/bin/env node
// node web/tools/hashes.mjs FILE.dbss
// Prints, per verified level, the line `dbss info FILE --hashes` prints
// ('level L vertices V triangles T fnv1a64 HEX', spec/decoding.md section
// 8), decoding with the WebAssembly build, so the two outputs compare with
// diff.  Like the native command, a damaged or cut file still lists the
// levels verified before the damage, and the error goes to stderr with a
// non-zero exit.
import { readFileSync } from 'node:fs';
import { loadModule, StreamingDecoder } from '../dbss.mjs';
import { fnv1a64 } from '../hash.mjs';

const path = process.argv[2];
if (!path || process.argv.length > 3) {
  console.error('usage: node web/tools/hashes.mjs FILE.dbss');
  process.exit(2);
}
let bytes;
try {
  bytes = readFileSync(path);
} catch (e) {
  console.error(`hashes: ${path}: ${e.message}`);
  process.exit(1);
}
const d = new StreamingDecoder(await loadModule());
let error = null;
try {
  d.push(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.length));
  d.finish();
} catch (e) {
  error = e;
}
const lines = [];
try {
  for (let l = 0; l < d.levelsReady(); ++l) {
    const { positions, indices } = d.level(l);
    lines.push(`level ${l} vertices ${positions.length / 3} triangles ${indices.length / 3} fnv1a64 ${fnv1a64(positions)}`);
  }
} catch (e) {
  error ??= e;
}
process.stdout.write(lines.map((s) => s + '\n').join(''));
if (error) {
  console.error(`hashes: ${path}: ${error.message}`);
  process.exit(1);
}
