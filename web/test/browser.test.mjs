// The viewer in headless Chromium (Debian's /usr/bin/chromium through
// playwright-core; WebGL2 on SwiftShader): levels arrive in order over a
// slow server and hash as natively; a cut file keeps its verified levels
// and shows `truncated`; damaged bytes show their error and no mesh from
// them; Range requests fetch exactly up to a level; a screenshot shows the
// mesh (kept as build-web/artefacts/viewer.png).  Also: three.js's own
// GLTFLoader reads what `dbss export` and `dbss decode -o x.glb` write, with
// each level's counts (and, where not Draco-compressed, positions) as dbss's.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer, repoMounts } from '../tools/serve.mjs';
import { loadModule, StreamingDecoder } from '../dbss.mjs';

const repo = fileURLToPath(new URL('../..', import.meta.url));
const buildDir = process.env.DBSS_WEB_BUILD ?? join(repo, 'build-web');
const dbss = process.env.DBSS_BIN ?? join(repo, 'build/bin/dbss');
const work = join(buildDir, 'test-files');
const artefacts = join(buildDir, 'artefacts');
const RATE = 16000;  // bytes per second for the slow server, in 512-byte pieces

function nativeHashes(file) {
  return nativeLevels(file).map((l) => l.hash);
}

// `dbss info --hashes` as {level, vertices, triangles, hash} per level.
function nativeLevels(file) {
  const r = spawnSync(dbss, ['info', file, '--hashes'], { encoding: 'utf8' });
  return r.stdout.trim().split('\n').filter(Boolean).map((l) => {
    const w = l.split(' ');
    return { level: Number(w[1]), vertices: Number(w[3]), triangles: Number(w[5]), hash: w[7] };
  });
}

function runDbss(args) {
  const r = spawnSync(dbss, args, { encoding: 'utf8' });
  assert.equal(r.status, 0, `dbss ${args.join(' ')}: ${r.stderr}`);
}

let browser, slow, fast, files = {}, tocOf = {};
const hold = {};  // the slow server's hold (see serve.mjs), set by the slow-server test

before(async () => {
  mkdirSync(work, { recursive: true });
  mkdirSync(artefacts, { recursive: true });
  // A freshly encoded example, and cut and damaged copies of it.
  const example = join(work, 'example.dbss');
  const enc = spawnSync(dbss, ['encode', join(repo, 'examples/double-torus.xyz'), '-o', example, '--levels', '4'], { encoding: 'utf8' });
  assert.equal(enc.status, 0, enc.stderr);
  const bytes = new Uint8Array(readFileSync(example));
  const d = new StreamingDecoder(await loadModule());
  d.push(bytes);
  const toc = d.toc();
  d.dispose();
  const levl = toc.filter((e) => e.type === 'LEVL'), ctrl = toc.find((e) => e.type === 'CTRL');
  assert.equal(levl.length, 4);
  const cut = join(work, 'cut.dbss');
  writeFileSync(cut, bytes.subarray(0, levl[3].offset + Math.floor(levl[3].length / 2)));
  const damaged = join(work, 'damaged-level2.dbss');
  const dl = bytes.slice();
  dl[levl[1].offset + 12 + 3] ^= 0x10;
  writeFileSync(damaged, dl);
  const damagedCtrl = join(work, 'damaged-control.dbss');
  const dc = bytes.slice();
  dc[ctrl.offset + 12 + 20] ^= 0x01;
  writeFileSync(damagedCtrl, dc);
  // glTF of every level (MSFT_lod), the same with Draco below the finest
  // level, and one level alone.
  const glb = join(work, 'example.glb'), glbDraco = join(work, 'example-draco.glb'), glbLevel = join(work, 'level2.glb');
  runDbss(['export', example, '-o', glb]);
  runDbss(['export', example, '-o', glbDraco, '--draco', '14']);
  runDbss(['decode', example, '--level', '2', '-o', glbLevel]);
  files = { '/example.glb': glb, '/example-draco.glb': glbDraco, '/level2.glb': glbLevel, '/example.dbss': example, '/cut.dbss': cut, '/damaged-level2.dbss': damaged, '/damaged-control.dbss': damagedCtrl,
    '/garbage-control.dbss': join(repo, 'tests/format/data/garbage-control.dbss') };
  for (const f of readdirSync(join(repo, 'tests/golden/v1')).filter((f) => f.endsWith('.dbss')))
    files[`/golden/${f}`] = join(repo, 'tests/golden/v1', f);
  tocOf = { ctrl, levl, size: bytes.length };
  const mounts = repoMounts(repo, buildDir);
  slow = await startServer({ rate: RATE, piece: 512, files, mounts, hold });
  fast = await startServer({ files, mounts });
  browser = await chromium.launch({ executablePath: process.env.DBSS_CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });
});

after(async () => {
  await browser?.close();
  slow?.server.close();
  fast?.server.close();
});

async function view(base, query, whileHeld = null) {
  const page = await browser.newPage({ viewport: { width: 900, height: 700 } });
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${base.url}/web/viewer/?${query}`);
  if (whileHeld) await whileHeld(page);
  await page.waitForFunction(() => window.dbssViewer && window.dbssViewer.done, null, { timeout: 60000 });
  const state = await page.evaluate(() => window.dbssViewer);
  assert.deepEqual(problems, []);
  return { page, state };
}

test('slow server: levels appear in order 0..4, each hashing as natively, each before the file is all in', async () => {
  // The server stops at the end of level 2's chunk until levels 0..2 are on
  // screen: drawing from a prefix is then a property, not a race with the
  // clock (a loaded machine once drew level 2 only after the last byte).
  const ends = [tocOf.ctrl.end, ...tocOf.levl.map((e) => e.end)];
  let release;
  Object.assign(hold, { path: '/example.dbss', at: ends[2], until: new Promise((ok) => { release = ok; }) });
  assert.ok(ends[2] < tocOf.size);
  let early;
  const { page, state } = await view(slow, 'file=/example.dbss', async (p) => {
    try {
      await p.waitForFunction(() => window.dbssViewer && window.dbssViewer.levels.length >= 3, null, { timeout: 60000 });
      early = await p.evaluate(() => window.dbssViewer.levels.map((l) => ({ level: l.level, bytes: l.bytes })));
    } finally {
      release();
      hold.until = null;
    }
  });
  assert.deepEqual(early.map((l) => l.level).slice(0, 3), [0, 1, 2]);
  early.forEach((l) => assert.ok(l.bytes <= ends[2], `level ${l.level} drawn at byte ${l.bytes}, while the server held at ${ends[2]}`));
  const expected = nativeHashes(files['/example.dbss']);
  assert.equal(expected.length, 5);
  assert.deepEqual(state.levels.map((l) => l.level), [0, 1, 2, 3, 4]);
  assert.deepEqual(state.levels.map((l) => l.hash), expected);
  assert.equal(state.error, null);
  assert.equal(state.shown, 4);
  // Each level was drawn only once the bytes up to its chunk were in (and
  // levels 0..2 before the rest were sent, above).
  state.levels.forEach((l, i) => assert.ok(l.bytes >= ends[i], `level ${i} drawn at byte ${l.bytes}, its chunk ends at ${ends[i]}`));
  for (let i = 1; i < state.levels.length; ++i) assert.ok(state.levels[i].at > state.levels[i - 1].at);
  assert.ok(state.firstDrawnMs > 0);
  console.log(`# first byte to level 0 drawn at ${RATE} bytes/s: ${state.firstDrawnMs.toFixed(0)} ms; level 0 complete at byte ${ends[0]} of ${tocOf.size}`);
  await page.close();
});

test('a cut file keeps the finest complete level on screen and shows truncated', async () => {
  const { page, state } = await view(fast, 'file=/cut.dbss');
  assert.deepEqual(state.levels.map((l) => l.hash), nativeHashes(files['/example.dbss']).slice(0, 4));
  assert.equal(state.shown, 3);
  assert.equal(state.error?.codeName, 'truncated');
  assert.match(await page.textContent('#status'), /truncated/);
  await page.close();
});

test('a damaged level shows checksum_mismatch and no mesh from its bytes', async () => {
  const { page, state } = await view(fast, 'file=/damaged-level2.dbss');
  assert.equal(state.error?.codeName, 'checksum_mismatch');
  assert.ok(state.error.offset >= tocOf.levl[1].offset && state.error.offset < tocOf.levl[1].end);
  assert.deepEqual(state.levels.map((l) => l.hash), nativeHashes(files['/example.dbss']).slice(0, 2));
  assert.match(await page.textContent('#status'), /checksum_mismatch/);
  await page.close();
});

test('a damaged control mesh shows its error and draws nothing', async () => {
  const { page, state } = await view(fast, 'file=/damaged-control.dbss');
  assert.equal(state.error?.codeName, 'checksum_mismatch');
  assert.deepEqual(state.levels, []);
  assert.equal(state.shown, -1);
  await page.close();
});

test('a control mesh that is not Draco (its CRC holds) shows compression and draws nothing', async () => {
  const { page, state } = await view(fast, 'file=/garbage-control.dbss');
  assert.equal(state.error?.codeName, 'compression');
  assert.deepEqual(state.levels, []);
  assert.match(await page.textContent('#status'), /compression/);
  await page.close();
});

test('Range requests: up to level 1, then level 2 now', async () => {
  const { page, state } = await view(fast, 'file=/example.dbss&upto=1');
  const expected = nativeHashes(files['/example.dbss']);
  assert.deepEqual(state.levels.map((l) => l.hash), expected.slice(0, 2));
  assert.equal(state.bytes, tocOf.levl[0].end);
  await page.evaluate(() => { window.dbssViewer.done = false; document.getElementById('more').click(); });
  await page.waitForFunction(() => window.dbssViewer.done, null, { timeout: 30000 });
  const after = await page.evaluate(() => window.dbssViewer);
  assert.deepEqual(after.levels.map((l) => l.hash), expected.slice(0, 3));
  assert.equal(after.bytes, tocOf.levl[1].end);
  await page.close();
});

test('screenshot: the mesh covers a good part of the canvas', async () => {
  const { page } = await view(fast, 'file=/example.dbss');
  // Pixels of the WebGL canvas that differ from the background colour.
  const fraction = await page.evaluate(() => {
    const c = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = c.width;
    copy.height = c.height;
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    let differ = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 0x20) + Math.abs(px[i + 1] - 0x24) + Math.abs(px[i + 2] - 0x2a) > 24) ++differ;
    }
    return differ / (px.length / 4);
  });
  await page.screenshot({ path: join(artefacts, 'viewer.png') });
  console.log(`# mesh covers ${(100 * fraction).toFixed(1)}% of the canvas; screenshot ${join(artefacts, 'viewer.png')}`);
  assert.ok(fraction > 0.1, `only ${(100 * fraction).toFixed(1)}% of the canvas differs from the background`);
  await page.close();
});

test('without WebAssembly SIMD the worker loads the scalar build by itself: the example and every golden file hash as natively', async () => {
  // web/test/pages/no-simd.html runs web/worker.mjs unchanged, with
  // WebAssembly.validate refusing SIMD modules as an engine without SIMD
  // does; which module it fetched is read off the network.
  const context = await browser.newContext();
  const wasm = [];
  context.on('request', (r) => { if (r.url().endsWith('.wasm')) wasm.push(new URL(r.url()).pathname); });
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  const names = Object.keys(files).filter((f) => f === '/example.dbss' || f.startsWith('/golden/'));
  assert.ok(names.length >= 13);
  await page.goto(`${fast.url}/web/test/pages/no-simd.html?${names.map((f) => `file=${encodeURIComponent(f)}`).join('&')}`);
  await page.waitForFunction(() => window.noSimdResult, null, { timeout: 120000 });
  const res = await page.evaluate(() => window.noSimdResult);
  await context.close();
  assert.deepEqual(problems, []);
  assert.equal(res.workerError, undefined);
  assert.deepEqual(wasm, ['/build-web/dist/dbss_wasm_scalar.wasm']);
  for (const f of names) {
    assert.equal(res[f].error, null, f);
    assert.deepEqual(res[f].hashes, nativeHashes(files[f]), f);
  }
});

// The page web/test/pages/gltf.html: what GLTFLoader made of a .glb.
async function loadGltf(name) {
  const page = await browser.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${fast.url}/web/test/pages/gltf.html?url=${encodeURIComponent(name)}`);
  await page.waitForFunction(() => window.gltfResult, null, { timeout: 60000 });
  const res = await page.evaluate(() => window.gltfResult);
  await page.close();
  assert.deepEqual(problems, []);
  assert.equal(res.error, undefined, res.error);
  return res;
}

test('GLTFLoader reads `dbss export`: one node per level, counts and positions as dbss decodes them', async () => {
  const levels = nativeLevels(files['/example.dbss']);
  assert.equal(levels.length, 5);
  const res = await loadGltf('/example.glb');
  assert.ok(res.extensionsUsed.includes('MSFT_lod'));
  assert.deepEqual(res.nodes.map((n) => n.name).sort(), levels.map((l) => `level ${l.level}`).sort());
  for (const l of levels) {
    const node = res.nodes.find((n) => n.name === `level ${l.level}`);
    assert.equal(node.prims.length, 1, `level ${l.level}`);
    assert.deepEqual(node.prims[0], { vertices: l.vertices, triangles: l.triangles, hash: l.hash }, `level ${l.level}`);
  }
  // Viewers without MSFT_lod draw the finest level.
  const finest = levels[levels.length - 1];
  assert.deepEqual(res.scene, [{ vertices: finest.vertices, triangles: finest.triangles }]);
});

test('GLTFLoader with DRACOLoader reads `dbss export --draco`: every level\'s counts, the finest level\'s bits', async () => {
  const levels = nativeLevels(files['/example.dbss']);
  const res = await loadGltf('/example-draco.glb');
  assert.ok(res.extensionsUsed.includes('KHR_draco_mesh_compression'));
  for (const l of levels) {
    const node = res.nodes.find((n) => n.name === `level ${l.level}`);
    assert.ok(node, `level ${l.level}`);
    assert.equal(node.prims.length, 1);
    assert.equal(node.prims[0].vertices, l.vertices, `level ${l.level} vertices`);
    assert.equal(node.prims[0].triangles, l.triangles, `level ${l.level} triangles`);
  }
  const finest = levels[levels.length - 1];
  assert.equal(res.nodes.find((n) => n.name === `level ${finest.level}`).prims[0].hash, finest.hash);
});

test('GLTFLoader reads `dbss decode --level 2 -o x.glb`: level 2\'s counts and positions', async () => {
  const l2 = nativeLevels(files['/example.dbss'])[2];
  const res = await loadGltf('/level2.glb');
  const prims = res.nodes.flatMap((n) => n.prims);
  assert.deepEqual(prims, [{ vertices: l2.vertices, triangles: l2.triangles, hash: l2.hash }]);
  assert.deepEqual(res.scene, [{ vertices: l2.vertices, triangles: l2.triangles }]);
});
