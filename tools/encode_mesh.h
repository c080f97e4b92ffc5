#pragma once

#include <string>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/encode.h"

namespace dbss::tools {

// `dbss encode` on a mesh (the default for a file with faces): encodes,
// writes `output` atomically and prints the report; returns the exit code.
int run_encode_mesh(const std::string& input, const std::string& output, const TriangleMesh& mesh,
                    EncodeOptions options, double read_seconds);

}  // namespace dbss::tools
