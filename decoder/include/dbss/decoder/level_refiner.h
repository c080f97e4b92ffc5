// The decoder's level-to-level refinement as a library object, for the
// encoder's closed loop: each step runs the very kernels the progressive
// decoder runs, but lets the caller choose every odd vertex's integer from
// the undisplaced point and the unit normal the step computed.  So the
// encoder places each vertex exactly where a decoder will (one
// implementation of subdivision, never two).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "dbss/decoder/kernels.h"
#include "dbss/decoder/mesh.h"
#include "dbss/decoder/odd_chooser.h"
#include "dbss/format/container.h"
#include "dbss/format/status.h"

namespace dbss {

struct LevelRefinerOptions {
  Kernels kernels = Kernels::best;  // the same bits either way
};

class LevelRefiner {
 public:
  // Fails with bad_mesh as build_topology() does.
  static Result<LevelRefiner> create(const TriangleMesh& control, const LevelRefinerOptions& options = {});
  // With the control mesh's crease tags (empty: none); bad_mesh also as
  // set_creases() gives it.
  static Result<LevelRefiner> create(const TriangleMesh& control, const format::Creases& creases,
                                     const LevelRefinerOptions& options = {});
  ~LevelRefiner();
  LevelRefiner(LevelRefiner&&) noexcept;
  LevelRefiner& operator=(LevelRefiner&&) noexcept;

  // One level finer: every odd vertex's q from `choose` (written to `q`,
  // resized to the odd count), moved by q * step.  `threads` >= 1; the
  // result is the same for any value.
  void refine(const OddChooser& choose, float step, std::vector<int32_t>& q, unsigned threads = 1);
  // The same, then (format 1.3) each boundary odd vertex's in-surface value
  // from `bchoose` (written to `bq`, resized to the boundary edge count),
  // moved by that value * bstep across the boundary (decoding.md 7a).
  void refine(const OddChooser& choose, float step, std::vector<int32_t>& q, const BoundaryChooser& bchoose,
              float bstep, std::vector<int32_t>& bq, unsigned threads = 1);

  uint32_t level() const noexcept;
  // The current level; valid until the next refine().
  std::span<const float> positions() const noexcept;
  std::span<const uint32_t> triangles() const noexcept;
  // Odd vertices the next refine() creates (the current level's edges).
  uint64_t next_odd_count() const noexcept;

 private:
  struct State;
  explicit LevelRefiner(std::unique_ptr<State> s);
  std::unique_ptr<State> s_;
};

}  // namespace dbss
