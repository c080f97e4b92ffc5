#include "encode_mesh.h"
#include "progress.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

#include "dbss/encoder/encode_mesh.h"
#include "dbss/io/file.h"
#include "dbss/measure/mesh_distance.h"

namespace dbss::tools {

namespace {
// Most triangles (level and input together) the report measures a level's
// distance to the input for.
constexpr size_t kMaxReportTriangles = 6'000'000;
}  // namespace

int run_encode_mesh(const std::string& input, const std::string& output, const TriangleMesh& mesh, EncodeOptions options,
                    double read_s, bool report) {
  Progress progress("dbss encode");
  options.source_name = std::filesystem::path(input).filename().string();
  options.encoder_version = DBSS_VERSION;
  options.on_progress = [&](const std::string& what) { progress.show(what); };
  auto encoded = encode_mesh(mesh, options);
  progress.done();
  if (!encoded.ok()) {
    // Bad input is named plainly; anything else carries its code.
    const Status& s = encoded.status();
    std::fprintf(stderr, "dbss encode: %s: %s\n", input.c_str(),
                 (s.code() == ErrorCode::invalid_argument ? s.message() : s.to_string()).c_str());
    return encoded.status().code() == ErrorCode::internal ? 2 : 1;
  }
  // Not const: the per-level table below takes the levels out of it.
  MeshEncoding& me = encoded.value();
  Encoding& e = me.encoding;
  if (Status s = io::write_file_atomic(output, e.bytes); !s.ok()) {
    std::fprintf(stderr, "dbss encode: %s\n", s.message().c_str());
    return 1;
  }
  const MeshInfo& in = me.input_info;
  std::printf("%s: mesh of %zu vertices, %zu triangles -> %s: %zu bytes\n", input.c_str(), me.input.vertex_count(),
              me.input.triangle_count(), output.c_str(), e.bytes.size());
  std::printf("input: %u component(s), genus %lld, %u boundary loop(s)", in.components, static_cast<long long>(in.genus),
              in.boundary_loops);
  if (me.cleanup.degenerate_triangles || me.cleanup.unused_vertices)
    std::printf("; %zu triangles with a repeated corner and %zu unused vertices dropped", me.cleanup.degenerate_triangles,
                me.cleanup.unused_vertices);
  std::printf("\n%-22s %9s  %s\n", "stage", "ms", "notes");
  std::printf("%-22s %9.1f  %s\n", "read mesh", read_s * 1e3, "");
  std::printf("%-22s %9.1f  %s\n", "check", e.seconds.outliers * 1e3, "oriented manifold");
  std::printf("%-22s %9.1f  %u -> %zu triangles, %zu boundary vertices on the input's boundary\n", "QEM control mesh",
              e.seconds.control * 1e3, me.control_stats.faces_before, e.control.triangle_count(),
              me.control_stats.boundary_vertices);
  if (!e.control_choice.empty())
    std::printf("%-22s %9.1f  %s\n", "control size choice", e.seconds.choice * 1e3, e.control_choice.c_str());
  std::printf("%-22s %9.1f  %zu bytes, %d-bit positions\n", "Draco", e.seconds.draco * 1e3, e.contents.control_mesh.size(),
              e.control_bits);
  std::printf("%-22s %9.1f  %u level(s)%s\n", "cast displacements", e.seconds.levels * 1e3, e.level_count,
              options.levels == kAutoLevels ? " (auto: up to the first level with more vertices than the input)" : "");
  std::printf("%-22s %9.1f  %zu bytes\n", "container", e.seconds.serialize * 1e3, e.bytes.size());
  // Per level: topology against the input's, and the two-sided mean
  // distance to the input surface relative to the diagonal.
  std::printf("\n%-5s %9s %10s %10s %10s %8s %11s %11s\n", "level", "vertices", "triangles", "prefix", "components",
              "genus", "boundaries", "to input");
  bool kept = true;
  MeshDistanceOptions mo;
  mo.samples = 100000;
  mo.threads = std::max(1u, options.threads);
  // The input's tree and samples once for every level (MeshDistanceTo),
  // made only when some level is measured.  Costs memory: the input's tree
  // stays while the finest level's is built (832k-triangle armadillo, 4
  // levels: peak 300 -> 352 MB; freeing it before the finest level did not
  // bring the peak back, 370 MB).
  std::optional<MeshDistanceTo> to_input;
  for (uint32_t l = 0; l <= e.level_count; ++l) {
    // The level is moved out of the encoding (the file is written), not
    // copied, and freed after its row; its counts are mesh_counts', as the
    // input's are, not mesh_info's (the decoder's topology, about 100 bytes
    // a triangle): a level is the decoder's refinement of a manifold, and
    // the copy beside every level plus that topology made the process's
    // peak (elephant-with-holes, 5 levels, --no-report: 1.7x the encoder's).
    const TriangleMesh m{std::move(e.levels.positions[l]), std::move(e.levels.triangles[l])};
    const MeshInfo info = mesh_counts(m);
    kept = kept && info.components == in.components && info.genus == in.genus && info.boundary_loops == in.boundary_loops;
    // The distance builds a tree of both meshes (about 100 bytes a
    // triangle): past a few million triangles the report would need more
    // memory than the encoding did, so it is left out there.
    const bool measured = report && m.triangle_count() + me.input.triangle_count() <= kMaxReportTriangles;
    if (measured && !to_input) to_input.emplace(me.input, mo);
    const double d = measured ? to_input->from(m).mean() / e.diagonal : 0.0;
    std::printf("%-5u %9zu %10zu %10llu %10u %8lld %11u ", l, m.vertex_count(), m.triangle_count(),
                static_cast<unsigned long long>(prefix_bytes(e, l)), info.components, static_cast<long long>(info.genus),
                info.boundary_loops);
    if (measured) std::printf("%11.3e\n", d);
    else std::printf("%11s\n", "-");
  }
  if (!report) std::printf("(distances to the input not measured: --no-report)\n");
  if (!kept) {
    std::fprintf(stderr, "dbss encode: %s: warning (topology): a level's topology differs from the input's\n", input.c_str());
  }
  return 0;
}

}  // namespace dbss::tools
