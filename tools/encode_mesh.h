#pragma once

#include <string>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/encode.h"

namespace dbss::tools {

// `dbss encode` on a mesh (the default for a file with faces): encodes,
// writes `output` atomically and prints the report; returns the exit code.
// Without `report` (--no-report) the levels' distances to the input are
// not measured: at a million triangles that costs as much as the encoding.
int run_encode_mesh(const std::string& input, const std::string& output, const TriangleMesh& mesh,
                    EncodeOptions options, double read_seconds, bool report = true);

}  // namespace dbss::tools
