// `dbss export`: a range of levels as levels of detail in one glTF asset.
#include "export.h"

#include <cstdio>
#include <string>

#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"
#include "dbss/io/file.h"
#include "dbss/io/gltf.h"
#include "args.h"
#include "open_dbss.h"
#include "progress.h"

namespace dbss::tools {

namespace {
constexpr const char* kHelp =
    "usage: dbss export IN.dbss -o OUT.{glb,gltf} [--levels A..B] [--draco BITS]\n"
    "\n"
    "Decodes levels A to B of a .dbss file and writes them as levels of detail\n"
    "of one glTF 2.0 asset: one mesh per level (float32 positions equal to\n"
    "`dbss decode`'s bit for bit; uint16 indices where they fit, else uint32),\n"
    "linked by the MSFT_lod extension with MSFT_screencoverage hints.  The\n"
    "scene shows the finest level, so viewers without MSFT_lod show it; the\n"
    "coarser levels are nodes named \"level A\" .. \"level B-1\".\n"
    "No normals, texture coordinates or materials are written.\n"
    "\n"
    "  -o, --output FILE   .glb (binary) or .gltf (text, buffer embedded), replaced atomically\n"
    "  --levels A..B       levels to export, 0 = control mesh; a single number L\n"
    "                      exports that level alone (default: 0 to the finest level)\n"
    "  --draco BITS        compress every level but the finest with Draco\n"
    "                      (KHR_draco_mesh_compression, BITS position bits, 4 to 30;\n"
    "                      11 to 14 is usual); the extension becomes required, so\n"
    "                      viewers without a Draco decoder refuse the file. The\n"
    "                      finest level stays plain, bit for bit.\n"
    "\n"
    "A damaged or truncated file keeps the levels verified before the damage:\n"
    "without --levels they are exported with a warning; with --levels, every\n"
    "level asked for must have been verified.\n"
    "Exit status: 0 written, 1 bad input, levels not available, or usage,\n"
    "2 internal error.\n";

int usage(const std::string& m) {
  std::fprintf(stderr, "dbss export: %s\n\n%s", m.c_str(), kHelp);
  return 1;
}

// "A..B" or "L".
bool parse_levels(std::string_view s, long& first, long& last) {
  const long hi = format::kMaxLevelsInPractice;
  const auto dots = s.find("..");
  if (dots == std::string_view::npos) {
    if (!parse_int(s, 0, hi, first)) return false;
    last = first;
    return true;
  }
  return parse_int(s.substr(0, dots), 0, hi, first) && parse_int(s.substr(dots + 2), 0, hi, last) && first <= last;
}
}  // namespace

int run_export(const std::vector<std::string_view>& args) {
  std::string input, output;
  long first = -1, last = -1, draco_bits = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "-o" || a == "--output") {
      if (i + 1 >= args.size()) return usage("-o needs a file name");
      output = args[++i];
    } else if (a == "--levels") {
      if (i + 1 >= args.size()) return usage("--levels needs A..B");
      if (!parse_levels(args[++i], first, last))
        return usage("--levels needs A..B with whole numbers 0 <= A <= B <= " + std::to_string(format::kMaxLevelsInPractice) +
                     ", or one level L");
    } else if (a == "--draco") {
      if (i + 1 >= args.size() || !parse_int(args[++i], 4, 30, draco_bits))
        return usage("--draco needs a whole number of position bits from 4 to 30");
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = a;
    } else {
      return usage("more than one input file");
    }
  }
  if (input.empty()) return usage("no input file");
  if (output.empty()) return usage("no output file (-o OUT.glb)");
  {
    const auto dot = output.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : output.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != "glb" && ext != "gltf") return usage("the output must be a .glb or .gltf file: " + output);
  }

  ProgressiveDecoder d;
  Status end;
  if (!open_dbss("export", input, d, end)) return 1;
  const int ready = d.ready_level();
  const int declared = d.reader().header().level_count;
  if (first < 0) {
    first = 0;
    last = ready;
  } else if (last > declared) {
    std::fprintf(stderr, "dbss export: %s: level %ld is not in the file (finest level: %d)\n", input.c_str(), last, declared);
    return 1;
  } else if (last > ready) {
    std::fprintf(stderr, "dbss export: %s: level %ld is not available: %s (finest verified level: %d)\n", input.c_str(),
                 last, end.to_string().c_str(), ready);
    return 1;
  }
  for (const Status& w : d.reader().warnings())
    std::fprintf(stderr, "dbss export: warning: %s: %s (ignored)\n", input.c_str(), w.to_string().c_str());
  if (!end.ok())
    std::fprintf(stderr, "dbss export: warning: %s: %s; levels 0..%d were verified before it and are usable\n",
                 input.c_str(), end.to_string().c_str(), ready);

  // Coarse to fine, so each level continues from the one before.
  Progress progress("dbss export");
  std::vector<TriangleMesh> meshes;
  for (long l = first; l <= last; ++l) {
    progress.show("decoding level " + std::to_string(l));
    auto mesh = d.decode(static_cast<uint32_t>(l));
    if (!mesh.ok()) {
      progress.done();
      std::fprintf(stderr, "dbss export: %s: %s\n", input.c_str(), mesh.status().to_string().c_str());
      return 1;
    }
    meshes.push_back(mesh.value().copy());
  }
  // Finest first, as MSFT_lod lists them.
  std::vector<GltfLod> lods;
  for (long l = last; l >= first; --l) lods.push_back({"level " + std::to_string(l), &meshes[static_cast<size_t>(l - first)]});
  progress.show("writing " + output);
  GltfOptions options;
  options.draco_bits = static_cast<int>(draco_bits);
  const Status written = write_gltf_lods(output, lods, options);
  progress.done();
  if (!written.ok()) {
    std::fprintf(stderr, "dbss export: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("%s: levels %ld..%ld (%zu to %zu triangles) -> %s\n", input.c_str(), first, last,
              meshes.front().triangle_count(), meshes.back().triangle_count(), output.c_str());
  return 0;
}

}  // namespace dbss::tools
