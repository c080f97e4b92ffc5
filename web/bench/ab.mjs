#!/usr/bin/env node
// A/B of two node builds of the module in one process (no browser):
//
//   node web/bench/ab.mjs DIR_A DIR_B FILE.dbss [ROUNDS] [LEVELS] [--parse | --control]
//
// DIR_A and DIR_B each hold a dbss_wasm.cjs (+ .wasm), e.g. build-web/node
// and a copy of it from another commit.  For levels 3-5 of FILE: the whole
// decode of the bytes up to level L (fresh decoder, as web/bench's), each
// sample enough calls for >= 100 ms of this process's CPU time, the two
// builds in turns (the order alternating), ROUNDS (default 15) samples
// each.  Prints medians (quartiles) in ms and the median of per-round
// ratios B/A: on a loaded machine the rounds' ratios move much less than
// either side's times.  Why: a Chromium run (run.mjs --compare) costs a
// minute and a half; this one a fifth of that, with the same engine.
// LEVELS (default 3,4,5) picks the levels; --parse times only the bytes
// pushed up to level L (container, CRCs, the range decoder of levels
// 1..L), --control those bytes and level 0 (Draco, level 0's topology):
// a stage's change is then not lost in the whole decode's noise.
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { loadModule, StreamingDecoder } from '../dbss.mjs';
import { levelEnd } from '../loader.mjs';

const args = process.argv.slice(2);
const only = args.includes('--parse') ? 'parse' : args.includes('--control') ? 'control' : null;
const [dirA, dirB, file, rounds = '15', levelsArg = '3,4,5'] = args.filter((a) => !a.startsWith('--'));
if (!file) {
  console.error('usage: node web/bench/ab.mjs DIR_A DIR_B FILE.dbss [ROUNDS] [LEVELS] [--parse | --control]');
  process.exit(2);
}
const load = (dir) => loadModule(pathToFileURL(resolve(dir, 'dbss_wasm.cjs')).href);
const A = await load(dirA), B = await load(dirB);
const bytes = new Uint8Array(readFileSync(file));
const probe = new StreamingDecoder(A);
probe.push(bytes);
const run = (m, prefix, L) => {
  const d = new StreamingDecoder(m, { keepLevels: false });
  d.push(prefix);
  if (only !== 'parse') d.level(only === 'control' ? 0 : L);
  d.dispose();
};
const cpuMs = () => {
  const u = process.cpuUsage();
  return (u.user + u.system) / 1000;
};
const q = (xs, p) => [...xs].sort((a, b) => a - b)[Math.round(p * (xs.length - 1))];
const mq = (xs) => `${q(xs, 0.5).toFixed(3)} (${q(xs, 0.25).toFixed(3)}-${q(xs, 0.75).toFixed(3)})`;
for (const L of levelsArg.split(',').map(Number)) {
  const prefix = bytes.subarray(0, levelEnd(probe, L));
  for (let i = 0; i < 3; ++i) run(A, prefix, L), run(B, prefix, L);  // warm up both
  let reps = 1;
  for (;;) {
    const c = cpuMs();
    for (let i = 0; i < reps; ++i) run(A, prefix, L);
    if (cpuMs() - c > 100) break;
    reps *= 2;
  }
  const a = [], b = [], r = [];
  for (let k = 0; k < Number(rounds); ++k) {
    for (const [m, xs] of k % 2 ? [[B, b], [A, a]] : [[A, a], [B, b]]) {
      const c = cpuMs();
      for (let i = 0; i < reps; ++i) run(m, prefix, L);
      xs.push((cpuMs() - c) / reps);
    }
    r.push(b[b.length - 1] / a[a.length - 1]);
  }
  console.log(`${only ? `${only} of ` : ''}level ${L}: A ${mq(a)} ms, B ${mq(b)} ms, B/A per round ${mq(r)}`);
}
