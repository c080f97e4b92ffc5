#!/usr/bin/env node
// Browser decoding benchmark: dbss WASM vs draco3d WASM in headless
// Chromium, levels 3-5 of the shipped example encoded with 5 levels.
//
//   node web/bench/run.mjs [--scalar | --compare DIR] [--file FILE.dbss]
//
// FILE (default: the shipped example encoded with 5 levels) needs levels
// 3-5.  Makes its files in build-web/bench/ with build/bin/dbss (encode, decode
// --level L to PLY) and Debian's draco_encoder (its defaults), serves them,
// and prints a table and the gzipped sizes of what a page ships.  --scalar
// also times the build without WebAssembly SIMD (build-web/dist/
// dbss_wasm_scalar.*, what loadModule() falls back to) after checking that
// it gives the same hashes;
// --compare DIR times another web build of the module (DIR holds its
// dbss_wasm.mjs and .wasm, e.g. one built from an older commit) the same way.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, statSync } from 'node:fs';
import { basename, dirname, join, resolve } from 'node:path';
import { gzipSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer, repoMounts } from '../tools/serve.mjs';

const repo = fileURLToPath(new URL('../..', import.meta.url));
const buildDir = join(repo, 'build-web');
const dbss = process.env.DBSS_BIN ?? join(repo, 'build/bin/dbss');
const work = join(buildDir, 'bench');
const levels = [3, 4, 5];
mkdirSync(work, { recursive: true });

function run(cmd, args) {
  const r = spawnSync(cmd, args, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`${cmd} ${args.join(' ')}: ${r.error ?? r.stderr}`);
  return r.stdout;
}

const fileArg = process.argv.indexOf('--file');
const file = fileArg > 0 ? resolve(process.argv[fileArg + 1]) : join(work, 'double-torus-5.dbss');
if (fileArg < 0 && !existsSync(file)) run(dbss, ['encode', join(repo, 'examples/double-torus.xyz'), '-o', file, '--levels', '5']);
const stem = basename(file, '.dbss');
const native = run(dbss, ['info', file, '--hashes']).trim().split('\n').map((l) => l.split(' ').pop());
for (const L of levels) {
  const ply = join(work, `${stem}-level${L}.ply`), drc = join(work, `${stem}-level${L}.drc`);
  if (!existsSync(drc) || statSync(drc).mtimeMs < statSync(file).mtimeMs) {
    run(dbss, ['decode', file, '--level', String(L), '-o', ply]);
    run('draco_encoder', ['-i', ply, '-o', drc]);
  }
}

const scalar = process.argv.includes('--scalar');
const compareArg = process.argv.indexOf('--compare');
const compareDir = compareArg > 0 ? resolve(process.argv[compareArg + 1]) : null;
const other = scalar ? 'scalar' : compareDir ? 'other' : null;
const mounts = { ...repoMounts(repo, buildDir), '/bench-files/': work, '/bench-input/': dirname(file),
  '/other/': compareDir ?? join(buildDir, 'dist') };
const { server, url } = await startServer({ mounts });
const browser = await chromium.launch({ executablePath: process.env.DBSS_CHROMIUM ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
async function measure(otherWasm) {
  const page = await browser.newPage();
  const q = new URLSearchParams({ dbss: `/bench-input/${basename(file)}`, drc: `/bench-files/${stem}-level{L}.drc`, levels: levels.join(',') });
  if (otherWasm) q.set('other', otherWasm);
  await page.goto(`${url}/web/bench/?${q}`);
  await page.waitForFunction(() => window.benchResult, null, { timeout: 300000 });
  const res = await page.evaluate(() => window.benchResult);
  await page.close();
  if (res.error) throw new Error(res.error);
  for (const r of res.rows) {
    if (r.hash !== native[r.level]) throw new Error(`level ${r.level}: browser hash ${r.hash}, native ${native[r.level]}`);
    if (otherWasm && r.otherHash !== native[r.level]) throw new Error(`level ${r.level}: the other build's hash ${r.otherHash}, native ${native[r.level]}`);
    if (r.dracoVertices !== r.vertices || r.dracoTriangles !== r.triangles) throw new Error(`level ${r.level}: Draco's mesh has other counts`);
  }
  return res;
}

// The builds and draco3d take turns in one page (bench.mjs).
const res = await measure(scalar ? '/other/dbss_wasm_scalar.mjs' : other ? '/other/dbss_wasm.mjs' : null);
await browser.close();
server.close();

const pad = (s, n) => String(s).padStart(n);
console.log(`${res.userAgent.match(/Chrome\/[\d.]+/)?.[0] ?? 'Chromium'}, headless, one thread; ${file.replace(repo, '')}; best of repetitions`);
if (compareDir) console.log(`other: the module in ${compareDir}`);
console.log(`level  triangles |  dbss bytes  dbss ms | draco bytes  draco3d ms | draco3d / dbss${other ? ` | dbss ${other} ms  ratio` : ''}`);
res.rows.forEach((r, i) => {
  let line = `${pad(r.level, 5)} ${pad(r.triangles, 10)} | ${pad(r.dbssBytes, 11)} ${pad(r.dbssMs.toFixed(2), 8)} | ${pad(r.dracoBytes, 11)} ${pad(r.dracoMs.toFixed(2), 11)} | ${pad((r.dracoMs / r.dbssMs).toFixed(2) + 'x', 14)}`;
  if (other) line += ` | ${pad(r.otherMs.toFixed(2), 12)} ${pad((r.dracoMs / r.otherMs).toFixed(2) + 'x', 6)}`;
  console.log(line);
});
console.log('every level hashes as build/bin/dbss decodes it' + (other ? ` (the ${other} build too)` : ''));

// What a page ships, gzipped (-9).
const gz = (p) => gzipSync(readFileSync(p), { level: 9 }).length;
const sizes = [
  ['dbss wasm, SIMD (build-web/dist/dbss_wasm.wasm)', join(buildDir, 'dist/dbss_wasm.wasm')],
  ['dbss glue, SIMD (dbss_wasm.mjs)', join(buildDir, 'dist/dbss_wasm.mjs')],
  ['dbss wasm, scalar (dbss_wasm_scalar.wasm)', join(buildDir, 'dist/dbss_wasm_scalar.wasm')],
  ['dbss glue, scalar (dbss_wasm_scalar.mjs)', join(buildDir, 'dist/dbss_wasm_scalar.mjs')],
  ['dbss API (dbss.mjs, loader.mjs, hash.mjs, worker.mjs)', ['dbss.mjs', 'loader.mjs', 'hash.mjs', 'worker.mjs'].map((f) => join(repo, 'web', f))],
  ['draco3d wasm (draco_decoder.wasm)', join(repo, 'web/node_modules/draco3d/draco_decoder.wasm')],
  ['draco3d glue (draco_decoder_nodejs.js)', join(repo, 'web/node_modules/draco3d/draco_decoder_nodejs.js')],
];
console.log('\nshipped                                                    bytes   gzipped');
for (const [name, p] of sizes) {
  const ps = [p].flat();
  const raw = ps.reduce((s, f) => s + readFileSync(f).length, 0), z = ps.reduce((s, f) => s + gz(f), 0);
  console.log(`${name.padEnd(56)} ${pad(raw, 8)} ${pad(z, 9)}`);
}
