// FNV-1a 64 of decoded positions, the per-level hash of spec/decoding.md
// section 8: each binary32 position as its 4 bytes little-endian, in vertex
// order.  Computed here in JavaScript, not in the module, so comparing it
// with the native command checks the positions the JavaScript side sees.
//
// 64-bit arithmetic in four 16-bit limbs, every intermediate below 2^27,
// so the engine keeps it all in int32 (shifts and masks, no division):
// about 3x faster than the same limbs carried with Math.floor and %
// (Chromium 156, a level of 1.9 MB: 25 -> 8 ms), and BigInt would be some
// 50x slower still.

const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

export function fnv1a64(floats) {
  let bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  if (!LITTLE_ENDIAN) {
    const copy = new Uint8Array(bytes.length);
    const view = new DataView(copy.buffer);
    floats.forEach((f, i) => view.setFloat32(4 * i, f, true));
    bytes = copy;
  }
  // h = 0xcbf29ce484222325 as limbs h0 (low) .. h3 (high).
  let h0 = 0x2325, h1 = 0x8422, h2 = 0x9ce4, h3 = 0xcbf2;
  // prime = 0x100000001b3 = 2^40 + 0x1b3: h*p = h*0x1b3 + (h << 40).
  for (let i = 0; i < bytes.length; ++i) {
    h0 ^= bytes[i];
    // h << 40 adds h0 << 8 to limb 2 and h1 << 8 to limb 3 (h0 < 2^16, so h0 << 8 < 2^24).
    const a0 = h0 * 0x1b3, a1 = h1 * 0x1b3, a2 = h2 * 0x1b3 + (h0 << 8), a3 = h3 * 0x1b3 + (h1 << 8);
    h0 = a0 & 0xffff;
    const c1 = a1 + (a0 >>> 16);
    h1 = c1 & 0xffff;
    const c2 = a2 + (c1 >>> 16);
    h2 = c2 & 0xffff;
    h3 = (a3 + (c2 >>> 16)) & 0xffff;
  }
  const hex = (v) => v.toString(16).padStart(4, '0');
  return hex(h3) + hex(h2) + hex(h1) + hex(h0);
}
