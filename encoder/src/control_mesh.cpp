#include "dbss/encoder/control_mesh.h"

#include <chrono>
#include <string>

#include "dbss/encoder/mesh_ops.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/projection.h"
#include "dbss/encoder/shell_mesh.h"

namespace dbss {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Status check_stage(const TriangleMesh& m, const MeshInfo& want, const char* stage) {
  const MeshInfo got = mesh_info(m);
  if (!got.manifold || !got.closed || got.components != want.components || got.genus != want.genus)
    return Status(ErrorCode::internal, std::string(stage) + " changed the topology: " + std::to_string(got.components) +
                                           " components of genus " + std::to_string(got.genus) + " (manifold " +
                                           std::to_string(got.manifold) + ", closed " + std::to_string(got.closed) +
                                           "), expected " + std::to_string(want.components) + " of genus " +
                                           std::to_string(want.genus));
  return {};
}
}  // namespace

Result<ControlMeshStages> build_control_mesh(const PointCloud& points, const ControlMeshOptions& o) {
  return build_control_mesh(PointIndex(points), o);
}

Result<ControlMeshStages> build_control_mesh(const PointIndex& index, const ControlMeshOptions& o) {
  const PointCloud& points = index.points();
  ControlMeshStages s;
  auto stage = [&](const char* name) {
    if (o.on_stage) o.on_stage(name);
  };
  stage("choosing the grid");
  auto t = Clock::now();
  if (o.grid > 0) {
    s.seconds.grid = since(t);
    stage("carving cells");
    t = Clock::now();
    s.cells = carve(points, o.grid, &s.carving);
  } else {
    // The search carves its choice on the way: its time is the grid's.
    CarvingChoice chosen = choose_carving(points, index);
    s.cells = std::move(chosen.cells);
    s.carving = chosen.stats;
    s.seconds.grid = since(t);
    t = Clock::now();
  }
  s.seconds.carve = since(t);

  stage("triangulating");
  t = Clock::now();
  auto shell = triangulate_shell(s.cells);
  if (!shell.ok()) return shell.status();
  s.shell = std::move(shell).value();
  s.shell_info = mesh_info(s.shell);
  s.seconds.triangulate = since(t);

  stage("shrink-wrapping");
  t = Clock::now();
  s.wrapped = s.shell;
  s.wrap_stats = shrink_wrap(s.wrapped, index, o.shrink_wrap);
  s.seconds.shrink_wrap = since(t);
  if (Status st = check_stage(s.wrapped, s.shell_info, "shrink-wrapping"); !st.ok()) return st;

  stage("simplifying");
  t = Clock::now();
  const uint32_t target = o.control_faces ? o.control_faces
                                          : default_control_faces(static_cast<uint32_t>(s.shell.triangle_count()), s.shell_info.genus);
  auto simplified = simplify_mesh(s.wrapped, target, &s.simplify_stats);
  if (!simplified.ok()) return simplified.status();
  s.simplified = std::move(simplified).value();
  s.seconds.simplify = since(t);
  if (Status st = check_stage(s.simplified, s.shell_info, "simplification"); !st.ok()) return st;

  stage("projecting");
  t = Clock::now();
  s.control = s.simplified;
  // Smooth out any fold the collapses left, then project: the projection
  // refuses moves that fold, so the control mesh ends fold-free.
  s.untangled = untangle_folds(s.control);
  // Collapses can make distant sheets cross; projection below keeps the
  // mesh free of crossings only if it starts free of them.
  s.relaxed = relax_self_intersections(s.control);
  const std::vector<float> before = s.control.positions;
  // A vertex whose move was refused may go once its neighbours have moved.
  s.projection_skipped = project_to_points(s.control, index);
  for (int again = 0; again < 3 && s.projection_skipped > 0; ++again) s.projection_skipped = project_to_points(s.control, index);
  // Projection checks folds only locally; on thin parts a vertex can still
  // pass through the opposite side.
  s.projection_skipped += undo_self_intersections(s.control, before);
  s.seconds.project = since(t);
  return s;
}

}  // namespace dbss
