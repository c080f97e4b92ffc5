// Refinement step (detail::Refiner): one level to the next on reused buffers, for both decoders.
#include "refinement_step.h"

#include <cstring>
#include <utility>

#include "boundary_shift.h"
#include "zero_displacement.h"
#include "odd_vertices.h"

namespace dbss::detail {

TopologyRef Refiner::Topology::ref() const {
  TopologyRef r;
  r.vertex_count = vertex_count, r.face_count = face_count, r.edge_count = edge_count;
  r.tri = tri.data(), r.twin = twin.data(), r.edge_of = edge_of.data(), r.edge_half = edge_half.data();
  r.vertex_start = vertex_start.data(), r.valence = valence.data(), r.boundary = boundary.data();
  r.across = across.data();
  r.crease = has_creases ? crease.data() : nullptr;
  return r;
}

void Refiner::Topology::release(BlockPool* pool) {
  for (Buffer<uint32_t>* b : {&tri, &twin, &edge_of, &edge_half, &vertex_start, &across}) b->release(pool);
  valence.release(pool);
  for (Buffer<uint8_t>* b : {&boundary, &crease}) b->release(pool);
  has_creases = false;
}

void Refiner::Topology::swap(Topology& o) noexcept {
  std::swap(vertex_count, o.vertex_count), std::swap(face_count, o.face_count), std::swap(edge_count, o.edge_count);
  tri.swap(o.tri), twin.swap(o.twin), edge_of.swap(o.edge_of), edge_half.swap(o.edge_half);
  vertex_start.swap(o.vertex_start), across.swap(o.across), valence.swap(o.valence), boundary.swap(o.boundary);
  crease.swap(o.crease), std::swap(has_creases, o.has_creases);
}

void Refiner::recycle() {
  pool_.clear();  // what the last stream did not reuse
  parent_.release(&pool_);
  spare_.release(&pool_);
  for (Buffer<float>* b : {&positions_, &next_positions_}) b->release(&pool_);
  triangles_.release(&pool_);
  base_across_.release(&pool_);
  position_floats_ = 0;
  base_ = nullptr;
  level_ = 0;
}

void Refiner::reset(const LevelTopology& base, std::span<const float> base_positions) {
  // Back to level 0 keeps nothing of the finer levels.
  parent_.release();
  spare_.release();
  positions_.release();
  next_positions_.release();
  triangles_.release();
  base_ = &base;
  level_ = 0;
  const TopologyRef b = ref_of(base);
  base_across_.resize_for_overwrite(3 * size_t{b.face_count}, &pool_);
  for (uint32_t x = 0; x < 3 * b.face_count; ++x) base_across_[x] = across_of(b, x);
  // One float of slack: the kernels load a point as four floats.
  positions_.resize_for_overwrite(base_positions.size() + 1, &pool_);
  std::memcpy(positions_.data(), base_positions.data(), base_positions.size_bytes());
  positions_[base_positions.size()] = 0;
  position_floats_ = base_positions.size();
  triangles_.resize_for_overwrite(base.triangles.size(), &pool_);
  std::memcpy(triangles_.data(), base.triangles.data(), base.triangles.size() * sizeof(uint32_t));
}

Refiner::Counts Refiner::counts() const noexcept {
  const TopologyRef p = level_ <= 1 ? ref_of(*base_) : parent_.ref();
  if (level_ == 0) return {p.vertex_count, p.edge_count, p.face_count};
  return {uint64_t{p.vertex_count} + p.edge_count, 2 * uint64_t{p.edge_count} + 3 * uint64_t{p.face_count},
          4 * uint64_t{p.face_count}};
}

TopologyRef Refiner::base_topology() const {
  TopologyRef t = ref_of(*base_);
  t.across = base_across_.data();
  return t;
}

TopologyRef Refiner::current_topology(unsigned threads) {
  if (level_ == 0) return base_topology();
  // Level L's triangles are already in triangles_: they move into the
  // topology instead of being split out of L-1 again.
  const TopologyRef p = level_ == 1 ? base_topology() : parent_.ref();
  Topology& c = spare_;
  c.vertex_count = p.vertex_count + p.edge_count;
  c.face_count = 4 * p.face_count;
  c.edge_count = 2 * p.edge_count + 3 * p.face_count;
  const size_t halves = 3 * size_t{c.face_count};
  c.tri.swap(triangles_);
  c.twin.resize_for_overwrite(halves, &pool_);
  c.edge_of.resize_for_overwrite(halves, &pool_);
  c.across.resize_for_overwrite(halves, &pool_);
  c.edge_half.resize_for_overwrite(c.edge_count, &pool_);
  c.vertex_start.resize_for_overwrite(c.vertex_count, &pool_);
  c.valence.resize_for_overwrite(c.vertex_count, &pool_);
  c.boundary.resize_for_overwrite(c.vertex_count, &pool_);
  c.has_creases = p.crease != nullptr;
  if (c.has_creases) c.crease.resize_for_overwrite(c.edge_count, &pool_);
  const TopologyOut out{nullptr,          c.twin.data(),    c.edge_of.data(),  c.edge_half.data(),
                        c.vertex_start.data(), c.valence.data(), c.boundary.data(), c.across.data(),
                        c.has_creases ? c.crease.data() : nullptr};
  parallel(p.face_count, threads, [&](uint32_t fb, uint32_t fe) {
    refine_faces(p, fb, fe, out);
    // Even vertices: the same share of the parent's vertices.
    const uint64_t n = p.vertex_count;
    refine_vertices(p, static_cast<uint32_t>(n * fb / p.face_count), static_cast<uint32_t>(n * fe / p.face_count),
                    out);
  });
  parent_.swap(c);  // parent_ becomes level L; spare_ holds L-1's buffers until the step frees them
  return parent_.ref();
}

void Refiner::step(std::span<const int32_t> q, float step, unsigned threads, std::span<const int32_t> bq,
                   float bstep) {
  BoundaryStep b;
  if (!bq.empty() && !q.empty()) b.q = bq.data(), b.step = bstep;  // values only on a displaced level
  step_impl(q.empty() ? nullptr : q.data(), nullptr, nullptr, step, threads, b);
}

void Refiner::step_chosen(const OddChooser& choose, int32_t* q, float step, unsigned threads,
                          const BoundaryChooser* bchoose, int32_t* bq, float bstep) {
  BoundaryStep b;
  if (bchoose) b.choose = bchoose, b.chosen = bq, b.step = bstep;
  step_impl(nullptr, &choose, q, step, threads, b);
}

void Refiner::step_impl(const int32_t* q, const OddChooser* choose, int32_t* chosen, float step, unsigned threads,
                        const BoundaryStep& boundary) {
  const TopologyRef t = current_topology(threads);
  const uint32_t evens = t.vertex_count, odds = t.edge_count;
  const size_t floats = 3 * (size_t{evens} + odds);
  next_positions_.resize_for_overwrite(floats + 1, &pool_);  // slack for the kernels' four-float loads
  next_positions_[floats] = 0;
  const float* p = positions_.data();
  float* out = next_positions_.data();
  float* out_odd = out + 3 * size_t{evens};
  // The next level's triangles need 12 entries per face, the stencil points
  // kept per half-edge 9 floats per face: until pass 3 writes the
  // triangles, their (fresh) array holds the points, which saves the
  // memory and the page faults of a separate scratch array.
  triangles_.resize_for_overwrite(12 * size_t{t.face_count}, &pool_);
  // A level whose integers are all 0 (and that moves nothing across the
  // boundary) is its stencil points, bit for bit, when they and the evens
  // are finite and no odd coordinate is -0 (zero_displacement.h): then it
  // needs no normals, and pass 1 writes straight into the output.
  const size_t boundary_edges = 2 * size_t{t.edge_count} - 3 * size_t{t.face_count};
  const bool zero_level = q && all_zero(q, odds) && (!boundary.q || all_zero(boundary.q, boundary_edges));
  // Pass 1: every odd vertex at its stencil point (normals need all of
  // them); straight into the output when nothing moves, else per half-edge.
  const auto stencil_pass = [&](float* per_half) {
    if (per_half) per_half[9 * size_t{t.face_count}] = 0;  // slack (inside the 12 per face)
    parallel(t.face_count, threads, [&](uint32_t fb, uint32_t fe) {
      kernels_.stencil_points(t, p, fb, fe, per_half ? nullptr : out_odd, per_half);
      // In 64 bits: where size_t has 32 (WebAssembly), evens * fe overflows it
      // from about 65,000 evens on (the web build copied too few evens).
      const size_t vb = static_cast<size_t>(uint64_t{evens} * fb / t.face_count);
      const size_t ve = static_cast<size_t>(uint64_t{evens} * fe / t.face_count);
      std::memcpy(out + 3 * vb, p + 3 * vb, sizeof(float) * 3 * (ve - vb));
    });
  };
  const auto half_points = [&] { return triangles_.reuse_as<float>(9 * size_t{t.face_count} + 1); };
  float* per_half = (q || choose) && !zero_level ? half_points() : nullptr;
  stencil_pass(per_half);
  if (zero_level && !(all_finite(p, 3 * size_t{evens}) && all_finite_no_negative_zero(out_odd, 3 * size_t{odds}))) {
    // Not provably the stencil points (never seen in a real file): the
    // whole computation.
    per_half = half_points();
    stencil_pass(per_half);
  }
  // Pass 2: normals from the undisplaced level, and the displacements;
  // with every point finite, the odd vertices whose q is 0 are copied.
  if (per_half) {
    const bool finite = q && all_finite(p, 3 * size_t{evens}) && all_finite(per_half, 9 * size_t{t.face_count});
    parallel(t.face_count, threads, [&](uint32_t fb, uint32_t fe) {
      if (choose) kernels_.displaced_points_chosen(t, p, per_half, *choose, chosen, step, fb, fe, out_odd);
      else kernels_.displaced_points(t, p, per_half, q, step, fb, fe, out_odd, finite);
    });
  }
  // Pass 2b (format 1.3, decoding.md section 7a): boundary odd vertices
  // across the boundary, one thread (boundary edges are few, and the k-th
  // value needs the count of boundary edges before it).
  if (per_half && boundary.active())
    shift_boundary(t, p, per_half, boundary.q, boundary.choose, boundary.chosen, boundary.step, out_odd);
  // Pass 3: the next level's triangles, over the stencil points.
  uint32_t* tri = triangles_.reuse_as<uint32_t>(12 * size_t{t.face_count});
  parallel(t.face_count, threads, [&](uint32_t fb, uint32_t fe) { refine_triangle_range(t, fb, fe, tri); });
  positions_.swap(next_positions_);
  position_floats_ = floats;
  ++level_;
  // Level L-1's positions and L-2's topology are not needed any more, and
  // too small to be reused for a finer level: free them now.
  next_positions_.release();
  spare_.release();
}

}  // namespace dbss::detail
