#include "dbss/decoder/progressive.h"

#include <new>
#include <string>
#include <thread>

#include "dbss/decoder/control_mesh.h"
#include "refinement_step.h"

namespace dbss {

struct ProgressiveDecoder::State {
  DecoderOptions options;
  format::Reader reader;
  Status status;  // decoder-side errors (the reader keeps its own)
  unsigned threads = 1;

  bool have_base = false;
  LevelTopology base_topology;
  std::vector<float> base_positions;

  // The current level (positions, triangles, and the topology of the level
  // below it), in buffers reused from level to level.
  bool have_current = false;
  detail::Refiner current;

  // keep_levels: every level decoded so far.
  std::vector<std::vector<float>> kept_positions;
  std::vector<std::vector<uint32_t>> kept_triangles;

  explicit State(const DecoderOptions& o) : options(o), reader(o.limits), current(o.kernels) {
    threads = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  }

  const Status& first_error() const { return !status.ok() ? status : reader.status(); }

  Status fail(ErrorCode code, std::string message) {
    status = Status(code, std::move(message));
    return status;
  }

  Status load_base() {
    const format::Header& h = reader.header();
    auto mesh = decode_control_mesh(reader.control_payload(), h.control_vertex_count, h.control_triangle_count);
    if (!mesh.ok()) return fail(mesh.status().code(), mesh.status().message());
    TriangleMesh& m = mesh.value();
    if (m.vertex_count() != h.control_vertex_count || m.triangle_count() != h.control_triangle_count)
      return fail(ErrorCode::bad_mesh, "control mesh has " + std::to_string(m.vertex_count()) + " vertices and " +
                                           std::to_string(m.triangle_count()) + " triangles; the header declares " +
                                           std::to_string(h.control_vertex_count) + " and " +
                                           std::to_string(h.control_triangle_count));
    auto topo = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
    if (!topo.ok()) return fail(topo.status().code(), "control mesh: " + topo.status().message());
    if (topo.value().edge_count() != h.control_edge_count)
      return fail(ErrorCode::bad_mesh, "control mesh has " + std::to_string(topo.value().edge_count()) +
                                           " edges; the header declares " + std::to_string(h.control_edge_count));
    base_topology = std::move(topo).value();
    base_positions = std::move(m.positions);
    have_base = true;
    return {};
  }

  // The crease tags arrive in CREA, after CTRL and before LEVL 1: level 0
  // can be drawn without them, level 1 cannot be computed without them.
  bool creases_applied = false;
  Status apply_creases() {
    const format::Creases& c = reader.creases();
    if (Status st = set_creases(base_topology, c.edge, c.corner); !st.ok())
      return fail(st.code(), "crease tags: " + st.message());
    creases_applied = true;
    have_current = false;  // the refiner's level-0 tables predate them
    return {};
  }
  void reset_to_base() {
    current.reset(base_topology, base_positions);
    have_current = true;
  }

  Status step() {
    const format::Level& data = reader.level(current.level() + 1);
    // The reader sized q from the header's counts, which the control mesh
    // matched, and bounded them by its limits; both checked again here
    // because the kernels index q without bounds and count in 32 bits.
    const detail::Refiner::Counts c = current.counts();
    if (!data.q.empty() && data.q.size() != c.edges)
      return fail(ErrorCode::bad_mesh, "level " + std::to_string(current.level() + 1) + " has " +
                                           std::to_string(data.q.size()) + " displacements for " +
                                           std::to_string(c.edges) + " odd vertices");
    if (c.vertices + c.edges >= kNoHalfEdge || 12 * c.faces >= kNoHalfEdge)
      return fail(ErrorCode::limit_exceeded, "level " + std::to_string(current.level() + 1) + " is too large");
    // Format 1.3: one boundary value per boundary edge (2E - 3F of this level).
    if (!data.boundary.empty() && data.boundary.q.size() != 2 * c.edges - 3 * c.faces)
      return fail(ErrorCode::bad_mesh, "level " + std::to_string(current.level() + 1) + " has " +
                                           std::to_string(data.boundary.q.size()) + " boundary values for " +
                                           std::to_string(2 * c.edges - 3 * c.faces) + " boundary edges");
    current.step(data.q, data.step, threads, data.boundary.q, data.boundary.step);
    return {};
  }

  MeshView view() const { return {current.level(), current.positions(), current.triangles()}; }
};

ProgressiveDecoder::ProgressiveDecoder(const DecoderOptions& options) : s_(std::make_unique<State>(options)) {}
ProgressiveDecoder::~ProgressiveDecoder() = default;
ProgressiveDecoder::ProgressiveDecoder(ProgressiveDecoder&&) noexcept = default;
ProgressiveDecoder& ProgressiveDecoder::operator=(ProgressiveDecoder&&) noexcept = default;

Status ProgressiveDecoder::feed(std::span<const uint8_t> bytes) {
  if (!s_->status.ok()) return s_->status;
  return s_->reader.feed(bytes);
}

void ProgressiveDecoder::reset() {
  State& s = *s_;
  s.current.recycle();
  s.reader = format::Reader(s.options.limits);
  s.status = {};
  s.have_base = false;
  s.creases_applied = false;
  s.base_topology = {};
  s.base_positions = {};
  s.have_current = false;
  s.kept_positions = {};
  s.kept_triangles = {};
}

Status ProgressiveDecoder::finish() {
  if (!s_->status.ok()) return s_->status;
  return s_->reader.finish();
}

const Status& ProgressiveDecoder::status() const noexcept { return s_->first_error(); }
const format::Reader& ProgressiveDecoder::reader() const noexcept { return s_->reader; }

int ProgressiveDecoder::ready_level() const noexcept {
  if (!s_->status.ok() || !s_->reader.has_control()) return -1;
  return static_cast<int>(s_->reader.levels_ready());
}

Result<MeshView> ProgressiveDecoder::decode(uint32_t level) {
  State& s = *s_;
  if (!s.status.ok()) return s.status;
  if (static_cast<int>(level) > ready_level())
    return Status(ErrorCode::bad_state, "level " + std::to_string(level) + " is not ready (finest ready level: " +
                                            std::to_string(ready_level()) + ")");
  try {
    if (!s.have_base) {
      if (Status st = s.load_base(); !st.ok()) return st;
    }
    if (s.options.keep_levels && level < s.kept_positions.size())
      return MeshView{level, s.kept_positions[level], s.kept_triangles[level]};
    if (level > 0 && s.reader.has_creases() && !s.creases_applied) {
      if (Status st = s.apply_creases(); !st.ok()) return st;
    }
    if (!s.have_current || level < s.current.level()) s.reset_to_base();
    while (s.current.level() < level) {
      if (Status st = s.step(); !st.ok()) return st;
      if (s.options.keep_levels) {
        if (s.kept_positions.empty()) {
          s.kept_positions.push_back(s.base_positions);
          s.kept_triangles.push_back(s.base_topology.triangles);
        }
        const MeshView v = s.view();
        s.kept_positions.emplace_back(v.positions.begin(), v.positions.end());
        s.kept_triangles.emplace_back(v.triangles.begin(), v.triangles.end());
      }
    }
    return s.view();
  } catch (const std::bad_alloc&) {
    return s.fail(ErrorCode::limit_exceeded, "out of memory decoding level " + std::to_string(level));
  }
}

Result<TriangleMesh> decode_bytes(std::span<const uint8_t> bytes, int level, const DecoderOptions& options) {
  ProgressiveDecoder d(options);
  if (Status st = d.feed(bytes); !st.ok()) return st;
  if (Status st = d.finish(); !st.ok()) return st;
  const uint32_t want = level < 0 ? static_cast<uint32_t>(d.ready_level()) : static_cast<uint32_t>(level);
  auto view = d.decode(want);
  if (!view.ok()) return view.status();
  return view.value().copy();
}

}  // namespace dbss
