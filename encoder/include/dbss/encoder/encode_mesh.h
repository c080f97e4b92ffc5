// The encoder for mesh input: the control mesh simplified from the input
// mesh, displacements cast against its triangles, then the same Draco
// control mesh, closed-loop levels and container as encode_points().
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/format/status.h"

namespace dbss {

struct MeshEncoding {
  Encoding encoding;       // as encode_points() fills it; `points` holds the input's vertices,
                           // stages.simplified QEM's mesh and stages.control the projected one
  TriangleMesh input;      // the prepared input (prepare_mesh_input)
  MeshInfo input_info;     // its genus, components and boundary loops
  MeshCleanup cleanup;
  MeshControlStats control_stats;
};

// Levels up to the input mesh's vertex density add shape; a level past it
// only re-expresses the input's facets, and each of its vertices covers
// less of the surface.  So when an encoding has a level past the density,
// the levels up to it are quantized this many times finer than the levels
// past it.  The error target keeps its meaning: the levels past the
// density round to its step (2 x error x diagonal), the others finer.
// Measured with bench/lod_bench's equal-error search (bytes at exactly
// Draco's error): see bench/lod_bench.md, "Issue 18: finer steps up to the
// input's density".
inline constexpr double kMeshDenseStepRatio = 1.5;

// The control size choice for mesh input (mesh_control_choice.h): when the
// default control mesh's last level is floor-bound (its two-sided error
// against the input at least kMeshFloorRatio times the error target), a
// candidate with kMeshLargerControl times the faces is encoded too and kept
// when it reaches the default's last level's error in fewer bytes.
// Fitted on seven meshes with bench/lod_bench's equal-error search: see
// bench/lod_bench.md, "Issue 18, ninth session".
inline constexpr double kMeshFloorRatio = 0.65;
inline constexpr double kMeshLargerControl = 1.5;

// The control mesh's Draco grid for mesh input, in steps of the error
// target (control_bits_for_step of step x this: at 1, the step's own
// grid; 2 was measured and lost the cow's qp8), with its interior vertices rounded along the surface
// (MeshEncodeOptions::round_along_surface).  Measured with
// bench/lod_bench's equal-error search: bench/lod_bench.md, "Thirteenth
// session (issue 18)".
inline constexpr double kMeshControlGridSteps = 1;

struct MeshEncodeOptions {
  // kMeshDenseStepRatio; 1: one step for every level.
  double dense_step_ratio = kMeshDenseStepRatio;
  // The control mesh's Draco grid: each interior control vertex is placed
  // on the grid point nearest its tangent plane it can slide to
  // (round_along_surface, as the point path does); boundary vertices round
  // as Draco would (a slide would move the hole's rim).  false: Draco's
  // rounding for every vertex, as before.
  bool round_along_surface = true;
  // The grid's spacing in steps of the error target (control_bits_for_step
  // of step x this): kMeshControlGridSteps; 1 is the step's own rule.
  double control_grid_steps = kMeshControlGridSteps;
  // Format 1.3: boundary odd vertices also move across the boundary, within
  // the surface, onto the input's boundary curve (a BDRY chunk per level
  // that moves any).  false: normal displacements only (a 1.2 file).
  bool boundary_values = true;
  // With boundary_values: bit l set, level l may carry a BDRY chunk; a
  // level whose bit is clear keeps the boundary rule alone (no BDRY, its
  // boundary odd vertices cast as in a 1.2 file).  Bit 0 is unused.
  uint32_t boundary_levels = ~0u;
  // With boundary_values: a level writes BDRY only when its values remove
  // more error than its bytes would at the level's own exchange rate
  // (LevelEncodeOptions::boundary_when_pays, boundary_worth); false: BDRY
  // wherever a value is non-zero (the first 1.3 encoder).
  bool boundary_when_pays = true;
  // Rate-distortion optimised quantization (LevelEncodeOptions::rdo_lambda,
  // rdo_quantize.h) from level rdo_first_level on; 0: plain rounding.
  double rdo_lambda = 0;
  uint32_t rdo_first_level = 1;
  // The control size choice (EncodeOptions::choose_control and no
  // control.control_faces given): the floor ratio that triggers a
  // candidate (0: never) and the candidate's size over the default.
  double floor_ratio = kMeshFloorRatio;
  double larger_control = kMeshLargerControl;
};

// The control mesh size for a mesh input (`mesh` prepared, of genus
// `genus`): hole_budget(mesh, genus).faces, default_control_faces (the
// shape's budget) plus, per boundary loop, the faces its rim vertices
// need.  A loop keeps at least three control vertices on its rim, and QEM
// collapses an edge from the rim inwards onto its rim end, so on the
// shape's budget a mesh with many holes came out all rims:
// elephant-with-holes (4,463 triangles, 106 holes; budget 288) got 566
// triangles on 341 vertices, 336 of them on the holes (3.2 a hole), whose
// chords cut across every hole, and its levels floored at a level-to-input
// error of 1e-3 of the diagonal.  A floor of 14 faces a loop (the fourth
// session) lifted that; the budget per hole (hole_budget.h) gives each
// hole what its curve needs instead.  Closed meshes: default_control_faces.
uint32_t mesh_control_faces(const TriangleMesh& mesh, int64_t genus);

// The vertex counts of levels 0..levels of a control mesh of `vertices`,
// `edges` and `triangles` (a 1-to-4 split: every edge gains a vertex and
// becomes two edges, every triangle gains three edges).
std::vector<uint64_t> level_vertex_counts(uint64_t vertices, uint64_t edges, uint64_t triangles, uint32_t levels);

// The quantization step of a level of `level_vertices` vertices in an
// encoding whose finest level has `finest_vertices`, from an input of
// `input_vertices`: `step` (the error target's) past the input's density,
// and also for every level when no level goes past it; `step / ratio` for
// the levels up to the density otherwise.
inline float mesh_level_step(float step, uint64_t level_vertices, uint64_t finest_vertices, uint64_t input_vertices,
                             double ratio = kMeshDenseStepRatio) {
  const bool finer = finest_vertices > input_vertices && level_vertices <= input_vertices && ratio > 1;
  return finer ? static_cast<float>(step / ratio) : step;
}

// Encodes `mesh` (any triangle mesh: it is prepared first).  Of `options`,
// outlier removal and the surface/grid/shaping choices of points do not
// apply; control.control_faces (0: mesh_control_faces of the prepared input,
// or kMeshLargerControl times it when choose_control finds the last level
// floor-bound: MeshEncodeOptions::floor_ratio), control_bits, levels (kAutoLevels: up to the first
// level with more vertices than the input), error/step, effort, threads and
// the names do; levels up to the input's density are quantized finer
// (mesh_level_step, `mesh_options`).  Errors: invalid_argument for a mesh that is not an
// oriented manifold (naming the first offending edge or vertex) or bad
// options; internal for a stage that broke the topology (a bug).
Result<MeshEncoding> encode_mesh(const TriangleMesh& mesh, const EncodeOptions& options = {},
                                 const MeshEncodeOptions& mesh_options = {});

}  // namespace dbss
