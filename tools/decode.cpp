#include "decode.h"

#include <cstdio>
#include <string>

#include "dbss/decoder/progressive.h"
#include "dbss/io/file.h"
#include "dbss/io/geometry_files.h"
#include "dbss/format/reader.h"
#include "args.h"
#include "open_dbss.h"
#include "progress.h"

namespace dbss::tools {

namespace {
constexpr const char* kHelp =
    "usage: dbss decode IN.dbss -o OUT.{ply,obj,off,stl,glb,gltf} [--level L]\n"
    "\n"
    "Decodes one level of a .dbss file to a mesh file.\n"
    "\n"
    "  -o, --output FILE   mesh to write (.ply binary, .obj, .off, .stl binary, .glb or\n"
    "                      .gltf), replaced atomically\n"
    "  --level L           level to decode, 0 = control mesh (default: the finest\n"
    "                      level in the file)\n"
    "\n"
    "A damaged or truncated file keeps the levels verified before the damage\n"
    "(spec/dbss-format.md section 11): the error is printed on stderr as a\n"
    "warning and, without --level, the finest verified level is written; with\n"
    "--level L, level L is written if it was verified, else nothing is.\n"
    "Exit status: 0 written (with or without a warning), 1 bad input, the\n"
    "requested level not available, or usage, 2 internal error.\n";

int usage(const std::string& m) {
  std::fprintf(stderr, "dbss decode: %s\n\n%s", m.c_str(), kHelp);
  return 1;
}
}  // namespace

int run_decode(const std::vector<std::string_view>& args) {
  std::string input, output;
  long level = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return usage("-o needs a file name");
      output = args[++i];
    } else if (a == "--level") {
      if (i + 1 >= args.size()) return usage("--level needs a number");
      if (!parse_int(args[++i], 0, format::kMaxLevelsInPractice, level)) return usage("--level needs a whole number from 0 to " + std::to_string(format::kMaxLevelsInPractice));
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = a;
    } else {
      return usage("more than one input file");
    }
  }
  if (input.empty()) return usage("no input file");
  if (output.empty()) return usage("no output file (-o OUT.ply)");

  // Levels verified before an error stay usable (spec section 11), so only a
  // file with no usable control mesh, or a request past what was verified,
  // fails here.
  ProgressiveDecoder d;
  Status end;
  if (!open_dbss("decode", input, d, end)) return 1;
  const int ready = d.ready_level();
  const int declared = d.reader().header().level_count;
  if (level > declared) {
    std::fprintf(stderr, "dbss decode: %s: level %ld is not in the file (finest complete level: %d)\n", input.c_str(),
                 level, ready);
    if (!end.ok()) std::fprintf(stderr, "dbss decode: %s: %s\n", input.c_str(), end.to_string().c_str());
    return 1;
  }
  if (level > ready) {
    std::fprintf(stderr, "dbss decode: %s: level %ld is not available: %s (finest verified level: %d)\n",
                 input.c_str(), level, end.to_string().c_str(), ready);
    return 1;
  }
  for (const Status& w : d.reader().warnings())
    std::fprintf(stderr, "dbss decode: warning: %s: %s (ignored)\n", input.c_str(), w.to_string().c_str());
  if (!end.ok())
    std::fprintf(stderr, "dbss decode: warning: %s: %s; levels 0..%d were verified before it and are usable\n",
                 input.c_str(), end.to_string().c_str(), ready);
  const uint32_t want = level < 0 ? static_cast<uint32_t>(ready) : static_cast<uint32_t>(level);
  Progress progress("dbss decode");
  auto mesh = d.decode(want);
  if (!mesh.ok()) {
    progress.done();
    std::fprintf(stderr, "dbss decode: %s: %s\n", input.c_str(), mesh.status().to_string().c_str());
    return 1;
  }
  progress.show("writing " + output);
  const Status written = write_mesh(output, mesh.value().copy());
  progress.done();  // before any message, so none shares the progress line
  if (!written.ok()) {
    std::fprintf(stderr, "dbss decode: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("%s: level %u, %zu vertices, %zu triangles -> %s\n", input.c_str(), want, mesh.value().vertex_count(),
              mesh.value().triangle_count(), output.c_str());
  return 0;
}

}  // namespace dbss::tools
