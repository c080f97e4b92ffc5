// Fetching a .dbss progressively into a StreamingDecoder (web/dbss.mjs).
//
// Two ways: stream the whole body (fetch()'s ReadableStream: the decoder
// sees each network piece as it lands), or, with the table of contents,
// HTTP Range requests for "only up to level L" and "level L+1 now".  The
// container's chunks are in level order, so "up to level L" is the byte
// prefix ending at level L's chunk.

// The signature (8 bytes) and the HEAD chunk (12 + 56) come first, then the
// INDX chunk, whose 4-byte length field ends at byte 80 (spec/dbss-format.md):
// the table of contents is fetched in two exact requests, so "up to level L"
// never pulls in bytes of later levels.
const INDX_AT = 76;

// Pushes every piece of `response`'s body into `decoder`; calls
// onPiece(bytesSoFar) after each.  Throws the decoder's DbssError.
export async function pushBody(response, decoder, onPiece = () => {}) {
  const reader = response.body.getReader();
  let n = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) return n;
    try {
      decoder.push(value);
    } catch (e) {
      reader.cancel().catch(() => {});
      throw e;
    }
    n += value.length;
    onPiece(n);
  }
}

async function ok(response, url) {
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status} ${response.statusText}`);
  return response;
}

// The whole file as one stream; finish() at its end (a cut file throws
// `truncated` there, its verified levels still ready).
export async function streamAll(url, decoder, { onPiece, signal } = {}) {
  const response = await ok(await fetch(url, { signal }), url);
  await pushBody(response, decoder, onPiece);
  decoder.finish();
}

// Bytes [start, end) of url, pushed as they arrive.  Returns false when the
// server ignored the Range header (a 200 with the whole body, which is then
// pushed from where the decoder stands, so the result is the same).
async function pushRange(url, decoder, start, end, { onPiece, signal } = {}) {
  const response = await ok(await fetch(url, { signal, headers: { Range: `bytes=${start}-${end - 1}` } }), url);
  if (response.status === 206) {
    await pushBody(response, decoder, onPiece);
    return true;
  }
  // A plain 200: skip what the decoder already has.
  const all = new Uint8Array(await response.arrayBuffer());
  decoder.push(all.subarray(decoder.bytesFed()));
  decoder.finish();
  return false;
}

// The byte offset where level `level`'s chunk ends (level 0: the control
// mesh), from the table of contents; null before the table is in.
export function levelEnd(decoder, level) {
  const toc = decoder.toc();
  if (!toc.length) return null;
  let seen = -1;
  for (const e of toc) {
    if (e.type === 'CTRL' || e.type === 'LEVL') ++seen;
    if (seen === level) return e.end;
  }
  return decoder.fileSize();  // past the last level: all of it
}

// Only up to level L: the header and table of contents first, then the
// range up to level L's chunk.  Leaves the decoder open for fetchNextLevel.
export async function fetchUpToLevel(url, decoder, level, opts = {}) {
  if (!decoder.toc().length) {
    const head = await ok(await fetch(url, { signal: opts.signal, headers: { Range: `bytes=0-${INDX_AT + 3}` } }), url);
    const bytes = new Uint8Array(await head.arrayBuffer());
    if (head.status !== 206) {  // no Range support: the whole file came
      decoder.push(bytes.subarray(decoder.bytesFed()));
      opts.onPiece?.(bytes.length);
      decoder.finish();
      return;
    }
    if (decoder.bytesFed() < bytes.length) decoder.push(bytes.subarray(decoder.bytesFed()));
    if (bytes.length < INDX_AT + 4) decoder.finish();  // throws truncated
    const indxLength = new DataView(bytes.buffer, bytes.byteOffset).getUint32(INDX_AT, true);
    const indxEnd = INDX_AT + 12 + indxLength;
    if (decoder.bytesFed() < indxEnd && !(await pushRange(url, decoder, decoder.bytesFed(), indxEnd, opts))) return;
    if (!decoder.toc().length) decoder.finish();  // throws: the table is cut or damaged
  }
  const end = levelEnd(decoder, level);
  if (end > decoder.bytesFed()) await pushRange(url, decoder, decoder.bytesFed(), end, opts);
}

// Level L+1 now: the range from where the decoder stands to the end of the
// next level's chunk.  Returns false when every level is in.
export async function fetchNextLevel(url, decoder, opts = {}) {
  const next = decoder.levelsReady();
  if (decoder.levelCount() >= 0 && next >= decoder.levelCount()) return false;
  await fetchUpToLevel(url, decoder, next, opts);
  return true;
}
