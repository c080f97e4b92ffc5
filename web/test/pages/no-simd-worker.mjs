// The decoding worker (web/worker.mjs) in an engine without WebAssembly SIMD.
import './no-simd.mjs';
import '../../worker.mjs';
