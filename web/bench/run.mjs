#!/usr/bin/env node
// Browser decoding benchmark: dbss WASM vs draco3d WASM in headless
// Chromium, levels 3-5 of the shipped example encoded with 5 levels.
//
//   node web/bench/run.mjs [--scalar | --compare DIR] [--file FILE.dbss] [--samples N] [--wall] [--streaming] [--json]
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
// --streaming also times the streaming case as its own side: a decoder that
// already holds level L - 1 gets LEVL L's bytes and decodes level L
// (columns "L-1 -> L"; draco3d still decodes all of level L).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, readdirSync, statSync } from 'node:fs';
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
const samplesArg = process.argv.indexOf('--samples');
const samples = samplesArg > 0 ? Number(process.argv[samplesArg + 1]) : 21;
const wall = process.argv.includes('--wall');
const streaming = process.argv.includes('--streaming');
const compareArg = process.argv.indexOf('--compare');
const compareDir = compareArg > 0 ? resolve(process.argv[compareArg + 1]) : null;
const other = scalar ? 'scalar' : compareDir ? 'other' : null;
const mounts = { ...repoMounts(repo, buildDir), '/bench-files/': work, '/bench-input/': dirname(file),
  '/other/': compareDir ?? join(buildDir, 'dist') };
const { server, url } = await startServer({ mounts });
const browser = await chromium.launch({ executablePath: process.env.DBSS_CHROMIUM ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
// CPU time, not wall time: on a shared machine the wall clock counts the
// time other processes held the CPU (at a load average of 14 on 2 cores,
// a 0.6 ms decode took 5 ms of wall time).  The page asks for the CPU time
// of the renderer's main thread (where its JavaScript and WebAssembly run)
// before and after each sample: nanoseconds from Linux's
// /proc/PID/task/TID/schedstat, summed over every renderer this process started
// (the idle ones add nothing).  --wall times with performance.now().
function rendererMainThreads() {
  const root = process.pid;  // playwright starts the browser as this process's child
  if (!existsSync('/proc/self/schedstat')) return [];
  const parent = new Map();
  for (const d of readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    try { parent.set(Number(d), Number(readFileSync(`/proc/${d}/stat`, 'utf8').replace(/^.*\) /s, '').split(' ')[1])); } catch {}
  }
  const ours = (pid) => { for (let p = pid; p > 1; p = parent.get(p) ?? 0) if (p === root) return true; return false; };
  // A renderer's main thread is the thread whose id is the process's.
  const out = [];
  for (const pid of parent.keys()) {
    try {
      if (ours(pid) && readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes('--type=renderer'))
        out.push(`/proc/${pid}/task/${pid}/schedstat`);
    } catch {}
  }
  return out;
}
async function measure(otherWasm) {
  const page = await browser.newPage();
  if (!wall) {
    let threads = null;
    await page.exposeFunction('dbssCpuNs', () => {
      threads ??= rendererMainThreads();
      if (!threads.length) throw new Error('no renderer thread found for CPU time (use --wall)');
      let ns = 0;
      for (const f of threads) try { ns += Number(readFileSync(f, 'utf8').split(' ')[0]); } catch {}
      return ns;
    });
  }
  const q = new URLSearchParams({ dbss: `/bench-input/${basename(file)}`, drc: `/bench-files/${stem}-level{L}.drc`, levels: levels.join(','),
    samples: String(samples) });
  if (otherWasm) q.set('other', otherWasm);
  if (streaming) q.set('streaming', '1');
  await page.goto(`${url}/web/bench/?${q}`);
  await page.waitForFunction(() => window.benchResult, null, { timeout: 300000 });
  const res = await page.evaluate(() => window.benchResult);
  await page.close();
  if (res.error) throw new Error(res.error);
  for (const r of res.rows) {
    if (r.hash !== native[r.level]) throw new Error(`level ${r.level}: browser hash ${r.hash}, native ${native[r.level]}`);
    if (otherWasm && r.otherHash !== native[r.level]) throw new Error(`level ${r.level}: the other build's hash ${r.otherHash}, native ${native[r.level]}`);
    if (streaming && r.incrementHash !== native[r.level]) throw new Error(`level ${r.level}: the streaming decoder's hash ${r.incrementHash}, native ${native[r.level]}`);
    if (r.dracoVertices !== r.vertices || r.dracoTriangles !== r.triangles) throw new Error(`level ${r.level}: Draco's mesh has other counts`);
  }
  return res;
}

// The builds and draco3d take turns in one page (bench.mjs).
const res = await measure(scalar ? '/other/dbss_wasm_scalar.mjs' : other ? '/other/dbss_wasm.mjs' : null);
await browser.close();
server.close();

const pad = (s, n) => String(s).padStart(n);
const f2 = (x) => x.toFixed(2);
// A median with its quartiles: "1.23 (1.20-1.31)".
const mq = (st, n) => pad(`${f2(st.median)} (${f2(st.q1)}-${f2(st.q3)})`, n);
const r0 = res.rows[0];
console.log(`${res.userAgent.match(/Chrome\/[\d.]+/)?.[0] ?? 'Chromium'}, headless, one thread; ${file.replace(repo, '')}; ` +
  `median (quartiles) of ${r0.dbss.n} samples per side taken in turns, each sample the mean of enough calls to take >= 150 ms; ` +
  `${res.clock}; the ${(res.emptySampleMs).toFixed(1)} ms an empty sample costs taken off each sample`);
if (compareDir) console.log(`other: the module in ${compareDir}`);
console.log(`level  triangles | dbss bytes        dbss ms        | draco bytes     draco3d ms       | draco3d / dbss per round${other ? ` | dbss ${other} ms` : ''}${streaming ? ` | dbss L-1 -> L ms      | draco3d / (L-1 -> L)` : ''}`);
res.rows.forEach((r) => {
  let line = `${pad(r.level, 5)} ${pad(r.triangles, 10)} | ${pad(r.dbssBytes, 10)} ${mq(r.dbss, 21)} | ${pad(r.dracoBytes, 11)} ${mq(r.draco, 22)} | ${mq(r.ratio, 24)}`;
  if (other) line += ` | ${mq(r.other, 21)}`;
  if (streaming) line += ` | ${mq(r.increment, 21)} | ${mq(r.incrementRatio, 22)}`;
  console.log(line);
});
console.log('every level hashes as build/bin/dbss decodes it' + (other ? ` (the ${other} build too)` : ''));
if (process.argv.includes('--json')) console.log(JSON.stringify(res.rows));

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
