// Decoding speed in the browser, one page, one thread: dbss's WebAssembly
// decoder (the whole decode of level L from the file's bytes up to level
// L's chunk: the bytes copied into the module, container and checksums,
// the Draco control mesh, every level up to L) against draco3d's
// WebAssembly decoder (npm) decoding the same level's mesh, made with
// draco_encoder at its defaults (its bytes copied into its module, the
// decode, positions and triangles copied into its memory as arrays).  Both
// end with positions and triangle indices in their module's memory; a
// fresh decoder each call on both sides.  Medians and quartiles of
// `samples` samples per side, taken in turns (see calibrate and sample).
//
// ?dbss=URL&levels=3,4,5&drc=URL_PATTERN (with {L} for the level)
//  &wasm=URL of the dbss module (default build-web/dist/dbss_wasm.mjs)
//  &other=URL of another build of it, timed the same way (optional)
//  &samples=N (default 21)
//  &streaming=1: also time level L decoded by a decoder that holds L - 1
//  (dbssIncrement), as its own side
import { loadModule, StreamingDecoder } from '../dbss.mjs';
import { levelEnd } from '../loader.mjs';
import { fnv1a64 } from '../hash.mjs';

const params = new URLSearchParams(location.search);
const levels = (params.get('levels') ?? '3,4,5').split(',').map(Number);
const out = document.getElementById('out');

// Timing.  A sample runs a decode `reps` times in a row, enough to last
// >= 150 ms of CPU time (see calibrate), and gives the time per call: the browser's clock is coarse (0.1
// ms steps), and with run.mjs's CPU clock (window.dbssCpuNs, the renderer
// thread's CPU time read by node between samples) each reading costs a
// round trip whose tail the sample counts.  Each side is warmed up and
// calibrated alone, then the samples alternate (dbss, draco3d, [other
// build], then the reverse order) so that a busy machine slows all of them
// alike; each row reports every side's median and quartiles, and the median
// of the per-round ratios (draco3d / dbss of samples taken back to back).
// Warms fn up, then doubles reps until a sample lasts >= 150 ms on the
// clock the samples use.  Why so long: each CPU clock reading is a round
// trip to node that costs the renderer several ms of its own CPU time
// (about 7 ms measured here); `overheadMs`, the median of empty samples,
// is subtracted from every sample, and at 150 ms what is left of its
// spread is a few percent of a sample, on both sides alike.
let overheadMs = 0;
async function calibrate(fn) {
  for (let i = 0; i < 3; ++i) await sample(fn, 1);  // warm up: compile tiers, grow memory
  let reps = 1;
  while ((await sample(fn, reps)) * reps < (window.dbssCpuNs ? 150 : 20) && reps < 65536) reps *= 2;
  return reps;
}
// With window.dbssCpuNs (run.mjs provides it), a sample is CPU time of the
// page's thread; else wall time.
// fn.prepare(reps), when fn has it, runs before the clock starts and its
// result is passed to every call as fn(i, prepared); fn.done(prepared)
// after the clock stops (the streaming side's decoders already at level
// L - 1).
async function sample(fn, reps) {
  const state = fn.prepare ? fn.prepare(reps) : undefined;
  let ms;
  if (window.dbssCpuNs) {
    const c = await window.dbssCpuNs();
    for (let i = 0; i < reps; ++i) fn(i, state);
    ms = ((await window.dbssCpuNs() - c) / 1e6 - overheadMs) / reps;
  } else {
    const t = performance.now();
    for (let i = 0; i < reps; ++i) fn(i, state);
    ms = (performance.now() - t) / reps;
  }
  if (fn.done) fn.done(state);
  return ms;
}
function quantile(xs, q) {
  const s = [...xs].sort((a, b) => a - b), i = q * (s.length - 1), lo = Math.floor(i);
  return lo + 1 < s.length ? s[lo] + (i - lo) * (s[lo + 1] - s[lo]) : s[lo];
}
const stats = (xs) => ({ median: quantile(xs, 0.5), q1: quantile(xs, 0.25), q3: quantile(xs, 0.75),
  min: Math.min(...xs), max: Math.max(...xs), n: xs.length });

// One dbss decode of level L from `prefix` (new decoder, bytes copied into
// the module, control mesh, every level up to L, views of the result).
function dbssCall(module, prefix, L, info) {
  return () => {
    const d = new StreamingDecoder(module, { keepLevels: false });
    d.push(prefix);
    const v = d.level(L);
    if (!info.hash) {
      info.vertices = v.positions.length / 3;
      info.triangles = v.indices.length / 3;
      info.hash = fnv1a64(v.positions);
    }
    d.dispose();
  };
}

// The streaming case: a viewer that holds level L - 1 (a decoder that has
// decoded it from the bytes up to it) receives level L's bytes and decodes
// level L: the bytes of LEVL L pushed (copy, CRC, range decoding) and one
// refinement step.  The decoders at level L - 1 are made before the clock
// starts.
function dbssIncrement(module, before, prefix, L, info) {
  const head = prefix.subarray(0, before), tail = prefix.subarray(before);
  const fn = (i, ds) => {
    const d = ds[i];
    d.push(tail);
    const v = d.level(L);
    if (!info.hash) info.hash = fnv1a64(v.positions);
  };
  fn.prepare = (reps) => Array.from({ length: reps }, () => {
    const d = new StreamingDecoder(module, { keepLevels: false });
    d.push(head);
    d.level(L - 1);
    return d;
  });
  fn.done = (ds) => ds.forEach((d) => d.dispose());
  return fn;
}

async function run() {
  const module = await loadModule(params.get('wasm') ?? undefined);
  const otherModule = params.get('other') ? await loadModule(params.get('other')) : null;
  const samples = Number(params.get('samples') ?? 21);
  const streaming = params.get('streaming') === '1';
  const file = new Uint8Array(await (await fetch(params.get('dbss'))).arrayBuffer());
  const probe = new StreamingDecoder(module);
  probe.push(file);
  const draco = await DracoDecoderModule({ wasmBinary: await (await fetch('../node_modules/draco3d/draco_decoder.wasm')).arrayBuffer() });
  const rows = [];
  // What one clock reading pair costs a sample (an empty sample, ms).
  const empty = [];
  for (let i = 0; i < 15; ++i) empty.push(await sample(() => {}, 1));
  overheadMs = quantile(empty, 0.5);
  for (const L of levels) {
    const prefix = file.subarray(0, levelEnd(probe, L));
    const drc = new Int8Array(await (await fetch(params.get('drc').replace('{L}', L))).arrayBuffer());
    let dracoVertices = 0, dracoTriangles = 0;
    const dracoCall = () => {
      const dec = new draco.Decoder(), mesh = new draco.Mesh();
      const st = dec.DecodeArrayToMesh(drc, drc.length, mesh);
      if (!st.ok()) throw new Error(`draco3d: ${st.error_msg()}`);
      const attr = dec.GetAttribute(mesh, dec.GetAttributeId(mesh, draco.POSITION));
      const nf = 3 * mesh.num_points(), nt = 3 * mesh.num_faces();
      const p = draco._malloc(4 * nf), t = draco._malloc(4 * nt);
      dec.GetAttributeDataArrayForAllPoints(mesh, attr, draco.DT_FLOAT32, 4 * nf, p);
      dec.GetTrianglesUInt32Array(mesh, 4 * nt, t);
      dracoVertices = nf / 3;
      dracoTriangles = nt / 3;
      draco._free(p);
      draco._free(t);
      draco.destroy(mesh);
      draco.destroy(dec);
    };
    const mineInfo = {}, otherInfo = {};
    const sides = [{ fn: dbssCall(module, prefix, L, mineInfo), ms: [] }, { fn: dracoCall, ms: [] }];
    if (otherModule) sides.push({ fn: dbssCall(otherModule, prefix, L, otherInfo), ms: [] });
    const incInfo = {};
    const inc = streaming ? { fn: dbssIncrement(module, levelEnd(probe, L - 1), prefix, L, incInfo), ms: [] } : null;
    if (inc) sides.push(inc);
    for (const s of sides) s.reps = await calibrate(s.fn);
    const ratios = [];
    for (let r = 0; r < samples; ++r) {
      // Turns in both orders, so that neither side always follows the other.
      for (const s of r % 2 ? [...sides].reverse() : sides) s.ms.push(await sample(s.fn, s.reps));
      ratios.push(sides[1].ms[r] / sides[0].ms[r]);
    }
    const { vertices, triangles, hash } = mineInfo;
    rows.push({ level: L, vertices, triangles, dbssBytes: prefix.length, dbss: stats(sides[0].ms), dbssReps: sides[0].reps,
      dracoBytes: drc.length, draco: stats(sides[1].ms), dracoReps: sides[1].reps, ratio: stats(ratios),
      dracoVertices, dracoTriangles, hash, other: otherModule ? stats(sides[2].ms) : undefined, otherHash: otherInfo.hash,
      increment: inc ? stats(inc.ms) : undefined, incrementHash: incInfo.hash,
      incrementRatio: inc ? stats(inc.ms.map((ms, r) => sides[1].ms[r] / ms)) : undefined });
  }
  probe.dispose();
  window.benchResult = { rows, userAgent: navigator.userAgent, emptySampleMs: quantile(empty, 0.5),
    clock: window.dbssCpuNs ? "CPU time of the renderer's main thread" : 'wall time (performance.now)' };
  out.textContent = JSON.stringify(window.benchResult, null, 1);
}

run().catch((e) => { window.benchResult = { error: String(e && e.stack || e) }; out.textContent = window.benchResult.error; });
