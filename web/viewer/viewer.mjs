// The dbss viewer: a Web Worker (web/worker.mjs) fetches and decodes; this
// page draws level 0 as soon as it is posted and swaps in each finer level
// as it arrives.  It never decodes on the main thread.
//
// window.dbssViewer is the page's state for the browser tests: the levels
// in the order they were drawn (level, hash, counts), the error, done.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const state = window.dbssViewer = { levels: [], shown: -1, error: null, done: false, bytes: 0, firstDrawnMs: null };

// --- three.js scene --------------------------------------------------------
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20242a);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(1, 2, 3);
camera.add(sun);
scene.add(camera);
const material = new THREE.MeshStandardMaterial({ color: 0xc8a060, roughness: 0.6, metalness: 0.05, side: THREE.DoubleSide });
const mesh = new THREE.Mesh(new THREE.BufferGeometry(), material);
scene.add(mesh);
let fitted = false;

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', () => { resize(); render(); });
function render() { renderer.render(scene, camera); }
controls.addEventListener('change', render);
resize();

// Levels kept on the page (copies the worker transferred), for the slider.
const geometries = [];

function show(l) {
  const g = geometries[l];
  if (!g) return;
  mesh.geometry = g.geometry;
  if (!fitted) {
    g.geometry.computeBoundingSphere();
    const { center, radius } = g.geometry.boundingSphere;
    controls.target.copy(center);
    camera.position.copy(center).add(new THREE.Vector3(0.35, -1.1, 0.75).normalize().multiplyScalar(radius * 2.6));
    camera.up.set(0, 0, 1);
    camera.near = radius / 100;
    camera.far = radius * 100;
    camera.updateProjectionMatrix();
    controls.update();
    fitted = true;
  }
  state.shown = l;
  $('s-level').textContent = `${l} of ${state.levelCount != null ? state.levelCount - 1 : '?'}`;
  $('s-vertices').textContent = (g.positions.length / 3).toLocaleString('en');
  $('s-triangles').textContent = (g.indices.length / 3).toLocaleString('en');
  $('s-decode').textContent = `${g.decodeMs.toFixed(1)} ms`;
  $('s-hash').textContent = g.hash;
  $('slider').value = l;
  $('slider-value').textContent = l;
  render();
}

function addLevel(msg) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(msg.positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(msg.indices, 1));
  geometry.computeVertexNormals();
  geometries[msg.level] = { geometry, positions: msg.positions, indices: msg.indices, decodeMs: msg.decodeMs, hash: msg.hash };
  const following = state.shown === geometries.length - 2 || state.shown < 0;
  state.levels.push({ level: msg.level, hash: msg.hash, vertices: msg.positions.length / 3,
    triangles: msg.indices.length / 3, bytes: msg.bytes, at: performance.now() });
  $('slider').max = geometries.length - 1;
  $('slider').disabled = false;
  if (following) show(msg.level);  // the user did not pick a coarser level: refine
  if (msg.level === 0 && state.firstDrawnMs == null && msg.firstByteAt >= 0) {
    // First byte (in the worker) to level 0 drawn (here); timeOrigin-based
    // times compare across the two threads.
    state.firstDrawnMs = performance.timeOrigin + performance.now() - msg.firstByteAt;
    $('s-first').textContent = `${state.firstDrawnMs.toFixed(0)} ms`;
  }
}

// --- the worker --------------------------------------------------------------
let worker = null;

// upToLevel: fetch with Range requests only up to that level; the 'more'
// button then fetches one level at a time.
function open(url, upToLevel = null) {
  if (worker) worker.terminate();
  for (const g of geometries) g && g.geometry.dispose();
  geometries.length = 0;
  Object.assign(state, { levels: [], shown: -1, error: null, done: false, bytes: 0, firstDrawnMs: null, levelCount: null, url });
  fitted = false;
  mesh.geometry = new THREE.BufferGeometry();
  $('slider').disabled = true;
  $('status').className = '';
  $('status').textContent = `loading ${url}`;
  for (const id of ['s-bytes', 's-level', 's-vertices', 's-triangles', 's-decode', 's-first', 's-hash']) $(id).textContent = '-';
  render();
  worker = new Worker(new URL('../worker.mjs', import.meta.url), { type: 'module' });
  worker.onmessage = (ev) => {
    const msg = ev.data;
    if (msg.type === 'progress') {
      state.bytes = msg.bytes;
      $('s-bytes').textContent = msg.bytes.toLocaleString('en');
    } else if (msg.type === 'level') {
      addLevel(msg);
    } else if (msg.type === 'error') {
      state.error = { code: msg.code, codeName: msg.codeName, offset: msg.offset, message: msg.message };
      $('status').className = 'error';
      $('status').textContent = `${msg.message}` + (msg.levelsReady ? ` (showing the ${msg.levelsReady} level(s) verified before it)` : '');
      state.done = true;
    } else if (msg.type === 'done') {
      state.levelCount = msg.levelCount;
      if (state.shown >= 0) $('s-level').textContent = `${state.shown} of ${msg.levelCount - 1}`;
      if (!state.error) $('status').textContent = msg.complete ? `complete: ${msg.levelsReady} levels, ${msg.bytes.toLocaleString('en')} bytes, every chunk verified` : `${msg.levelsReady} levels so far`;
      state.done = true;
    }
  };
  worker.onerror = (e) => { state.error = { code: -1, codeName: 'worker', offset: -1, message: e.message }; state.done = true; $('status').textContent = e.message; };
  $('more').hidden = upToLevel == null;
  // No wasmUrl: the worker's loadModule() then probes for SIMD and loads
  // the scalar module where the engine has none.
  worker.postMessage({ type: 'open', url: new URL(url, location.href).href, upToLevel });
}

// --- controls -------------------------------------------------------------------
$('open').addEventListener('submit', (e) => { e.preventDefault(); if ($('url').value) open($('url').value); });
function openFile(file) { open(URL.createObjectURL(file)); $('url').value = file.name; }
$('file').addEventListener('change', () => { if ($('file').files[0]) openFile($('file').files[0]); });
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  if (e.dataTransfer.files[0]) openFile(e.dataTransfer.files[0]);
});
$('slider').addEventListener('input', () => show(Number($('slider').value)));
for (const r of document.querySelectorAll('input[name=shading]')) {
  r.addEventListener('change', () => { material.flatShading = r.value === 'flat' && r.checked; material.needsUpdate = true; render(); });
}
$('wireframe').addEventListener('change', () => { material.wireframe = $('wireframe').checked; render(); });

$('more').addEventListener('click', () => { state.done = false; worker.postMessage({ type: 'more' }); });

// ?file=URL opens a file; &upto=L fetches it with Range requests up to level L.
const params = new URLSearchParams(location.search);
const start = params.get('file');
if (start) {
  $('url').value = start;
  open(start, params.has('upto') ? Number(params.get('upto')) : null);
}
