// The dbss command.  Exit codes: 0 success, 1 bad input or usage (the
// message names the file and the problem), 2 internal error.
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "dbss/format/reader.h"
#include "decode.h"
#include "export.h"
#include "info.h"
#ifdef DBSS_HAVE_ENCODER
#include "compare.h"
#include "encode.h"
#endif

namespace {

constexpr const char* kUsage =
    "usage: dbss <command> [options]\n"
    "\n"
    "Displaced Butterfly Subdivision Surfaces codec. Reads format versions 1.0 to 1.3;\n"
    "writes the lowest version a file needs (1.2 for context-coded levels, 1.3 when a\n"
    "mesh's boundary vertices move across the boundary).\n"
    "\n"
    "commands:\n"
    "  encode INPUT -o OUT.dbss   reconstruct a point cloud or mesh and write it\n"
    "  decode IN.dbss -o OUT      one level as a .ply, .obj, .off, .stl, .glb or .gltf mesh\n"
    "  export IN.dbss -o OUT.glb  levels A..B as glTF levels of detail (MSFT_lod) in one file\n"
    "  info IN.dbss [--json|--hashes]  chunks, sizes, per-level counts, steps, checks; --hashes: per-level hashes\n"
    "  compare INPUT [--json]     sizes and errors per level: dbss vs full-vertex DSS vs Draco\n"
    "\n"
    "Run 'dbss <command> --help' for a command's options.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::fputs(kUsage, stderr);
    return 1;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args[0] == "--version") {
    std::printf("dbss %s (format %u.%u)\n", DBSS_VERSION, dbss::format::kVersionMajor, dbss::format::kVersionMinor);
    return 0;
  }
  const std::string_view cmd = args[0];
  args.erase(args.begin());
  try {
    if (cmd == "info") return dbss::tools::run_info(args);
    if (cmd == "decode") return dbss::tools::run_decode(args);
    if (cmd == "export") return dbss::tools::run_export(args);
#ifdef DBSS_HAVE_ENCODER
    if (cmd == "encode") return dbss::tools::run_encode(args);
    if (cmd == "compare") return dbss::tools::run_compare(args);
#else
    if (cmd == "encode" || cmd == "compare") {
      std::fprintf(stderr, "dbss %.*s: this dbss was built without the encoder (DBSS_BUILD_ENCODER=OFF)\n",
                   static_cast<int>(cmd.size()), cmd.data());
      return 1;
    }
#endif
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dbss %.*s: internal error: %s\n", static_cast<int>(cmd.size()), cmd.data(), e.what());
    return 2;
  }
  std::fprintf(stderr, "dbss: unknown command '%.*s'\n\n%s", static_cast<int>(cmd.size()), cmd.data(), kUsage);
  return 1;
}
