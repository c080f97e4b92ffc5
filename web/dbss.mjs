// dbss in JavaScript: the C++ decoder compiled to WebAssembly
// (scripts/web-build.sh), behind a streaming API.  Feed the bytes of a .dbss
// file as they arrive; after each piece, levelsReady() says how many levels
// can be drawn and level(l) returns one as typed-array views into the
// module's memory (no copy).
//
//   import { loadModule, StreamingDecoder } from './dbss.mjs';
//   const d = new StreamingDecoder(await loadModule());
//   for await (const piece of body) { d.push(piece); draw(d.level(d.levelsReady() - 1)); }
//   d.finish();
//
// Errors are DbssError exceptions carrying the spec's error code (its name,
// e.g. 'checksum_mismatch', and number) and the byte offset it is about.  An
// error voids nothing verified before it (spec section 11): after a cut or
// damaged chunk, levelsReady() still counts the levels verified before it.

export class DbssError extends Error {
  constructor(code, codeName, offset, message) {
    super(offset >= 0 ? `${codeName} at byte ${offset}: ${message}` : `${codeName}: ${message}`);
    this.name = 'DbssError';
    this.code = code;          // the pinned number of spec/dbss-format.md's error codes
    this.codeName = codeName;  // its lower-case name
    this.offset = offset;      // byte offset in the file, or -1 when none applies
    this.detail = message;
  }
}

const isNode = typeof process !== 'undefined' && process.versions != null && process.versions.node != null
  && typeof window === 'undefined';

// Loads the module.  In node: build-web/node/ (or DBSS_WASM_DIR); in a
// browser or worker: `url`, by default build-web/dist/ beside this file's
// folder.  Without a URL it picks the build by probing the engine:
// dbss_wasm (WebAssembly SIMD: Chrome 91, Firefox 89, Safari 16.4 and
// later) where it validates SIMD, else dbss_wasm_scalar (same bits, some
// 15% slower).  { simd: false } forces the scalar build, { simd: true } the
// SIMD one.  The module's `simd` property says which was loaded (undefined
// for a URL given).
export async function loadModule(url, { simd } = {}) {
  const useSimd = url === undefined ? (simd ?? simdSupported()) : undefined;
  const name = useSimd === false ? 'dbss_wasm_scalar' : 'dbss_wasm';
  let module;
  if (isNode) {
    const { createRequire } = await import('node:module');
    const { pathToFileURL } = await import('node:url');
    const dir = process.env.DBSS_WASM_DIR;
    const file = url ?? (dir ? pathToFileURL(`${dir}/${name}.cjs`).href
      : new URL(`../build-web/node/${name}.cjs`, import.meta.url).href);
    const factory = createRequire(import.meta.url)(new URL(file).pathname);
    module = await factory();
  } else {
    const { default: factory } = await import(url ?? new URL(`../build-web/dist/${name}.mjs`, import.meta.url).href);
    module = await factory();
  }
  module.simd = useSimd;
  return module;
}

// A module whose one function returns a v128 constant: valid only where
// the engine has SIMD.
const SIMD_PROBE = new Uint8Array([
  0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00,  // magic, version 1
  0x01, 0x05, 0x01, 0x60, 0x00, 0x01, 0x7b,        // types: () -> v128
  0x03, 0x02, 0x01, 0x00,                          // functions: one of type 0
  0x0a, 0x16, 0x01, 0x14, 0x00, 0xfd, 0x0c,        // code: no locals, v128.const
  0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // its 16 bytes
  0x0b,                                            // end
]);

export function simdSupported() {
  return typeof WebAssembly === 'object' && WebAssembly.validate(SIMD_PROBE);
}

const FOURCC = (v) => String.fromCharCode(v & 0xff, (v >>> 8) & 0xff, (v >>> 16) & 0xff, v >>> 24);

export class StreamingDecoder {
  // keepLevels: keep every decoded level, so going back to a coarser one is
  // free (the viewer's slider); off, only the current level is kept.
  constructor(module, { keepLevels = true } = {}) {
    this.m = module;
    this.h = module._dbss_new(keepLevels ? 1 : 0);
    this.buf = 0;
    this.bufSize = 0;
    this.err = null;
  }

  dispose() {
    if (this.h) this.m._dbss_delete(this.h);
    if (this.buf) this.m._dbss_free(this.buf);
    this.h = 0;
    this.buf = 0;
  }

  // Parses a piece of the file (any size).  Cheap: no subdivision happens
  // here.  Throws the file's first error (and again on every later push).
  push(bytes) {
    this.#live();
    if (this.err) throw this.err;
    if (!ArrayBuffer.isView(bytes)) bytes = new Uint8Array(bytes);  // an ArrayBuffer
    if (bytes.length > this.bufSize) {
      if (this.buf) this.m._dbss_free(this.buf);
      this.buf = 0;
      this.bufSize = 0;
      const size = Math.max(bytes.length, 65536);
      const buf = this.m._dbss_alloc(size);
      // With memory growth on, malloc returns 0 when WebAssembly memory is
      // exhausted; writing there would overwrite the module's own data.
      if (!buf) throw new RangeError('dbss: out of WebAssembly memory');
      this.buf = buf;
      this.bufSize = size;
    }
    this.m.HEAPU8.set(bytes, this.buf);
    if (this.m._dbss_feed(this.h, this.buf, bytes.length) !== 0) this.#fail();
  }

  // End of input: throws a `truncated` DbssError when the file was cut.
  finish() {
    this.#live();
    if (this.err) throw this.err;
    if (this.m._dbss_finish(this.h) !== 0) this.#fail();
  }

  // How many levels can be drawn: levels 0 .. levelsReady() - 1.
  levelsReady() { this.#live(); return this.m._dbss_ready_level(this.h) + 1; }
  // Levels the file declares, level 0 included; -1 before the header is in.
  levelCount() { this.#live(); const n = this.m._dbss_level_count(this.h); return n < 0 ? -1 : n + 1; }
  bytesFed() { this.#live(); return this.m._dbss_bytes_fed(this.h); }
  complete() { this.#live(); return this.m._dbss_complete(this.h) === 1; }
  // The first error, or null.
  error() { return this.err; }

  // The table of contents once it is in ([] before): the chunks after INDX
  // in file order, {type, offset, length, end}; `end` is one past the
  // chunk's last byte, so bytes [0, end) hold everything up to it.
  toc() {
    this.#live();
    const n = this.m._dbss_toc_size(this.h), out = [];
    for (let i = 0; i < n; ++i) {
      const offset = this.m._dbss_toc_offset(this.h, i), length = this.m._dbss_toc_length(this.h, i);
      out.push({ type: FOURCC(this.m._dbss_toc_type(this.h, i)), offset, length, end: offset + 12 + length });
    }
    return out;
  }
  fileSize() { this.#live(); return this.m._dbss_file_size(this.h); }

  // Level l (0 .. levelsReady() - 1): {level, positions, indices} where
  // positions holds 3 floats per vertex and indices 3 per counter-clockwise
  // triangle.  Both are views into the module's memory, valid until the next
  // call on this decoder (or any module call that grows memory): copy them
  // (slice()) to keep them.
  level(l) {
    this.#live();
    if (!(l >= 0 && l < this.levelsReady())) throw new RangeError(`level ${l} is not ready (levels ready: ${this.levelsReady()})`);
    if (this.m._dbss_decode(this.h, l) !== 0) this.#fail();
    const m = this.m, h = this.h;
    const nv = m._dbss_vertex_count(h), nt = m._dbss_triangle_count(h);
    return {
      level: l,
      positions: new Float32Array(m.HEAPU8.buffer, m._dbss_positions(h), 3 * nv),
      indices: new Uint32Array(m.HEAPU8.buffer, m._dbss_indices(h), 3 * nt),
    };
  }

  #live() { if (!this.h) throw new Error('StreamingDecoder used after dispose()'); }

  #fail() {
    const m = this.m, h = this.h, code = m._dbss_last_code(h);
    this.err = new DbssError(code, m.UTF8ToString(m._dbss_error_name(code)), m._dbss_last_offset(h),
      m.UTF8ToString(m._dbss_last_message(h)));
    throw this.err;
  }
}
