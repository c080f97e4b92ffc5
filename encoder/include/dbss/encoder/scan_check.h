// The encoder's self-check: the finished encoding against the points it came
// from, so a broken surface is never written without saying so.  Each figure
// outside its bound becomes a warning naming the figure and its likely cause;
// `dbss encode` prints them, records them in the file's `meta` chunk and,
// under --strict, fails with nothing written.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dbss/encoder/point_index.h"

namespace dbss {

struct Encoding;

struct ScanWarning {
  std::string code;     // stable short name, e.g. "clamped" (used in `meta` and tests)
  std::string message;  // one line for people: the figure, the bound, the likely cause
};

struct ScanCheck {
  double spacing = 0;             // the points' median distance to their nearest point, model units
  uint32_t surface_components = 0;  // of the surface (every level has the same topology)
  uint32_t point_clusters = 0;      // of the points, linked at a few spacings
  bool open = false;                // the surface has a boundary
  uint32_t boundary_loops = 0;
  double clamped_share = 0;       // of clamped_level's displacements, 0..1
  uint32_t clamped_level = 0;     // the level clamped_share is of (see check_scan: coarser than the measured one on noise)
  double uncovered_share = 0;     // of the measured level's surface area, farther than a few spacings from any point, 0..1
  double points_to_surface = 0;   // mean, model units, to the measured level (of at most 2^18 points: see check_scan)
  // Pairs of rims where the points end (point_rims.h) that look like the
  // two ends of a tube the scan cut through, and that a closed surface caps
  // instead of joining: each may be a lost handle.
  uint32_t capped_rim_pairs = 0;
  // Handles of a closed surface whose tunnel has no point within
  // kBareHandleReach local spacings (bare_handles.h), the encoder's own tubes
  // excluded where it built them: a gap through a thin part taken for a hole.
  uint32_t bare_handles = 0;
  // The largest reach (in local spacings, of 2, 3, 4, 5, 6, 8, 12) at which
  // some handle, the encoder's own tubes aside, is still bare; 0 if none is
  // at 2: how far from the scan the least supported handle lies.
  float bare_handle_reach = 0;
  std::vector<std::array<float, 3>> bare_handle_at;  // a point on each bare handle's tunnel, model units
  // Handles the grid search's coarser carvings showed that the closed,
  // one-piece surface lacks (ControlMeshStages::coarser_genus less the
  // surface's genus, at least 0): a tube whose ends the chosen carving
  // capped where the scan missed a band round it.
  uint32_t lost_handles = 0;
  std::vector<ScanWarning> warnings;
};

// Checks `e` (its finest level, or the first with more vertices than there
// are points when the file goes past it: the levels after that one store
// only zeros; the control mesh with no levels) against the points `index`
// was built on (the points the encoder used).
// points_to_surface is the mean over every point up to 2^18 of them, over
// 2^18 evenly spaced in the input's order above that.  `threads` share
// the distances; the figures are the same on any number.
ScanCheck check_scan(const Encoding& e, const PointIndex& index, unsigned threads = 1);

}  // namespace dbss
