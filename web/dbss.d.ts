// Types of web/dbss.mjs (the WebAssembly decoder's JavaScript API) and
// web/loader.mjs (progressive fetching).

/** The emscripten module of scripts/web-build.sh (opaque to callers). */
export interface DbssModule {
  readonly HEAPU8: Uint8Array;
  /** true: the SIMD build, false: the scalar one, undefined: loaded from a URL given. */
  simd: boolean | undefined;
}

/** An error of the file or the decoder, with the spec's error code. */
export class DbssError extends Error {
  readonly name: 'DbssError';
  /** The pinned number of the error code (spec/dbss-format.md), e.g. 5. */
  readonly code: number;
  /** Its lower-case name, e.g. 'checksum_mismatch', 'truncated'. */
  readonly codeName: string;
  /** Byte offset in the file the error is about, or -1. */
  readonly offset: number;
  /** The decoder's message without code and offset. */
  readonly detail: string;
}

/**
 * Loads the module: build-web/node/ in node, build-web/dist/ (or `url`) in a browser or worker.
 * Without a URL: the SIMD build where simdSupported(), else the scalar one; `simd` forces either.
 */
export function loadModule(url?: string, options?: { simd?: boolean }): Promise<DbssModule>;
/** Whether this engine has WebAssembly SIMD (loadModule() then picks the SIMD build). */
export function simdSupported(): boolean;

export interface LevelView {
  level: number;
  /** 3 floats per vertex; a view into the module's memory. */
  positions: Float32Array;
  /** 3 vertex indices per counter-clockwise triangle; a view into the module's memory. */
  indices: Uint32Array;
}

export interface TocEntry {
  /** Four-letter chunk type: 'CTRL', 'LEVL', 'meta', ... */
  type: string;
  /** File offset of the chunk's length field. */
  offset: number;
  /** Bytes of the chunk's data. */
  length: number;
  /** One past the chunk's last byte. */
  end: number;
}

export class StreamingDecoder {
  /** keepLevels (default true): keep decoded levels so coarser ones come back without recomputing. */
  constructor(module: DbssModule, options?: { keepLevels?: boolean });
  /** Parses a piece of the file, any size.  Throws DbssError (sticky). */
  push(bytes: Uint8Array): void;
  /** End of input; throws DbssError 'truncated' when the file was cut. */
  finish(): void;
  /** Levels 0 .. levelsReady() - 1 are verified and can be decoded. */
  levelsReady(): number;
  /** Levels the file declares, level 0 included; -1 before its header. */
  levelCount(): number;
  bytesFed(): number;
  /** Every chunk the table of contents lists is verified. */
  complete(): boolean;
  /** The first error, or null. */
  error(): DbssError | null;
  /** The table of contents, [] until it is in. */
  toc(): TocEntry[];
  /** Declared file size, 0 until the table of contents is in. */
  fileSize(): number;
  /**
   * Decodes level l.  The arrays are views valid until the next call on this
   * decoder (or anything that grows the module's memory): slice() to keep.
   * Throws RangeError for a level not ready, DbssError for a bad control mesh.
   */
  level(l: number): LevelView;
  /** Frees the decoder's memory in the module. */
  dispose(): void;
}
