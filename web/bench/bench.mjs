// Decoding speed in the browser, one page, one thread: dbss's WebAssembly
// decoder (the whole decode of level L from the file's bytes up to level
// L's chunk: container, Draco control mesh, every level) against draco3d's
// WebAssembly decoder (npm) decoding the same level's mesh, made with
// draco_encoder at its defaults.  Both end with positions and triangle
// indices in their module's memory.  Best of several repetitions each, in
// `rounds` rounds that take turns (dbss, the other dbss build, draco3d), so
// that a busy machine slows all of them alike.
//
// ?dbss=URL&levels=3,4,5&drc=URL_PATTERN (with {L} for the level)
//  &wasm=URL of the dbss module (default build-web/dist/dbss_wasm.mjs)
//  &other=URL of another build of it, timed the same way (optional)
//  &rounds=N (default 3)
import { loadModule, StreamingDecoder } from '../dbss.mjs';
import { levelEnd } from '../loader.mjs';
import { fnv1a64 } from '../hash.mjs';

const params = new URLSearchParams(location.search);
const levels = (params.get('levels') ?? '3,4,5').split(',').map(Number);
const out = document.getElementById('out');

// Best time per call over samples filling at least `budget` ms (at least 5
// samples); each sample repeats fn enough times to last >= 5 ms, as the
// browser's clock is coarse (0.1 ms steps).
function best(fn, budget = 800) {
  fn();  // warm up
  let reps = 1;
  for (;;) {
    const t = performance.now();
    for (let i = 0; i < reps; ++i) fn();
    if (performance.now() - t >= 5 || reps >= 1024) break;
    reps *= 2;
  }
  let bestMs = Infinity, spent = 0;
  for (let n = 0; n < 5 || spent < budget; ++n) {
    const t = performance.now();
    for (let i = 0; i < reps; ++i) fn();
    const ms = performance.now() - t;
    bestMs = Math.min(bestMs, ms / reps);
    spent += ms;
    if (n >= 100) break;
  }
  return bestMs;
}

// One dbss decode of level L from `prefix`: {ms, vertices, triangles, hash}.
function timeDbss(module, prefix, L) {
  let hash = '', vertices = 0, triangles = 0;
  const ms = best(() => {
    const d = new StreamingDecoder(module, { keepLevels: false });
    d.push(prefix);
    const v = d.level(L);
    vertices = v.positions.length / 3;
    triangles = v.indices.length / 3;
    if (!hash) hash = fnv1a64(v.positions);
    d.dispose();
  });
  return { ms, vertices, triangles, hash };
}

async function run() {
  const module = await loadModule(params.get('wasm') ?? undefined);
  const otherModule = params.get('other') ? await loadModule(params.get('other')) : null;
  const rounds = Number(params.get('rounds') ?? 3);
  const file = new Uint8Array(await (await fetch(params.get('dbss'))).arrayBuffer());
  const probe = new StreamingDecoder(module);
  probe.push(file);
  const draco = await DracoDecoderModule({ wasmBinary: await (await fetch('../node_modules/draco3d/draco_decoder.wasm')).arrayBuffer() });
  const rows = [];
  for (const L of levels) {
    const prefix = file.subarray(0, levelEnd(probe, L));
    const drc = new Int8Array(await (await fetch(params.get('drc').replace('{L}', L))).arrayBuffer());
    let dracoVertices = 0, dracoTriangles = 0;
    const timeDraco = () => best(() => {
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
    });
    let mine = null, other = null, dracoMs = Infinity;
    for (let r = 0; r < rounds; ++r) {
      const a = timeDbss(module, prefix, L);
      if (!mine || a.ms < mine.ms) mine = a;
      if (otherModule) {
        const b = timeDbss(otherModule, prefix, L);
        if (!other || b.ms < other.ms) other = b;
      }
      dracoMs = Math.min(dracoMs, timeDraco());
    }
    const { vertices, triangles, hash } = mine;
    const dbssMs = mine.ms;
    rows.push({ level: L, vertices, triangles, dbssBytes: prefix.length, dbssMs, dracoBytes: drc.length, dracoMs,
      dracoVertices, dracoTriangles, hash, otherMs: other?.ms, otherHash: other?.hash });
  }
  probe.dispose();
  window.benchResult = { rows, userAgent: navigator.userAgent };
  out.textContent = JSON.stringify(window.benchResult, null, 1);
}

run().catch((e) => { window.benchResult = { error: String(e && e.stack || e) }; out.textContent = window.benchResult.error; });
