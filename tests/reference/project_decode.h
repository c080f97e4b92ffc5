// The project's whole decoding pipeline on a file, for comparison with the
// reference decoder: the error code name ("" when the file was read whole)
// and every level it verified.  The progressive decoder adds the control
// mesh's checks (bad_mesh, Draco's compression errors) that the container
// reader leaves to it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dbss/decoder/progressive.h"

namespace dbss::test {

struct ProjectDecode {
  std::string error;
  std::vector<TriangleMesh> levels;
};

inline ProjectDecode project_decode(std::span<const uint8_t> bytes) {
  ProjectDecode out;
  DecoderOptions options;
  options.threads = 1;
  ProgressiveDecoder d(options);
  Status s = d.feed(bytes);
  if (s.ok()) s = d.finish();
  if (!s.ok()) out.error = error_code_name(s.code());
  for (int l = 0; l <= d.ready_level(); ++l) {
    auto v = d.decode(static_cast<uint32_t>(l));
    if (!v.ok()) {
      if (out.error.empty()) out.error = error_code_name(v.status().code());
      break;
    }
    out.levels.push_back(v.value().copy());
  }
  return out;
}

}  // namespace dbss::test
