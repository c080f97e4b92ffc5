// Internal: the progressive decoder's level-to-level refinement, on buffers
// that are never zeroed (every entry is written before it is read) and that
// hold only what the current level needs.
//
// At level L it holds the positions and triangles of level L and the full
// connectivity of level L-1 only: the connectivity of level L is built when
// level L+1 is asked for (from L-1's, by the regular split), and the finest
// level never needs its own.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "buffer.h"
#include "parallel.h"
#include "dbss/decoder/kernels.h"
#include "dbss/decoder/odd_chooser.h"
#include "odd_vertices.h"
#include "topology_ref.h"

namespace dbss::detail {

class Refiner {
 public:
  explicit Refiner(Kernels kernels = Kernels::best) : kernels_(select_kernels(kernels)) {}
  // Starts over at level 0.  `base` must outlive the Refiner's use.
  void reset(const LevelTopology& base, std::span<const float> base_positions);
  // Forgets everything but keeps the arrays' storage for the next stream
  // (reset must follow before any other call).
  void recycle();
  // Level L -> L+1 with the odd vertices' integers q (E_L of them, or none
  // for plain subdivision) and the level's step.  `threads` >= 1; the result
  // is the same for any value.
  // `bq` (format 1.3): one value per boundary edge of level L, moved across
  // the boundary by bq * bstep after the normal displacement; empty: none
  // (ignored when q is empty: plain subdivision moves nothing).
  void step(std::span<const int32_t> q, float step, unsigned threads, std::span<const int32_t> bq = {},
            float bstep = 0);
  // The same step with each q chosen by `choose` and written to q[0..E_L),
  // and, with `bchoose`, each boundary value chosen by it and written to
  // bq[0..B_L).
  void step_chosen(const OddChooser& choose, int32_t* q, float step, unsigned threads,
                   const BoundaryChooser* bchoose = nullptr, int32_t* bq = nullptr, float bstep = 0);

  uint32_t level() const noexcept { return level_; }
  // Counts of the current level (E is the number of odd vertices the next
  // step creates), in 64 bits so callers can check the next level fits.
  struct Counts {
    uint64_t vertices, edges, faces;
  };
  Counts counts() const noexcept;
  std::span<const float> positions() const noexcept { return {positions_.data(), position_floats_}; }
  std::span<const uint32_t> triangles() const noexcept { return triangles_.span(); }

 private:
  struct Topology {
    uint32_t vertex_count = 0, face_count = 0, edge_count = 0;
    Buffer<uint32_t> tri, twin, edge_of, edge_half, vertex_start, across;
    Buffer<uint16_t> valence;
    Buffer<uint8_t> boundary;
    Buffer<uint8_t> crease;  // per edge; used only when has_creases
    bool has_creases = false;
    TopologyRef ref() const;
    void release(BlockPool* pool = nullptr);  // storage to `pool`, or freed
    void swap(Topology& o) noexcept;
  };
  struct BoundaryStep {
    const int32_t* q = nullptr;
    const BoundaryChooser* choose = nullptr;
    int32_t* chosen = nullptr;
    float step = 0;
    bool active() const noexcept { return q || choose; }
  };
  void step_impl(const int32_t* q, const OddChooser* choose, int32_t* chosen, float step, unsigned threads,
                 const BoundaryStep& boundary);
  TopologyRef base_topology() const;
  // The connectivity of the current level (built from `parent_`), as a ref.
  TopologyRef current_topology(unsigned threads);

  // fn over [0, n) on up to `threads` threads, with helpers kept between
  // passes and levels.
  template <class F>
  void parallel(uint32_t n, unsigned threads, F&& fn) {
    if (!workers_) workers_ = std::make_unique<Workers>();
    workers_->run(n, threads, fn);
  }

  OddVertexKernels kernels_;  // chosen once, for every step
  std::unique_ptr<Workers> workers_;  // made on first use; a pointer keeps Refiner movable
  BlockPool pool_;  // the last stream's storage, after recycle()
  const LevelTopology* base_ = nullptr;
  Buffer<uint32_t> base_across_;
  uint32_t level_ = 0;
  Topology parent_, spare_;  // levels L-1 and (scratch for) L
  Buffer<float> positions_, next_positions_;  // one float longer than the level's positions
  size_t position_floats_ = 0;
  Buffer<uint32_t> triangles_;
};

}  // namespace dbss::detail
