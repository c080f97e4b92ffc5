#!/usr/bin/env node
// Where a whole decode of level L goes, stage by stage, in one node
// process (the web build's node module, CPU time of this process):
//
//   node web/bench/stages.mjs FILE.dbss [LEVELS, default 3,4] [DIR of dbss_wasm.cjs]
//
// Each stage is timed as the difference of two whole calls, each repeated
// for >= 100 ms of CPU, median of 7 samples:
//   parse 0     new decoder + the bytes up to the control mesh pushed
//   parse L     new decoder + the bytes up to level L pushed (container,
//               CRCs, LEVL decoding of levels 1..L)
//   level 0     parse L + level(0): the Draco control mesh, its topology
//   level k     parse L + level(k): every level up to k
// so "level k - level k-1" is level k's refinement step alone.
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { readFileSync } from 'node:fs';
import { loadModule, StreamingDecoder } from '../dbss.mjs';
import { levelEnd } from '../loader.mjs';

const [file, levelsArg = '3,4', dir] = process.argv.slice(2);
const m = dir ? await loadModule(pathToFileURL(resolve(dir, 'dbss_wasm.cjs')).href) : await loadModule();
const bytes = new Uint8Array(readFileSync(file));
const probe = new StreamingDecoder(m);
probe.push(bytes);
const cpuMs = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
function time(fn) {
  for (let i = 0; i < 3; ++i) fn();
  let reps = 1;
  for (;;) {
    const c = cpuMs();
    for (let i = 0; i < reps; ++i) fn();
    if (cpuMs() - c > 100) break;
    reps *= 2;
  }
  const xs = [];
  for (let s = 0; s < 7; ++s) {
    const c = cpuMs();
    for (let i = 0; i < reps; ++i) fn();
    xs.push((cpuMs() - c) / reps);
  }
  return xs.sort((a, b) => a - b)[3];
}
const call = (prefix, upTo) => () => {
  const d = new StreamingDecoder(m, { keepLevels: false });
  d.push(prefix);
  for (let l = 0; l <= upTo; ++l) if (l === upTo) d.level(l);
  d.dispose();
};
for (const L of levelsArg.split(',').map(Number)) {
  const prefix = bytes.subarray(0, levelEnd(probe, L));
  const rows = [['parse 0', time(call(bytes.subarray(0, levelEnd(probe, 0)), -1))],
    [`parse ${L}`, time(call(prefix, -1))]];
  for (let k = 0; k <= L; ++k) rows.push([`level ${k}`, time(call(prefix, k))]);
  const total = rows[rows.length - 1][1];
  console.log(`${file} level ${L}: whole decode ${total.toFixed(3)} ms`);
  let prev = 0;
  for (const [name, ms] of rows) {
    const own = name === 'parse 0' ? ms : ms - prev;
    console.log(`  ${name.padEnd(9)} ${ms.toFixed(3)} ms  (this stage ${own.toFixed(3)} ms, ${(100 * own / total).toFixed(1)}%)`);
    prev = ms;
  }
}
