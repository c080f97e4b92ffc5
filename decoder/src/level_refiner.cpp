// LevelRefiner: the refinement step as a public object, for the encoder's closed loop.
#include "dbss/decoder/level_refiner.h"

#include "dbss/decoder/topology.h"
#include "refinement_step.h"

namespace dbss {

struct LevelRefiner::State {
  explicit State(Kernels kernels) : refiner(kernels) {}
  LevelTopology base;
  std::vector<float> base_positions;
  detail::Refiner refiner;
};

LevelRefiner::LevelRefiner(std::unique_ptr<State> s) : s_(std::move(s)) {}
LevelRefiner::~LevelRefiner() = default;
LevelRefiner::LevelRefiner(LevelRefiner&&) noexcept = default;
LevelRefiner& LevelRefiner::operator=(LevelRefiner&&) noexcept = default;

Result<LevelRefiner> LevelRefiner::create(const TriangleMesh& control, const LevelRefinerOptions& options) {
  return create(control, format::Creases{}, options);
}

Result<LevelRefiner> LevelRefiner::create(const TriangleMesh& control, const format::Creases& creases,
                                          const LevelRefinerOptions& options) {
  auto topo = build_topology(static_cast<uint32_t>(control.vertex_count()), control.triangles);
  if (!topo.ok()) return topo.status();
  if (Status st = set_creases(topo.value(), creases.edge, creases.corner); !st.ok()) return st;
  auto s = std::make_unique<State>(options.kernels);
  s->base = std::move(topo).value();
  s->base_positions = control.positions;
  s->refiner.reset(s->base, s->base_positions);
  return LevelRefiner(std::move(s));
}

void LevelRefiner::refine(const OddChooser& choose, float step, std::vector<int32_t>& q, unsigned threads) {
  q.resize(static_cast<size_t>(s_->refiner.counts().edges));
  s_->refiner.step_chosen(choose, q.data(), step, threads < 1 ? 1 : threads);
}

void LevelRefiner::refine(const OddChooser& choose, float step, std::vector<int32_t>& q,
                          const BoundaryChooser& bchoose, float bstep, std::vector<int32_t>& bq, unsigned threads) {
  const auto c = s_->refiner.counts();
  q.resize(static_cast<size_t>(c.edges));
  bq.resize(static_cast<size_t>(2 * c.edges - 3 * c.faces));
  s_->refiner.step_chosen(choose, q.data(), step, threads < 1 ? 1 : threads, &bchoose, bq.data(), bstep);
}

uint32_t LevelRefiner::level() const noexcept { return s_->refiner.level(); }
std::span<const float> LevelRefiner::positions() const noexcept { return s_->refiner.positions(); }
std::span<const uint32_t> LevelRefiner::triangles() const noexcept { return s_->refiner.triangles(); }
uint64_t LevelRefiner::next_odd_count() const noexcept { return s_->refiner.counts().edges; }

}  // namespace dbss
