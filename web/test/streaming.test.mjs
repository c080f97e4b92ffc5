// The JavaScript API (web/dbss.mjs) on the WebAssembly build: pieces of any
// size give the same levels; a cut file keeps its verified levels and
// reports `truncated`; damaged bytes give the spec's error, at the damaged
// chunk, and no level made from them; a prefix ending at a level's chunk
// (what an HTTP Range request for "up to level L" fetches) gives exactly
// levels 0..L.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadModule, StreamingDecoder, DbssError, simdSupported } from '../dbss.mjs';
import { fnv1a64 } from '../hash.mjs';

const repo = fileURLToPath(new URL('../..', import.meta.url));
const golden = (name) => new Uint8Array(readFileSync(`${repo}/tests/golden/v1/${name}.dbss`));
const recorded = (name) => readFileSync(`${repo}/tests/golden/v1/${name}.hashes`, 'utf8').trim().split('\n');
const module = await loadModule();

test('the SIMD probe validates where the SIMD build runs (node 20 runs it)', () => {
  // loadModule() picks the scalar build when this is false; a wrong probe
  // would send every browser to the slower build.
  assert.equal(simdSupported(), true);
  assert.equal(module.simd, true);
});

test('without SIMD, loadModule() falls back to the scalar build, which decodes the same bits', async () => {
  // An engine without SIMD, as the probe sees it: WebAssembly.validate
  // refuses the probe (and loading the SIMD build there would fail).
  const validate = WebAssembly.validate;
  let scalar;
  try {
    WebAssembly.validate = () => false;
    assert.equal(simdSupported(), false);
    scalar = await loadModule();
  } finally {
    WebAssembly.validate = validate;
  }
  assert.equal(scalar.simd, false);
  const forced = await loadModule(undefined, { simd: false });
  assert.equal(forced.simd, false);
  assert.notEqual(forced.HEAPU8.buffer, module.HEAPU8.buffer);
  for (const name of ['torus-4-levels', 'bordered-grid-3-levels']) {
    for (const m of [scalar, forced]) {
      const d = new StreamingDecoder(m);
      d.push(golden(name));
      d.finish();
      assert.deepEqual(levelHashes(d), recorded(name), `${name}, scalar build`);
      d.dispose();
    }
  }
});

function levelHashes(d) {
  const out = [];
  for (let l = 0; l < d.levelsReady(); ++l) out.push(fnv1a64(d.level(l).positions));
  return out;
}

test('one byte at a time: levels appear in order and hash to the recorded values', () => {
  for (const name of ['torus-4-levels', 'bipyramid9-3-levels', 'bordered-grid-3-levels', 'icosahedron-4-levels']) {
    const bytes = golden(name), d = new StreamingDecoder(module);
    let ready = 0;
    const seenAt = [];
    for (let i = 0; i < bytes.length; ++i) {
      d.push(bytes.subarray(i, i + 1));
      const r = d.levelsReady();
      assert.ok(r === ready || r === ready + 1, `${name}: levels ready jumped from ${ready} to ${r} at byte ${i}`);
      if (r > ready) seenAt.push(i);
      ready = r;
    }
    d.finish();
    assert.ok(d.complete());
    assert.equal(d.levelsReady(), d.levelCount());
    assert.deepEqual(levelHashes(d), recorded(name));
    assert.equal(seenAt.length, d.levelCount());
    d.dispose();
  }
});

test('pieces of 7 and 4096 bytes give the same levels as one piece', () => {
  const bytes = golden('torus-4-levels');
  for (const piece of [7, 4096]) {
    const d = new StreamingDecoder(module, { keepLevels: false });
    for (let i = 0; i < bytes.length; i += piece) d.push(bytes.subarray(i, i + piece));
    d.finish();
    // Coarser after finer (recomputed from the control mesh without keepLevels).
    const hashes = levelHashes(d);
    assert.deepEqual(hashes, recorded('torus-4-levels'));
    assert.equal(fnv1a64(d.level(0).positions), hashes[0]);
    d.dispose();
  }
});

test('an ArrayBuffer (a fetch body chunk) is read as its bytes', () => {
  const bytes = golden('torus-4-levels');
  const d = new StreamingDecoder(module);
  const copy = bytes.slice();
  d.push(copy.buffer);
  d.finish();
  assert.deepEqual(levelHashes(d), recorded('torus-4-levels'));
  d.dispose();
});

test('a cut file keeps the finest complete level and reports truncated', () => {
  const bytes = golden('torus-4-levels');
  const probe = new StreamingDecoder(module);
  probe.push(bytes);
  const levl = probe.toc().filter((e) => e.type === 'LEVL');
  assert.equal(levl.length, 4);
  // Cut in the middle of level 3's chunk: levels 0..2 stay.
  const cut = levl[2].offset + Math.floor(levl[2].length / 2);
  const d = new StreamingDecoder(module);
  d.push(bytes.subarray(0, cut));
  assert.equal(d.levelsReady(), 3);
  assert.throws(() => d.finish(), (e) => e instanceof DbssError && e.codeName === 'truncated' && e.code === 9 && e.offset >= levl[2].offset && e.offset <= cut);
  assert.equal(d.levelsReady(), 3);
  assert.deepEqual(levelHashes(d), recorded('torus-4-levels').slice(0, 3));
  probe.dispose();
  d.dispose();
});

test('a damaged byte in a level gives checksum_mismatch at that chunk and no level from it', () => {
  const bytes = golden('torus-4-levels').slice();
  const probe = new StreamingDecoder(module);
  probe.push(bytes);
  const levl = probe.toc().filter((e) => e.type === 'LEVL');
  bytes[levl[1].offset + 12 + 5] ^= 0x40;  // inside level 2's data
  const d = new StreamingDecoder(module);
  let thrown = null;
  try {
    for (let i = 0; i < bytes.length; i += 100) d.push(bytes.subarray(i, i + 100));
  } catch (e) {
    thrown = e;
  }
  assert.ok(thrown instanceof DbssError, `no DbssError: ${thrown}`);
  assert.equal(thrown.codeName, 'checksum_mismatch');
  assert.equal(thrown.code, 5);
  assert.ok(thrown.offset >= levl[1].offset && thrown.offset < levl[1].end, `offset ${thrown.offset} outside level 2's chunk`);
  assert.equal(d.levelsReady(), 2);  // levels 0 and 1, verified before the damage
  assert.deepEqual(levelHashes(d), recorded('torus-4-levels').slice(0, 2));
  // The error is sticky.
  assert.throws(() => d.push(new Uint8Array(1)), (e) => e === thrown);
  probe.dispose();
  d.dispose();
});

test('a damaged signature byte 1 is bad_signature at byte 1 with no level', () => {
  const bytes = golden('icosahedron-4-levels').slice();
  bytes[1] ^= 0xff;
  const d = new StreamingDecoder(module);
  assert.throws(() => d.push(bytes), (e) => e instanceof DbssError && e.codeName === 'bad_signature' && e.offset === 1);
  assert.equal(d.levelsReady(), 0);
  assert.throws(() => d.level(0), RangeError);
  d.dispose();
});

test('a prefix up to level L\'s chunk (a Range request) gives exactly levels 0..L', () => {
  const bytes = golden('icosahedron-4-levels');
  const head = new StreamingDecoder(module);
  head.push(bytes.subarray(0, 512));
  const toc = head.toc();
  assert.ok(toc.length >= 5, 'the table of contents is in the first 512 bytes');
  assert.equal(head.fileSize(), bytes.length);
  const ctrl = toc.find((e) => e.type === 'CTRL'), levl = toc.filter((e) => e.type === 'LEVL');
  const ends = [ctrl.end, ...levl.map((e) => e.end)];
  for (let L = 0; L < ends.length; ++L) {
    const d = new StreamingDecoder(module);
    d.push(bytes.subarray(0, ends[L]));
    assert.equal(d.levelsReady(), L + 1);
    // And "level L+1 now": the next range on top.
    if (L + 1 < ends.length) {
      d.push(bytes.subarray(ends[L], ends[L + 1]));
      assert.equal(d.levelsReady(), L + 2);
    }
    d.dispose();
  }
  head.dispose();
});

test('a control mesh that passes its CRC but is not Draco: compression error from level(0), then nothing ready', () => {
  const bytes = new Uint8Array(readFileSync(`${repo}/tests/format/data/garbage-control.dbss`));
  const d = new StreamingDecoder(module);
  d.push(bytes);
  assert.ok(d.levelsReady() >= 1);  // its bytes are verified; the decoder has not looked inside yet
  assert.throws(() => d.level(0), (e) => e instanceof DbssError && e.codeName === 'compression' && e.code === 10);
  assert.equal(d.levelsReady(), 0);  // a decoder-side error voids every level
  d.dispose();
});
