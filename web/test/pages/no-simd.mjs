// An engine without WebAssembly SIMD, as web/dbss.mjs's probe sees it:
// WebAssembly.validate refuses any module that holds the SIMD opcode
// prefix (0xfd; the probe does), as validation in such an engine would.
// Imported before the worker (no-simd-worker.mjs), so the worker's own
// loadModule() decides, unaided, which build to fetch.
const validate = WebAssembly.validate;
WebAssembly.validate = (bytes) => {
  const b = ArrayBuffer.isView(bytes) ? new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength) : new Uint8Array(bytes);
  return !b.includes(0xfd) && validate(bytes);
};
