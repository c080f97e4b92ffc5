// The decoding Web Worker: fetches and decodes a .dbss off the main thread
// and posts each level as it becomes ready, so the page never blocks on a
// level.  Messages in:
//   {type: 'open', url, wasmUrl?, upToLevel?}   stream a file (all of it, or
//                                               with Range requests up to a level)
//   {type: 'more'}                              Range request for the next level
//   {type: 'level', level}                      post a ready level again (recomputed
//                                               when coarser than the last one posted)
// Messages out:
//   {type: 'progress', bytes}
//   {type: 'level', level, positions, indices, hash, decodeMs, bytes, firstByteAt}
//   {type: 'error', code, codeName, offset, message, levelsReady}
//   {type: 'done', complete, levelsReady, levelCount, bytes}
import { loadModule, StreamingDecoder } from './dbss.mjs';
import { streamAll, fetchUpToLevel, fetchNextLevel } from './loader.mjs';
import { fnv1a64 } from './hash.mjs';

let module = null;
let decoder = null;
let url = null;
let posted = 0;     // levels posted so far
let firstByte = -1; // when the first byte arrived (performance.timeOrigin + now(), comparable across threads)

function postLevel(l) {
  const t = performance.now();
  const view = decoder.level(l);
  const decodeMs = performance.now() - t;
  // Copies out of the module's memory (its views die with the next call),
  // transferred, not cloned, to the page.
  const positions = view.positions.slice(), indices = view.indices.slice();
  self.postMessage({ type: 'level', level: l, positions, indices, hash: fnv1a64(positions), decodeMs,
    bytes: decoder.bytesFed(), firstByteAt: firstByte },
  [positions.buffer, indices.buffer]);
}

function onPiece(bytes) {
  if (firstByte < 0) firstByte = performance.timeOrigin + performance.now();
  self.postMessage({ type: 'progress', bytes: decoder.bytesFed() });
  while (posted < decoder.levelsReady()) postLevel(posted++);
}

function report(e) {
  if (e && e.name === 'DbssError') {
    self.postMessage({ type: 'error', code: e.code, codeName: e.codeName, offset: e.offset, message: e.message,
      levelsReady: decoder ? decoder.levelsReady() : 0 });
  } else {
    self.postMessage({ type: 'error', code: -1, codeName: 'network', offset: -1, message: String(e && e.message || e),
      levelsReady: decoder ? decoder.levelsReady() : 0 });
  }
}

function done() {
  self.postMessage({ type: 'done', complete: decoder.complete(), levelsReady: decoder.levelsReady(),
    levelCount: decoder.levelCount(), bytes: decoder.bytesFed() });
}

// Each 'open' starts a new generation: a stream still running for an older
// one stops at its next piece and reports nothing (its decoder is gone), so
// a page that opens a second file while the first streams sees only the
// second.  A 'more' while a fetch is in flight is ignored: two fetches would
// feed one decoder in no fixed order.
let generation = 0;
let inFlight = false;
class Superseded extends Error {}

async function fetching(gen, run) {
  inFlight = true;
  try {
    await run((bytes) => {
      if (gen !== generation) throw new Superseded();
      onPiece(bytes);
    });
  } finally {
    if (gen === generation) inFlight = false;
  }
}

self.onmessage = async (ev) => {
  const msg = ev.data;
  const gen = msg.type === 'open' ? ++generation : generation;
  try {
    if (msg.type === 'open') {
      module ??= await loadModule(msg.wasmUrl);
      if (gen !== generation) return;  // a newer 'open' came while the module loaded
      if (decoder) decoder.dispose();
      // keepLevels off: the page keeps every level it was sent (the
      // viewer's slider draws from its own copies), so a second copy of each
      // level in the module's memory bought nothing but memory and time (a
      // tenth of a fine level's decode: double torus level 5, node, 3.7 ->
      // 3.3 ms).  A 'level' message for a coarser level is then recomputed
      // from the control mesh.
      decoder = new StreamingDecoder(module, { keepLevels: false });
      url = msg.url;
      posted = 0;
      firstByte = -1;
      const d = decoder;
      try {
        await fetching(gen, (onPiece) => msg.upToLevel == null ? streamAll(url, d, { onPiece })
          : fetchUpToLevel(url, d, msg.upToLevel, { onPiece }));
      } finally {
        // Levels verified before an error are still drawn (spec section 11).
        if (gen === generation) while (decoder.levelsReady() > posted) postLevel(posted++);
      }
      if (gen === generation) done();
    } else if (msg.type === 'more') {
      if (inFlight || !decoder) return;
      await fetching(gen, (onPiece) => fetchNextLevel(url, decoder, { onPiece }));
      if (gen === generation) done();
    } else if (msg.type === 'level') {
      if (decoder) postLevel(msg.level);
    }
  } catch (e) {
    if (!(e instanceof Superseded) && gen === generation) report(e);
  }
};
