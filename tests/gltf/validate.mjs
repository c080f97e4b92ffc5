// Validates every .glb and .gltf file under the given files or directories
// with the Khronos glTF validator (pinned in package-lock.json).  Prints one
// line per file with its error, warning, info and hint counts and every
// error and warning message; exits 1 when any file has an error, when a
// file cannot be read, or when no file is found (a step that checked
// nothing must not pass).  Usage: node validate.mjs PATH...
import { readFile, readdir, stat } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

async function collect(p, out) {
  const s = await stat(p);
  if (s.isDirectory()) {
    for (const e of (await readdir(p)).sort()) await collect(path.join(p, e), out);
  } else if (/\.(glb|gltf)$/i.test(p)) {
    out.push(p);
  }
}

const files = [];
for (const p of process.argv.slice(2)) await collect(p, files);
if (files.length === 0) {
  console.error('validate: no .glb or .gltf files in ' + process.argv.slice(2).join(' '));
  process.exit(1);
}

let failed = 0;
for (const file of files) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    // A .gltf's buffers may sit beside it.
    externalResourceFunction: (uri) =>
      readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  for (const m of i.messages)
    if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} at ${m.pointer ?? m.offset}: ${m.message}`);
  if (i.numErrors > 0) failed++;
}
console.log(`validate: ${files.length} files, ${failed} with errors`);
process.exit(failed > 0 ? 1 : 0);
