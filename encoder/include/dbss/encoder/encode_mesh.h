// The encoder for mesh input: the control mesh simplified from the input
// mesh, displacements cast against its triangles, then the same Draco
// control mesh, closed-loop levels and container as encode_points().
#pragma once

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

// Encodes `mesh` (any triangle mesh: it is prepared first).  Of `options`,
// outlier removal and the surface/grid/shaping choices of points do not
// apply; control.control_faces (0: default_control_faces of the input's
// triangles and genus), control_bits, levels (kAutoLevels: up to the first
// level with more vertices than the input), error/step, effort, threads and
// the names do.  Errors: invalid_argument for a mesh that is not an
// oriented manifold (naming the first offending edge or vertex) or bad
// options; internal for a stage that broke the topology (a bug).
Result<MeshEncoding> encode_mesh(const TriangleMesh& mesh, const EncodeOptions& options = {});

}  // namespace dbss
