// The C ABI the WebAssembly module exports: a thin layer over
// dbss::ProgressiveDecoder (the same sources as the native build), so the
// browser decodes with the one implementation and gets the same bits.
// JavaScript (web/src/core.mjs) owns the handles and copies nothing it can
// view: positions and indices are read straight out of the module's memory.
//
// Every function is noexcept in effect: the decoder returns errors as
// values, and the few std::bad_alloc paths abort the module, which the
// JavaScript side reports as an exception.
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "dbss/decoder/progressive.h"
#include "dbss/format/status.h"

namespace {

struct Handle {
  dbss::ProgressiveDecoder decoder;
  dbss::Status last;  // the status of the last call (feed, finish, decode)
  dbss::MeshView view;
  explicit Handle(const dbss::DecoderOptions& o) : decoder(o) {}
};

dbss::DecoderOptions options(int keep_levels) {
  dbss::DecoderOptions o;
  o.threads = 1;  // the module is built without pthreads; one thread, same bits
  o.keep_levels = keep_levels != 0;
  return o;
}

int code(const dbss::Status& s) { return static_cast<int>(s.code()); }

}  // namespace

extern "C" {

void* dbss_alloc(uint32_t n) { return std::malloc(n ? n : 1); }
void dbss_free(void* p) { std::free(p); }

Handle* dbss_new(int keep_levels) { return new Handle(options(keep_levels)); }
void dbss_delete(Handle* h) { delete h; }

int dbss_feed(Handle* h, const uint8_t* bytes, uint32_t n) {
  h->last = h->decoder.feed(std::span<const uint8_t>(bytes, n));
  return code(h->last);
}

int dbss_finish(Handle* h) {
  h->last = h->decoder.finish();
  return code(h->last);
}

// Finest level whose bytes are verified, -1 before the control mesh.
int dbss_ready_level(const Handle* h) { return h->decoder.ready_level(); }

// Levels the header declares (not counting level 0), -1 before the header.
int dbss_level_count(const Handle* h) {
  const auto& r = h->decoder.reader();
  return r.has_header() ? static_cast<int>(r.header().level_count) : -1;
}

double dbss_bytes_fed(const Handle* h) { return static_cast<double>(h->decoder.reader().offset()); }
int dbss_complete(const Handle* h) { return h->decoder.reader().complete() ? 1 : 0; }

// Makes `level` current; its arrays are then at dbss_positions/dbss_indices.
int dbss_decode(Handle* h, uint32_t level) {
  auto r = h->decoder.decode(level);
  if (!r.ok()) {
    h->view = {};
    h->last = r.status();
    return code(h->last);
  }
  h->view = r.value();
  h->last = {};
  return 0;
}

const float* dbss_positions(const Handle* h) { return h->view.positions.data(); }
uint32_t dbss_vertex_count(const Handle* h) { return static_cast<uint32_t>(h->view.vertex_count()); }
const uint32_t* dbss_indices(const Handle* h) { return h->view.triangles.data(); }
uint32_t dbss_triangle_count(const Handle* h) { return static_cast<uint32_t>(h->view.triangle_count()); }

// The decoder's sticky first error (ok = 0), and the last call's.
int dbss_status_code(const Handle* h) { return code(h->decoder.status()); }
int dbss_last_code(const Handle* h) { return code(h->last); }
// Byte offset of the last call's error, -1 when it names none.
double dbss_last_offset(const Handle* h) {
  const uint64_t o = h->last.offset();
  return o == dbss::Status::kNoOffset ? -1.0 : static_cast<double>(o);
}
const char* dbss_last_message(const Handle* h) { return h->last.message().c_str(); }
const char* dbss_error_name(int c) { return dbss::error_code_name(static_cast<dbss::ErrorCode>(c)); }

// The table of contents (empty until INDX is verified): chunk type as four
// ASCII bytes packed little-endian, offset of its length field, data length.
uint32_t dbss_toc_size(const Handle* h) { return static_cast<uint32_t>(h->decoder.reader().toc().size()); }
uint32_t dbss_toc_type(const Handle* h, uint32_t i) {
  const auto& c = h->decoder.reader().toc()[i].type.c;
  return static_cast<uint32_t>(static_cast<uint8_t>(c[0])) | static_cast<uint32_t>(static_cast<uint8_t>(c[1])) << 8 |
         static_cast<uint32_t>(static_cast<uint8_t>(c[2])) << 16 | static_cast<uint32_t>(static_cast<uint8_t>(c[3])) << 24;
}
double dbss_toc_offset(const Handle* h, uint32_t i) { return static_cast<double>(h->decoder.reader().toc()[i].offset); }
double dbss_toc_length(const Handle* h, uint32_t i) { return static_cast<double>(h->decoder.reader().toc()[i].length); }
double dbss_file_size(const Handle* h) { return static_cast<double>(h->decoder.reader().file_size()); }

}  // extern "C"
