// Encoder I: points -> cells -> shell -> shrink-wrapped -> simplified ->
// control mesh.  Every stage's result is kept so it can be dumped and tested.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_input.h"
#include "dbss/encoder/shell_mesh.h"
#include "dbss/encoder/shrink_wrap.h"
#include "dbss/encoder/simplify.h"
#include "dbss/format/status.h"

namespace dbss {

// Whether the points enclose a volume.  closed: a closed surface, holes in
// the sampling bridged; open: a surface with a boundary where the points
// end (a scan seen from one side, a patch); automatic: decided from the
// data (see ControlMeshStages::surface_reason).
enum class SurfaceMode { automatic, closed, open };
const char* surface_mode_name(SurfaceMode m);

struct ControlMeshOptions {
  int grid = 0;                // cells along the longest side; 0 = choose_carving()
  // With a given grid: the cells moved by this share of a cell along each
  // axis, 0 <= grid_shift < 1 (the grid search's choice may be moved by half
  // a cell; meta's grid-shift= records it, so --grid N --grid-shift 0.5
  // carves what the search carved).  Ignored when grid is 0.
  double grid_shift = 0;
  SurfaceMode surface = SurfaceMode::automatic;
  uint32_t control_faces = 0;  // 0 = default_control_faces()
  ShrinkWrapOptions shrink_wrap;
  ShapeOptions shape;          // the shaping pass after QEM (enabled = false: QEM's mesh as it is)
  // Called with a stage's name as it starts (for progress display); may be empty.
  std::function<void(const char*)> on_stage;
};

struct StageTimes {
  // seconds; with an automatic grid the search carves the chosen grid, so
  // `grid` includes that carving and `carve` is about zero
  double grid = 0, carve = 0, triangulate = 0, shrink_wrap = 0, simplify = 0, shape = 0, project = 0;
};

struct ControlMeshStages {
  bool open = false;           // the surface keeps a boundary (SurfaceMode::open, or chosen so)
  std::string surface_reason;  // why closed or open, one line for people
  double bridged_area = 0;     // closed: share of the area bridged over holes (no points support it), 0..1
  size_t doubtful_caps = 0;    // closed: pairs of holes capped that might be a handle's two cut ends
  size_t bridged_tubes = 0;    // closed: pairs of holes joined by a tube (a handle no points support)
  std::vector<float> bridged_tube_triangles;  // those tubes' triangles, three corners (xyz) each, as built
  size_t cut_triangles = 0;
  size_t pinholes = 0;         // sheet: loops of a few cells closed as gaps in the sampling    // open: shell triangles removed (the far side of the sheet, and those with no points near)
  CarvingStats carving;
  // The genus three consecutive grids of the search coarser than the
  // chosen one all showed, where it is more than the chosen carving's
  // (CarvingChoice::coarser_euler): handles the coarse closing still
  // bridged and the chosen cells closed (check_scan's lost_handle).  0 when
  // none did, when the grid was given, or when the chosen carving is not
  // one piece (coarser cells merge nearby parts, which lowers the Euler
  // characteristic as a handle does).
  int64_t coarser_genus = 0;
  CellGrid cells;
  TriangleMesh shell;       // triangulated air faces
  TriangleMesh wrapped;     // after shrink-wrapping
  TriangleMesh simplified;  // after QEM
  TriangleMesh control;     // simplified, shaped (mesh_shape.h), vertices projected onto the points
  MeshInfo shell_info;
  ShrinkWrapStats wrap_stats;
  SimplifyStats simplify_stats;
  // The face count QEM was asked for (given or default_control_faces).  Later
  // stages (crease collapses, alignment) may change the count; `meta`
  // records this one, so --control-faces with it builds the same mesh.
  uint32_t target_faces = 0;
  ShapeStats shape_stats;  // flips and moves of the shaping pass, the shape before and after it
  size_t projection_skipped = 0;  // control vertices left off the points (a fold), plus moves undone (a crossing)
  size_t untangled = 0;           // folded edges the simplification left, smoothed out before projection
  size_t relaxed = 0;             // vertex moves that cleared crossings the simplification left
  StageTimes seconds;      // wall clock
  StageTimes cpu_seconds;  // CPU time of the process (all threads summed), what one core would take
};

// Runs every stage.  Fails with invalid_argument for unusable points and
// internal if a stage breaks the closed-manifold invariant (a bug).
Result<ControlMeshStages> build_control_mesh(const PointCloud& points, const ControlMeshOptions& options = {});
// The same with the caller's index over the points (built once for several
// stages of a pipeline).
Result<ControlMeshStages> build_control_mesh(const PointIndex& points, const ControlMeshOptions& options = {});

}  // namespace dbss
